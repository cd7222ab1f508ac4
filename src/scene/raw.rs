//! The scene file as written, before validation: the keys of `design.md`, each with its span.
//!
//! Unknown keys are errors (`deny_unknown_fields`): a typo must not silently drop an effect.
//! Arrays of a fixed length (`[x, y, z]`, `[i, j]`, a quaternion) take exactly that many
//! elements ([`exact`]): `[1, 2, 3, 4]` as a position is an error, not three numbers and a
//! fourth dropped. Which keys each shape and joint type takes is decided in `keys.rs`, from
//! the keys present (`present`).

use serde::Deserialize;
use toml::Spanned;

pub type Vec3 = Spanned<[f64; 3]>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLesson {
    pub title: Spanned<String>,
    pub summary: Option<String>,
    pub scene: Spanned<RawScene>,
    /// `[body]` (one) or `[[body]]` (one or more).
    pub body: Option<Spanned<RawBodies>>,
    #[serde(default, rename = "obstacle")]
    pub obstacles: Vec<Spanned<RawObstacle>>,
    #[serde(default, rename = "page")]
    pub pages: Vec<Spanned<RawPage>>,
    #[serde(default, rename = "cloth")]
    pub cloths: Vec<Spanned<RawCloth>>,
    #[serde(default, rename = "joint")]
    pub joints: Vec<Spanned<RawJoint>>,
    #[serde(default, rename = "spring")]
    pub springs: Vec<Spanned<RawSpring>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub dt: Spanned<f64>,
    pub duration: Option<Spanned<f64>>,
    pub integrator: Spanned<String>,
    #[serde(default, deserialize_with = "exact::option")]
    pub gravity: Option<Vec3>,
    pub drag: Option<Spanned<RawDrag>>,
    pub contact: Option<Spanned<RawContact>>,
    /// projection | baumgarte | none (joints only).
    pub joint_correction: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDrag {
    pub linear: Option<Spanned<f64>>,
    pub angular: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawContact {
    pub response: Spanned<String>,
    pub restitution: Option<Spanned<f64>>,
    pub friction: Option<Spanned<f64>>,
    /// `impulse` only: propagate | simultaneous.
    pub impacts: Option<Spanned<String>>,
    /// `soft-step` only: contact frequency (Hz), damping ratio, sub-steps per step.
    pub hertz: Option<Spanned<f64>>,
    pub damping_ratio: Option<Spanned<f64>>,
    pub substeps: Option<Spanned<i64>>,
}

/// `[body]`, a table, or `[[body]]`, an array of tables.
#[derive(Debug)]
pub enum RawBodies {
    One(Box<RawBody>),
    Many(Vec<Spanned<RawBody>>),
}

impl<'de> Deserialize<'de> for RawBodies {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
        struct Either;
        impl<'de> serde::de::Visitor<'de> for Either {
            type Value = RawBodies;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table [body] or an array of tables [[body]]")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<RawBodies, A::Error> {
                RawBody::deserialize(MapAccessDeserializer::new(map))
                    .map(|b| RawBodies::One(Box::new(b)))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> Result<RawBodies, A::Error> {
                Vec::deserialize(SeqAccessDeserializer::new(seq)).map(RawBodies::Many)
            }
        }
        deserializer.deserialize_any(Either)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    /// `[[body]]` only: unique in the file (default body1, body2, …).
    pub name: Option<Spanned<String>>,
    pub shape: Spanned<String>,
    #[serde(default, deserialize_with = "exact::option")]
    pub size: Option<Vec3>,
    #[serde(default, deserialize_with = "exact::option_list")]
    pub points: Option<Spanned<Vec<[f64; 3]>>>,
    pub masses: Option<Spanned<Vec<f64>>>,
    pub file: Option<Spanned<String>>,
    /// sphere, capsule, cylinder: m.
    pub radius: Option<Spanned<f64>>,
    /// capsule, cylinder: m, along the body y axis (capsule: the cylindrical part).
    pub length: Option<Spanned<f64>>,
    /// The body never moves (infinite mass).
    pub fixed: Option<Spanned<bool>>,
    pub mass: Option<Spanned<f64>>,
    pub inertia: Option<Spanned<String>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub position: Option<Vec3>,
    pub orientation: Option<Spanned<RawOrientation>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub velocity: Option<Vec3>,
    #[serde(default, deserialize_with = "exact::option")]
    pub angular_velocity: Option<Vec3>,
    #[serde(default, deserialize_with = "exact::option")]
    pub angular_velocity_body: Option<Vec3>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOrientation {
    #[serde(default, deserialize_with = "exact::option")]
    pub axis: Option<Vec3>,
    pub degrees: Option<Spanned<f64>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub quaternion: Option<Spanned<[f64; 4]>>,
}

/// An `[[obstacle]]` table: its `type`, and its other keys as written. The keys are those the
/// obstacle kinds declare (`physics::collision::obstacle::written`), each read as what its kind
/// says it holds (a number, three numbers or an orientation table), so a kind with a new key
/// needs nothing here. A key no kind declares is an error at the key, worded as a derived
/// table's (`unknown field`, listing every key), and so is a missing `type`.
#[derive(Debug)]
pub struct RawObstacle {
    /// `type`.
    pub(super) kind: Spanned<String>,
    /// Every other key (`scene/obstacle.rs` checks that each kind's keys are documented).
    pub(super) keys: Vec<(&'static str, RawValue)>,
}

/// The value of an obstacle's key.
#[derive(Debug)]
pub enum RawValue {
    Number(Spanned<f64>),
    Vector(Vec3),
    Rotation(Spanned<RawOrientation>),
}

impl RawValue {
    pub fn span(&self) -> std::ops::Range<usize> {
        match self {
            RawValue::Number(v) => v.span(),
            RawValue::Vector(v) => v.span(),
            RawValue::Rotation(v) => v.span(),
        }
    }
}

impl RawObstacle {
    /// The value of `key`, if written.
    pub fn value(&self, key: &str) -> Option<&RawValue> {
        self.keys.iter().find(|(k, _)| *k == key).map(|(_, v)| v)
    }
}

mod obstacle_table {
    use super::{exact, RawObstacle, RawOrientation, RawValue, Vec3};
    use crate::physics::collision::obstacle::{written, Value};
    use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};
    use std::fmt;
    use std::sync::OnceLock;
    use toml::Spanned;

    /// `type`, then every kind's keys ([`written::all_keys`]).
    fn fields() -> &'static [&'static str] {
        static FIELDS: OnceLock<Vec<&'static str>> = OnceLock::new();
        FIELDS.get_or_init(|| {
            std::iter::once("type")
                .chain(written::all_keys().iter().map(|k| k.name))
                .collect()
        })
    }

    /// What an obstacle's key holds (a key no kind declares is not read this far).
    fn value_of(key: &str) -> Value {
        written::all_keys()
            .iter()
            .find(|k| k.name == key)
            .map_or(Value::Number, |k| k.value)
    }

    impl<'de> serde::Deserialize<'de> for RawObstacle {
        fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            d.deserialize_struct("RawObstacle", fields(), Table)
        }
    }

    struct Table;

    impl<'de> Visitor<'de> for Table {
        type Value = RawObstacle;

        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("struct RawObstacle")
        }

        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawObstacle, A::Error> {
            let mut kind = None;
            let mut keys: Vec<(&'static str, RawValue)> = Vec::new();
            while let Some(key) = map.next_key_seed(Key)? {
                if key == "type" {
                    if kind.is_some() {
                        return Err(de::Error::duplicate_field("type"));
                    }
                    kind = Some(map.next_value::<Spanned<String>>()?);
                    continue;
                }
                if keys.iter().any(|(k, _)| *k == key) {
                    return Err(de::Error::duplicate_field(key));
                }
                let value = match value_of(key) {
                    Value::Number => RawValue::Number(map.next_value()?),
                    Value::Vector => RawValue::Vector(map.next_value_seed(Three)?),
                    Value::Rotation => {
                        RawValue::Rotation(map.next_value::<Spanned<RawOrientation>>()?)
                    }
                };
                keys.push((key, value));
            }
            let kind = kind.ok_or_else(|| de::Error::missing_field("type"))?;
            Ok(RawObstacle { kind, keys })
        }
    }

    /// A key's name: one of [`fields`], or the derived tables' "unknown field" error.
    struct Key;

    impl<'de> DeserializeSeed<'de> for Key {
        type Value = &'static str;

        fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<&'static str, D::Error> {
            d.deserialize_identifier(self)
        }
    }

    impl<'de> Visitor<'de> for Key {
        type Value = &'static str;

        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("field identifier")
        }

        fn visit_str<E: de::Error>(self, v: &str) -> Result<&'static str, E> {
            let fields = fields();
            fields
                .iter()
                .find(|k| **k == v)
                .copied()
                .ok_or_else(|| E::unknown_field(v, fields))
        }
    }

    /// Exactly three numbers, with their span ([`exact::required`]).
    struct Three;

    impl<'de> DeserializeSeed<'de> for Three {
        type Value = Vec3;

        fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Vec3, D::Error> {
            exact::required::<D, f64, 3>(d)
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPage {
    pub at: Spanned<f64>,
    pub title: String,
    /// May quote live numbers, `{{QUANTITY}}` and `{{QUANTITY@T}}` (see `live.rs`).
    pub text: Spanned<String>,
    /// `{ quantity = "cube.y", at = 1.0 }`: the app asks the student for a guess.
    pub predict: Option<Spanned<RawPredict>>,
    /// `["energy", "momentum"]`: panels the app shows first (`page_panels.rs`).
    pub panels: Option<Vec<Spanned<String>>>,
    /// `{ start = 0.5, stop = 2.0 }`: the stopwatch runs on simulated time (`measure`).
    pub stopwatch: Option<Spanned<RawStopwatch>>,
    /// `{ quantity = "bob.x", level = 0.0 }`: what the period timer watches.
    pub period: Option<Spanned<RawPeriod>>,
    /// `{ from = "bob", to = "rod.b" }`: the ruler's ends.
    pub ruler: Option<Spanned<RawRuler>>,
    /// `{ axis = "cube.y", against = "vertical" }`: the protractor's two directions.
    pub protractor: Option<Spanned<RawProtractor>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStopwatch {
    pub start: Option<Spanned<f64>>,
    pub stop: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPeriod {
    pub quantity: Spanned<String>,
    pub level: Option<Spanned<f64>>,
}

/// Each end: a name (`from`: a body, or a joint's or spring's anchor `rod.a`), a point
/// (`from_point`: in the named body's frame, or without a name a fixed world point), or both.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRuler {
    pub from: Option<Spanned<String>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub from_point: Option<Vec3>,
    pub to: Option<Spanned<String>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub to_point: Option<Vec3>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProtractor {
    pub axis: Spanned<String>,
    pub against: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPredict {
    pub quantity: Spanned<String>,
    pub at: Spanned<f64>,
}

/// A `[[cloth]]` table: a mass–spring sheet.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCloth {
    pub name: Option<Spanned<String>>,
    #[serde(deserialize_with = "exact::required")]
    pub size: Spanned<[f64; 2]>,
    /// Integers, signed so that a negative count gets our message, not serde's.
    #[serde(deserialize_with = "exact::required")]
    pub count: Spanned<[i64; 2]>,
    #[serde(default, deserialize_with = "exact::option")]
    pub position: Option<Vec3>,
    pub mass: Spanned<f64>,
    pub stretch: Spanned<f64>,
    pub shear: Option<Spanned<f64>>,
    pub bend: Option<Spanned<f64>>,
    pub damping: Option<Spanned<f64>>,
    /// A keyword (corners, edges, none) or an array of [i, j]: read by hand for clear errors.
    pub pinned: Option<Spanned<toml::Value>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub velocity: Option<Vec3>,
    pub integrator: Option<Spanned<String>>,
    /// Particles held to bodies: `[{ particle = [i, j], body = "name" }, …]`.
    pub attach: Option<Vec<Spanned<RawAttach>>>,
}

/// One entry of a cloth's `attach`: one `particle`, or a whole `edge`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawAttach {
    /// Signed so that a negative index gets our message, not serde's.
    #[serde(default, deserialize_with = "exact::option")]
    pub particle: Option<Spanned<[i64; 2]>>,
    /// `-x`, `+x`, `-z`, `+z` (the particles with i = 0, i = nx − 1, j = 0, j = nz − 1) or
    /// `all` (the whole rim).
    pub edge: Option<Spanned<String>>,
    /// Required: optional here so that its absence is called the entry's, not the file's
    /// `[body]`'s.
    pub body: Option<Spanned<String>>,
}

/// A `[[joint]]` table: an ideal constraint between two bodies or a body and the world.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawJoint {
    pub name: Option<Spanned<String>>,
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub bodies: Spanned<Vec<Spanned<String>>>,
    #[serde(default, deserialize_with = "exact::option")]
    pub anchor: Option<Vec3>,
    #[serde(default, deserialize_with = "exact::option")]
    pub axis: Option<Vec3>,
    #[serde(default, deserialize_with = "exact::option_list")]
    pub anchors: Option<Spanned<Vec<[f64; 3]>>>,
    pub length: Option<Spanned<f64>>,
    /// hinge (degrees) or slider (m): `[lo, hi]`.
    pub limits: Option<Spanned<Vec<f64>>>,
    /// hinge or slider: `{ speed, max_torque }` or `{ speed, max_force }`.
    pub motor: Option<Spanned<RawMotor>>,
}

/// A joint's `motor = { speed, max_force }` (slider) or `{ speed, max_torque }` (hinge).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMotor {
    pub speed: Option<Spanned<f64>>,
    pub max_force: Option<Spanned<f64>>,
    pub max_torque: Option<Spanned<f64>>,
}

/// A `[[spring]]` table: a Hooke spring with damping.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSpring {
    pub name: Option<Spanned<String>>,
    pub bodies: Spanned<Vec<Spanned<String>>>,
    #[serde(deserialize_with = "exact::list")]
    pub anchors: Spanned<Vec<[f64; 3]>>,
    pub stiffness: Spanned<f64>,
    pub damping: Option<Spanned<f64>>,
    pub rest_length: Option<Spanned<f64>>,
}

/// The keys of a table that are present, with their spans: what `keys.rs` checks against the
/// keys its kind takes. (A key added to a struct is added here too.)
pub type Present = Vec<(&'static str, std::ops::Range<usize>)>;

/// `(key, span)` of each `Some` field named.
macro_rules! present {
    ($raw:expr, $($key:ident),*) => {{
        let mut out: Present = Vec::new();
        $(if let Some(v) = &$raw.$key { out.push((stringify!($key), v.span())); })*
        out
    }};
}

impl RawBody {
    /// The shape-dependent keys present (every shape takes the others).
    pub fn present(&self) -> Present {
        present!(self, size, points, masses, file, radius, length)
    }
}

impl RawJoint {
    /// The type-dependent keys present (every joint takes `name`, `type`, `bodies`).
    pub fn present(&self) -> Present {
        present!(self, anchor, axis, anchors, length, limits, motor)
    }
}

/// Arrays of exactly N elements: serde reads the first N of a longer array and stops.
mod exact {
    use serde::de::{Deserialize, Deserializer, Error};
    use toml::Spanned;

    fn array<'de, D: Deserializer<'de>, T, const N: usize>(
        list: Vec<T>,
    ) -> Result<[T; N], D::Error> {
        let n = list.len();
        list.try_into()
            .map_err(|_| D::Error::invalid_length(n, &format!("an array of length {N}").as_str()))
    }

    pub fn required<'de, D, T, const N: usize>(d: D) -> Result<Spanned<[T; N]>, D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        let list = Spanned::<Vec<T>>::deserialize(d)?;
        let span = list.span();
        Ok(Spanned::new(span, array::<D, T, N>(list.into_inner())?))
    }

    pub fn option<'de, D, T, const N: usize>(d: D) -> Result<Option<Spanned<[T; N]>>, D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        required(d).map(Some)
    }

    /// A list of points of N numbers each, with its span.
    pub type Points<T, const N: usize> = Spanned<Vec<[T; N]>>;

    pub fn list<'de, D, T, const N: usize>(d: D) -> Result<Points<T, N>, D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        let lists = Spanned::<Vec<Vec<T>>>::deserialize(d)?;
        let span = lists.span();
        let arrays = lists
            .into_inner()
            .into_iter()
            .map(array::<D, T, N>)
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Spanned::new(span, arrays))
    }

    pub fn option_list<'de, D, T, const N: usize>(d: D) -> Result<Option<Points<T, N>>, D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        list(d).map(Some)
    }
}
