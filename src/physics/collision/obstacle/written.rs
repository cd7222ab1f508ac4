//! How an obstacle kind is written in a scene file, in words that know no file format: its
//! `type` word and keys ([`Written`], [`Key`]), and the lookup a scene reader hands the kind
//! to build itself from ([`Keys`]).
//!
//! The reader (`scene`) checks what every kind shares before a kind is asked: the `type` word
//! is one of the kinds' ([`written`]), no key of another kind is present, every required key
//! is present. The kind then reads its values through [`Keys`]; each error is made by the
//! reader, which pins it where the key was written (file:line:column).

use super::Obstacle;
use nalgebra::{UnitQuaternion, Vector3};

/// What a key holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Value {
    /// A number.
    Number,
    /// Three numbers `[x, y, z]`.
    Vector,
    /// A rotation (the scene file's `orientation` table: axis and degrees, or a quaternion).
    Rotation,
}

/// A key of a kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    pub name: &'static str,
    pub value: Value,
    /// Missing, it is an error ("a sphere obstacle needs `radius`").
    pub required: bool,
}

impl Key {
    pub const fn number(name: &'static str) -> Key {
        Key {
            name,
            value: Value::Number,
            required: true,
        }
    }

    pub const fn vector(name: &'static str) -> Key {
        Key {
            name,
            value: Value::Vector,
            required: true,
        }
    }

    pub const fn rotation(name: &'static str) -> Key {
        Key {
            name,
            value: Value::Rotation,
            required: true,
        }
    }

    /// The same key, which may be left out.
    pub const fn optional(self) -> Key {
        Key {
            required: false,
            ..self
        }
    }
}

/// A kind's place in the scene file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Written {
    /// Its place in the list of types that messages give ("valid types: ground, sphere, box,
    /// plane"), from 0.
    pub listed: u8,
    /// Its keys beside `type`, in the order messages list them.
    pub keys: &'static [Key],
}

/// The values of one obstacle's keys, as a kind reads them. A required key is there (the
/// reader checked); an error names the key, and the reader says where it was written.
pub trait Keys {
    type Error;
    /// A finite number.
    fn finite(&self, key: &str) -> Result<f64, Self::Error>;
    /// A finite number > 0.
    fn positive(&self, key: &str) -> Result<f64, Self::Error>;
    /// Three finite numbers.
    fn vector(&self, key: &str) -> Result<Vector3<f64>, Self::Error>;
    /// A rotation, None when the key is left out.
    fn rotation(&self, key: &str) -> Result<Option<UnitQuaternion<f64>>, Self::Error>;
    /// The error `message` at `key`.
    fn wrong(&self, key: &str, message: String) -> Self::Error;
}

/// Every kind a scene file can name, in the order messages list them: its `type` word and how
/// it is written.
pub fn written() -> Vec<(&'static str, Written)> {
    let mut kinds = super::written_kinds();
    kinds.sort_by_key(|(_, w)| w.listed);
    kinds
}

/// Every key of every kind, once, in the kinds' order (a rotation last: the order the scene
/// reader lists them when a key is unknown).
pub fn all_keys() -> Vec<Key> {
    let mut keys: Vec<Key> = Vec::new();
    for (_, w) in written() {
        for key in w.keys {
            if !keys.iter().any(|k| k.name == key.name) {
                keys.push(*key);
            }
        }
    }
    keys.sort_by_key(|k| k.value == Value::Rotation);
    keys
}

/// The obstacle of type `word` built from `keys`; None for a word no kind is written with.
pub fn build<K: Keys>(word: &str, keys: &K) -> Option<Result<Obstacle, K::Error>> {
    super::build_kind(word, keys)
}
