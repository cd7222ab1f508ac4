//! The scene file as written, before validation: the keys of `design.md`, each with its span.
//!
//! Unknown keys are errors (`deny_unknown_fields`): a typo must not silently drop an effect.

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
    pub size: Option<Vec3>,
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
    pub position: Option<Vec3>,
    pub orientation: Option<Spanned<RawOrientation>>,
    pub velocity: Option<Vec3>,
    pub angular_velocity: Option<Vec3>,
    pub angular_velocity_body: Option<Vec3>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOrientation {
    pub axis: Option<Vec3>,
    pub degrees: Option<Spanned<f64>>,
    pub quaternion: Option<Spanned<[f64; 4]>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObstacle {
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub height: Option<Spanned<f64>>,
    pub center: Option<Vec3>,
    pub radius: Option<Spanned<f64>>,
    pub min: Option<Vec3>,
    pub max: Option<Vec3>,
    /// plane: a point of it and its outward normal.
    pub point: Option<Vec3>,
    pub normal: Option<Vec3>,
    /// box: turned about its centre.
    pub orientation: Option<Spanned<RawOrientation>>,
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
    pub size: Spanned<[f64; 2]>,
    /// Integers, signed so that a negative count gets our message, not serde's.
    pub count: Spanned<[i64; 2]>,
    pub position: Option<Vec3>,
    pub mass: Spanned<f64>,
    pub stretch: Spanned<f64>,
    pub shear: Option<Spanned<f64>>,
    pub bend: Option<Spanned<f64>>,
    pub damping: Option<Spanned<f64>>,
    /// A keyword (corners, edges, none) or an array of [i, j]: read by hand for clear errors.
    pub pinned: Option<Spanned<toml::Value>>,
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
    pub particle: Option<[i64; 2]>,
    /// `-x`, `+x`, `-z`, `+z` (the particles with i = 0, i = nx − 1, j = 0, j = nz − 1) or
    /// `all` (the whole rim).
    pub edge: Option<Spanned<String>>,
    pub body: Spanned<String>,
}

/// A `[[joint]]` table: an ideal constraint between two bodies or a body and the world.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawJoint {
    pub name: Option<Spanned<String>>,
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub bodies: Spanned<Vec<Spanned<String>>>,
    pub anchor: Option<Vec3>,
    pub axis: Option<Vec3>,
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
    pub anchors: Spanned<Vec<[f64; 3]>>,
    pub stiffness: Spanned<f64>,
    pub damping: Option<Spanned<f64>>,
    pub rest_length: Option<Spanned<f64>>,
}
