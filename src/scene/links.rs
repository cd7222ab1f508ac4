//! `[[joint]]` and `[[spring]]` tables and `[scene] joint_correction`, validated into
//! [`Links`]: each broken rule a one-line error at the key at fault.
//!
//! | rule | error |
//! |---|---|
//! | `type` a joint kind | unknown joint type `hing` (did you mean `hinge`?); valid types: ball, hinge, fixed, distance, slider |
//! | `bodies` one or two known names | joint `bodies` needs one body name (jointed to the world) or two, found 3 |
//! | | unknown body `bbo` in joint `bodies` (did you mean `bob`?); bodies: bob, arm |
//! | two different bodies | a joint's two bodies must differ, found `bob` twice |
//! | ball, hinge, fixed, slider: `anchor`; distance, spring: `anchors` (two points) | a hinge joint needs `anchor` |
//! | keys of other kinds refused (`keys::JOINTS`; `limits`, `motor`: hinge and slider only) | `axis` does not apply to a ball joint (it is a key of hinge, slider); valid keys of a ball joint: … |
//! | hinge, slider `axis` non-zero | hinge `axis` has zero length: give a non-zero axis |
//! | `limits` two finite numbers, lo ≤ 0 ≤ hi (hinge: hi − lo < 360°) | hinge `limits` must hold 0 (the t = 0 pose): lo ≤ 0 ≤ hi, found [10, 90] |
//! | `motor` has `speed` and its bound: `max_torque` (hinge), `max_force` (slider), > 0 | a slider's motor takes `max_force` (N), not `max_torque` |
//! | distance `length` > 0, or the anchors apart at t = 0 | distance joint anchors coincide at t = 0: give `length` > 0 or two different points |
//! | spring `stiffness` > 0, `damping`, `rest_length` ≥ 0 | stiffness must be > 0, found 0 |
//! | names unique | duplicate joint name `pivot`: joint names must be unique in the file |
//! | `joint_correction` | unknown joint_correction `projektion` (did you mean `projection`?); valid: projection, baumgarte, none |

use super::error::did_you_mean;
use super::raw::{RawJoint, RawMotor, RawScene, RawSpring};
use super::{LoadError, SceneBody, Validator};
use crate::physics::joints::{Correction, Joint, JointKind, Links, Motor, Spring, SpringLaw};
use crate::physics::State;
use nalgebra::Vector3;
use std::ops::Range;
use toml::Spanned;

/// A joint's or spring's name, or the default `{prefix}{n}`, unique among `taken`.
fn name_of(
    v: &Validator,
    raw: &Option<Spanned<String>>,
    taken: &[String],
    prefix: &str,
    what: &str,
    n: usize,
) -> Result<String, LoadError> {
    match raw {
        Some(name) => {
            let text = name.get_ref().clone();
            if text.trim().is_empty() {
                return Err(v.error(name.span(), format!("{what} `name` must not be empty")));
            }
            if taken.contains(&text) {
                return Err(v.error(
                    name.span(),
                    format!(
                        "duplicate {what} name `{text}`: {what} names must be unique in the file"
                    ),
                ));
            }
            Ok(text)
        }
        None => {
            let mut k = n + 1;
            while taken.contains(&format!("{prefix}{k}")) {
                k += 1;
            }
            Ok(format!("{prefix}{k}"))
        }
    }
}

impl Validator<'_> {
    /// `joint_correction`, every `[[joint]]` and every `[[spring]]`, against the bodies.
    pub(super) fn links(
        &self,
        scene: &Spanned<RawScene>,
        joints: &[Spanned<RawJoint>],
        springs: &[Spanned<RawSpring>],
        bodies: &[(SceneBody, Range<usize>)],
    ) -> Result<Links, LoadError> {
        let correction = match &scene.get_ref().joint_correction {
            None => Correction::default(),
            Some(c) => Correction::from_name(c.get_ref()).ok_or_else(|| {
                let hint = did_you_mean(c.get_ref(), Correction::ALL.map(Correction::name))
                    .map(|s| format!(" (did you mean `{s}`?)"))
                    .unwrap_or_default();
                self.error(
                    c.span(),
                    format!(
                        "unknown joint_correction `{}`{hint}; valid: projection, baumgarte, none",
                        c.get_ref()
                    ),
                )
            })?,
        };
        let states: Vec<State> = bodies.iter().map(|(b, _)| b.initial).collect();
        let mut links = Links {
            correction,
            ..Links::default()
        };
        let mut names = Vec::new();
        for (n, raw) in joints.iter().enumerate() {
            let j = raw.get_ref();
            let name = name_of(self, &j.name, &names, "joint", "joint", n)?;
            names.push(name.clone());
            links.joints.push(self.joint(raw, name, bodies, &states)?);
        }
        let mut names = Vec::new();
        for (n, raw) in springs.iter().enumerate() {
            let s = raw.get_ref();
            let name = name_of(self, &s.name, &names, "spring", "spring", n)?;
            names.push(name.clone());
            let (a, b) = self.pair(&s.bodies, bodies, "spring")?;
            let anchors = self.two_points(&s.anchors, "spring")?;
            let stiffness = self.positive(&s.stiffness, "stiffness")?;
            let damping = s
                .damping
                .as_ref()
                .map_or(Ok(0.0), |d| self.non_negative(d, "spring damping"))?;
            let rest = s
                .rest_length
                .as_ref()
                .map(|r| self.non_negative(r, "rest_length"))
                .transpose()?;
            let law = SpringLaw {
                stiffness,
                damping,
                rest_length: rest,
            };
            links
                .springs
                .push(Spring::new(name, a, b, anchors, law, &states));
        }
        Ok(links)
    }

    /// `bodies = ["a"]` or `["a", "b"]`: indices.
    fn pair(
        &self,
        raw: &Spanned<Vec<Spanned<String>>>,
        bodies: &[(SceneBody, Range<usize>)],
        what: &str,
    ) -> Result<(usize, Option<usize>), LoadError> {
        let list = raw.get_ref();
        if list.is_empty() || list.len() > 2 {
            return Err(self.error(
                raw.span(),
                format!(
                    "{what} `bodies` needs one body name ({what} to the world) or two, found {}",
                    list.len()
                ),
            ));
        }
        let index = |name: &Spanned<String>| {
            bodies
                .iter()
                .position(|(b, _)| &b.name == name.get_ref())
                .ok_or_else(|| {
                    let all: Vec<&str> = bodies.iter().map(|(b, _)| b.name.as_str()).collect();
                    let hint = did_you_mean(name.get_ref(), all.iter().copied())
                        .map(|s| format!(" (did you mean `{s}`?)"))
                        .unwrap_or_default();
                    self.error(
                        name.span(),
                        format!(
                            "unknown body `{}` in {what} `bodies`{hint}; bodies: {}",
                            name.get_ref(),
                            if all.is_empty() {
                                "none".to_string()
                            } else {
                                all.join(", ")
                            }
                        ),
                    )
                })
        };
        let a = index(&list[0])?;
        let b = list.get(1).map(index).transpose()?;
        if b == Some(a) {
            return Err(self.error(
                list[1].span(),
                format!(
                    "a {what}'s two bodies must differ, found `{}` twice",
                    list[0].get_ref()
                ),
            ));
        }
        Ok((a, b))
    }

    /// `anchors = [[x, y, z], [x, y, z]]`.
    fn two_points(
        &self,
        raw: &Spanned<Vec<[f64; 3]>>,
        what: &str,
    ) -> Result<[Vector3<f64>; 2], LoadError> {
        let list = raw.get_ref();
        if list.len() != 2 || !list.iter().flatten().all(|c| c.is_finite()) {
            return Err(self.error(
                raw.span(),
                format!(
                    "{what} `anchors` needs two points [[x, y, z], [x, y, z]] with finite \
                     components, found {list:?}"
                ),
            ));
        }
        Ok([Vector3::from(list[0]), Vector3::from(list[1])])
    }

    fn joint(
        &self,
        raw: &Spanned<RawJoint>,
        name: String,
        bodies: &[(SceneBody, Range<usize>)],
        states: &[State],
    ) -> Result<Joint, LoadError> {
        let j = raw.get_ref();
        // The type word first, then the keys it takes (one table: `keys::JOINTS`).
        let family = &super::keys::JOINTS;
        let keys = family
            .kind(j.kind.get_ref())
            .map_err(|message| self.error(j.kind.span(), message))?;
        if let Some((at, message)) = family.misplaced(keys, &j.present()) {
            return Err(self.error(at, message));
        }
        let Some(kind) = JointKind::from_name(keys.name) else {
            return Err(self.error(j.kind.span(), "a joint type without a model"));
        };
        let kind_name = kind.name();
        let (a, b) = self.pair(&j.bodies, bodies, "joint")?;
        let needs =
            |key: &str| self.error(raw.span(), format!("a {kind_name} joint needs `{key}`"));
        if kind == JointKind::Distance {
            let anchors_raw = j.anchors.as_ref().ok_or_else(|| needs("anchors"))?;
            let anchors = self.two_points(anchors_raw, "distance joint")?;
            let length = j
                .length
                .as_ref()
                .map(|l| self.positive(l, "distance joint `length`"))
                .transpose()?;
            if length.is_none() && (anchors[0] - anchors[1]).norm() < 1e-12 {
                return Err(self.error(
                    anchors_raw.span(),
                    "distance joint anchors coincide at t = 0: give `length` > 0 or two \
                     different points",
                ));
            }
            return Ok(Joint::distance(name, a, b, anchors, length, states));
        }
        let anchor = self.vector(j.anchor.as_ref().ok_or_else(|| needs("anchor"))?, "anchor")?;
        let axis = match (kind, &j.axis) {
            (JointKind::Hinge | JointKind::Slider, None) => return Err(needs("axis")),
            (JointKind::Hinge | JointKind::Slider, Some(axis)) => {
                let v = self.vector(axis, &format!("{kind_name} axis"))?;
                if v.norm() < 1e-12 {
                    return Err(self.error(
                        axis.span(),
                        format!("{kind_name} `axis` has zero length: give a non-zero axis"),
                    ));
                }
                v
            }
            _ => Vector3::z(),
        };
        let mut joint = Joint::at_point(name, kind, a, b, anchor, axis, states);
        if let Some(limits) = &j.limits {
            joint.limits = Some(self.joint_limits(limits, kind)?);
        }
        if let Some(motor) = &j.motor {
            joint.motor = Some(self.joint_motor(motor, kind)?);
        }
        Ok(joint)
    }

    /// A hinge's or slider's `limits = [lo, hi]`: finite, lo ≤ 0 ≤ hi (the t = 0 pose is
    /// inside); a hinge's in degrees, less than a full turn apart, returned in radians.
    fn joint_limits(
        &self,
        raw: &Spanned<Vec<f64>>,
        kind: JointKind,
    ) -> Result<[f64; 2], LoadError> {
        let list = raw.get_ref();
        let kind_name = kind.name();
        let unit = if kind == JointKind::Hinge {
            "degrees"
        } else {
            "m"
        };
        let &[lo, hi] = list.as_slice() else {
            return Err(self.error(
                raw.span(),
                format!(
                    "{kind_name} `limits` needs two numbers [lo, hi] ({unit}), found {} number{}",
                    list.len(),
                    if list.len() == 1 { "" } else { "s" }
                ),
            ));
        };
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(self.error(
                raw.span(),
                format!("{kind_name} `limits` must be finite numbers, found [{lo}, {hi}]"),
            ));
        }
        if !(lo <= 0.0 && 0.0 <= hi) {
            return Err(self.error(
                raw.span(),
                format!(
                    "{kind_name} `limits` must hold 0 (the t = 0 pose): lo ≤ 0 ≤ hi, found \
                     [{lo}, {hi}]"
                ),
            ));
        }
        if kind == JointKind::Hinge {
            if hi - lo >= 360.0 {
                return Err(self.error(
                    raw.span(),
                    format!(
                        "hinge `limits` must be less than a full turn apart (hi − lo < 360°), \
                         found [{lo}, {hi}]"
                    ),
                ));
            }
            return Ok([lo.to_radians(), hi.to_radians()]);
        }
        Ok([lo, hi])
    }

    /// A hinge's `motor = { speed, max_torque }` (rad/s, N·m) or a slider's
    /// `{ speed, max_force }` (m/s, N).
    fn joint_motor(&self, raw: &Spanned<RawMotor>, kind: JointKind) -> Result<Motor, LoadError> {
        let m = raw.get_ref();
        let (key, other, unit) = if kind == JointKind::Hinge {
            ("max_torque", &m.max_force, "N·m")
        } else {
            ("max_force", &m.max_torque, "N")
        };
        if let Some(other) = other {
            let wrong = if kind == JointKind::Hinge {
                "max_force"
            } else {
                "max_torque"
            };
            return Err(self.error(
                other.span(),
                format!(
                    "a {}'s motor takes `{key}` ({unit}), not `{wrong}`",
                    kind.name()
                ),
            ));
        }
        let needs = |what: &str| {
            self.error(
                raw.span(),
                format!("a {} joint's `motor` needs `{what}`", kind.name()),
            )
        };
        let speed = m.speed.as_ref().ok_or_else(|| needs("speed"))?;
        let speed = self.finite(speed, "motor `speed`")?;
        let bound = if kind == JointKind::Hinge {
            &m.max_torque
        } else {
            &m.max_force
        };
        let bound = bound.as_ref().ok_or_else(|| needs(key))?;
        let max = self.positive(bound, &format!("motor `{key}`"))?;
        Ok(Motor { speed, max })
    }
}
