//! How a joint kind is written in a scene file, in words that know no file format: its `type`
//! word and keys ([`Written`]), what its coordinate measures ([`Measure`]), and the lookup a
//! scene reader hands the kind to build itself from ([`Keys`]).
//!
//! The reader (`scene::links`) checks what every kind shares before a kind is asked: the
//! `type` word is one of the kinds' (`JointKind::WRITTEN`), no key of another kind is present,
//! the `bodies`. The kind then reads its own keys through [`Keys`], in its order (a missing key
//! is an error when it is read); each error is made by the reader, which pins it where the key
//! was written (file:line:column). `limits` and `motor` are read by the reader after the kind,
//! in the units of its [`Measure`].

use super::{Joint, JointKind};
use crate::physics::State;
use nalgebra::Vector3;

/// A kind's place in the scene file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Written {
    /// Its `type` word.
    pub name: &'static str,
    /// Its keys beside `name`, `type` and `bodies`, in the order messages list them (`limits`
    /// and `motor` only on a kind with a [`Measure`]).
    pub keys: &'static [&'static str],
}

/// What a joint's coordinate measures: the quantity its limits and motor act on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// An angle, rad: limits written in degrees (less than a full turn apart), the motor's
    /// speed in rad/s and its bound a torque `max_torque`, N·m.
    Angle,
    /// A travel, m: limits in m, the motor's speed in m/s and its bound a force `max_force`, N.
    Travel,
}

/// The values of one joint's keys, as a kind reads them. A key left out that the kind reads is
/// an error ("a hinge joint needs `axis`"); each error names the key, and the reader says where
/// it was written.
pub trait Keys {
    type Error;
    /// A point `[x, y, z]`, finite components.
    fn point(&self, key: &str) -> Result<Vector3<f64>, Self::Error>;
    /// A direction `[x, y, z]`: finite components, not all zero.
    fn direction(&self, key: &str) -> Result<Vector3<f64>, Self::Error>;
    /// Two points `[[x, y, z], [x, y, z]]`, finite components.
    fn two_points(&self, key: &str) -> Result<[Vector3<f64>; 2], Self::Error>;
    /// A number > 0; None when the key is left out.
    fn optional_positive(&self, key: &str) -> Result<Option<f64>, Self::Error>;
    /// The error `message` at `key`.
    fn wrong(&self, key: &str, message: &str) -> Self::Error;
}

/// What every joint is built between: its name, its first body, its second (None: the world)
/// and the bodies' states at t = 0.
#[derive(Debug, Clone)]
pub struct Between<'a> {
    pub name: String,
    pub a: usize,
    pub b: Option<usize>,
    pub states: &'a [State],
}

impl Between<'_> {
    /// A joint of `kind` at world point `anchor` with its `axis` (`Joint::at_point`).
    pub fn at_point(self, kind: JointKind, anchor: Vector3<f64>, axis: Vector3<f64>) -> Joint {
        Joint::at_point(self.name, kind, self.a, self.b, anchor, axis, self.states)
    }
}
