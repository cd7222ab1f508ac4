//! `[[joint]]` and `[[spring]]` tables and `[scene] joint_correction`, validated into
//! [`Links`]: each broken rule a one-line error at the key at fault.
//!
//! A `[[joint]]` is read without knowing any kind (as `obstacle.rs` reads an `[[obstacle]]`):
//! the `type` word and the keys each kind takes come from the kinds' files
//! (`JointKind::WRITTEN`), the kind reads its own keys through [`JointKeys`] (the
//! format-neutral `physics::joints::written::Keys`), and `limits` and `motor` are read here in
//! the units of the kind's `Measure` (an angle: degrees, `max_torque`; a travel: m, `max_force`).
//!
//! | rule | error |
//! |---|---|
//! | `type` a joint kind | unknown joint type `hing` (did you mean `hinge`?); valid types: ball, hinge, fixed, distance, slider |
//! | `bodies` one or two known names | joint `bodies` needs one body name (jointed to the world) or two, found 3 |
//! | | unknown body `bbo` in joint `bodies` (did you mean `bob`?); bodies: bob, arm |
//! | two different bodies | a joint's two bodies must differ, found `bob` twice |
//! | ball, hinge, fixed, slider: `anchor`; distance, spring: `anchors` (two points) | a hinge joint needs `anchor` |
//! | keys of other kinds refused (`keys::JOINTS`, from each kind's file; `limits`, `motor`: the kinds with a coordinate, hinge and slider) | `axis` does not apply to a ball joint (it is a key of hinge, slider); valid keys of a ball joint: … |
//! | hinge, slider `axis` non-zero | hinge `axis` has zero length: give a non-zero axis |
//! | `limits` two finite numbers, lo ≤ 0 ≤ hi (hinge: hi − lo < 360°) | hinge `limits` must hold 0 (the t = 0 pose): lo ≤ 0 ≤ hi, found [10, 90] |
//! | `motor` has `speed` and its bound: `max_torque` (an angle: hinge), `max_force` (a travel: slider), > 0 | a slider's motor takes `max_force` (N), not `max_torque` |
//! | distance `length` > 0, or the anchors apart at t = 0 | distance joint anchors coincide at t = 0: give `length` > 0 or two different points |
//! | spring `stiffness` > 0, `damping`, `rest_length` ≥ 0 | stiffness must be > 0, found 0 |
//! | names unique | duplicate joint name `pivot`: joint names must be unique in the file |
//! | `joint_correction` | unknown joint_correction `projektion` (did you mean `projection`?); valid: projection, baumgarte, none |

use super::error::did_you_mean;
use super::raw::{RawJoint, RawMotor, RawScene, RawSpring, Vec3};
use super::{LoadError, SceneBody, Validator};
use crate::physics::joints::written::{Between, Keys, Measure};
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
        let (a, b) = self.pair(&j.bodies, bodies, "joint")?;
        let on = Between { name, a, b, states };
        let mut joint = kind.build(&JointKeys { v: self, raw, kind }, on)?;
        let measure = kind.measure();
        if let Some(limits) = &j.limits {
            joint.limits = Some(self.joint_limits(limits, kind.name(), measure)?);
        }
        if let Some(motor) = &j.motor {
            joint.motor = Some(self.joint_motor(motor, kind.name(), measure)?);
        }
        Ok(joint)
    }

    /// A coordinate without a [`Measure`] (a kind that lists `limits` or `motor` without one:
    /// the kinds' test refuses it).
    fn unmeasured(&self, span: Range<usize>, key: &str, kind_name: &str) -> LoadError {
        self.error(
            span,
            format!("`{key}` does not apply to a {kind_name} joint: it has no coordinate"),
        )
    }

    /// `limits = [lo, hi]` on a hinge's angle or a slider's travel: finite, lo ≤ 0 ≤ hi (the
    /// t = 0 pose is inside); an angle's in degrees, less than a full turn apart, returned in
    /// radians.
    fn joint_limits(
        &self,
        raw: &Spanned<Vec<f64>>,
        kind_name: &str,
        measure: Option<Measure>,
    ) -> Result<[f64; 2], LoadError> {
        let Some(measure) = measure else {
            return Err(self.unmeasured(raw.span(), "limits", kind_name));
        };
        let list = raw.get_ref();
        let angle = measure == Measure::Angle;
        let unit = if angle { "degrees" } else { "m" };
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
        if angle {
            if hi - lo >= 360.0 {
                return Err(self.error(
                    raw.span(),
                    format!(
                        "{kind_name} `limits` must be less than a full turn apart (hi − lo < \
                         360°), found [{lo}, {hi}]"
                    ),
                ));
            }
            return Ok([lo.to_radians(), hi.to_radians()]);
        }
        Ok([lo, hi])
    }

    /// `motor = { speed, max_torque }` (rad/s, N·m) on an angle, `{ speed, max_force }` (m/s,
    /// N) on a travel.
    fn joint_motor(
        &self,
        raw: &Spanned<RawMotor>,
        kind_name: &str,
        measure: Option<Measure>,
    ) -> Result<Motor, LoadError> {
        let Some(measure) = measure else {
            return Err(self.unmeasured(raw.span(), "motor", kind_name));
        };
        let m = raw.get_ref();
        let angle = measure == Measure::Angle;
        let (key, other, unit, wrong) = if angle {
            ("max_torque", &m.max_force, "N·m", "max_force")
        } else {
            ("max_force", &m.max_torque, "N", "max_torque")
        };
        if let Some(other) = other {
            return Err(self.error(
                other.span(),
                format!("a {kind_name}'s motor takes `{key}` ({unit}), not `{wrong}`"),
            ));
        }
        let needs = |what: &str| {
            self.error(
                raw.span(),
                format!("a {kind_name} joint's `motor` needs `{what}`"),
            )
        };
        let speed = m.speed.as_ref().ok_or_else(|| needs("speed"))?;
        let speed = self.finite(speed, "motor `speed`")?;
        let bound = if angle { &m.max_torque } else { &m.max_force };
        let bound = bound.as_ref().ok_or_else(|| needs(key))?;
        let max = self.positive(bound, &format!("motor `{key}`"))?;
        Ok(Motor { speed, max })
    }
}

/// The keys of one `[[joint]]` table, as its kind reads them (`physics::joints::written`): each
/// error pinned where the key was written, a missing key at the table.
struct JointKeys<'a> {
    v: &'a Validator<'a>,
    raw: &'a Spanned<RawJoint>,
    kind: JointKind,
}

impl JointKeys<'_> {
    /// "a hinge joint needs `axis`", at the table.
    fn missing(&self, key: &str) -> LoadError {
        let kind = self.kind.name();
        self.v
            .error(self.raw.span(), format!("a {kind} joint needs `{key}`"))
    }

    /// The value of a key that holds three numbers.
    fn three(&self, key: &str) -> Result<&Vec3, LoadError> {
        let j = self.raw.get_ref();
        match key {
            "anchor" => j.anchor.as_ref(),
            "axis" => j.axis.as_ref(),
            _ => None,
        }
        .ok_or_else(|| self.missing(key))
    }
}

impl Keys for JointKeys<'_> {
    type Error = LoadError;

    fn point(&self, key: &str) -> Result<Vector3<f64>, LoadError> {
        self.v.vector(self.three(key)?, key)
    }

    fn direction(&self, key: &str) -> Result<Vector3<f64>, LoadError> {
        let raw = self.three(key)?;
        let kind = self.kind.name();
        let v = self.v.vector(raw, &format!("{kind} {key}"))?;
        if v.norm() < 1e-12 {
            return Err(self.v.error(
                raw.span(),
                format!("{kind} `{key}` has zero length: give a non-zero {key}"),
            ));
        }
        Ok(v)
    }

    fn two_points(&self, key: &str) -> Result<[Vector3<f64>; 2], LoadError> {
        let j = self.raw.get_ref();
        let raw = match key {
            "anchors" => j.anchors.as_ref(),
            _ => None,
        }
        .ok_or_else(|| self.missing(key))?;
        self.v
            .two_points(raw, &format!("{} joint", self.kind.name()))
    }

    fn optional_positive(&self, key: &str) -> Result<Option<f64>, LoadError> {
        let j = self.raw.get_ref();
        let raw = match key {
            "length" => j.length.as_ref(),
            _ => None,
        };
        let what = format!("{} joint `{key}`", self.kind.name());
        raw.map(|l| self.v.positive(l, &what)).transpose()
    }

    fn wrong(&self, key: &str, message: &str) -> LoadError {
        let j = self.raw.get_ref();
        let span = match key {
            "anchor" => j.anchor.as_ref().map(Spanned::span),
            "axis" => j.axis.as_ref().map(Spanned::span),
            "anchors" => j.anchors.as_ref().map(Spanned::span),
            "length" => j.length.as_ref().map(Spanned::span),
            _ => None,
        };
        self.v
            .error(span.unwrap_or_else(|| self.raw.span()), message)
    }
}

#[cfg(test)]
mod tests {
    use crate::physics::joints::JointKind;

    /// Every key a joint kind declares is one a `[[joint]]` table holds (`RawJoint`), and
    /// `limits` and `motor` are declared exactly by the kinds whose coordinate has a measure.
    #[test]
    fn every_joint_kind_declares_keys_the_reader_knows() {
        let known = ["anchor", "axis", "anchors", "length", "limits", "motor"];
        for kind in JointKind::ALL {
            let written = kind.written();
            for key in written.keys {
                assert!(known.contains(key), "{}: `{key}`", written.name);
            }
            for key in ["limits", "motor"] {
                assert_eq!(
                    written.keys.contains(&key),
                    kind.measure().is_some(),
                    "{}: `{key}`",
                    written.name
                );
            }
        }
    }

    /// Every joint type and key a kind declares (in its own file) appears in
    /// `docs/lesson-format.md` as `` `word` ``.
    #[test]
    fn every_joint_type_and_key_is_documented() {
        let docs = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/lesson-format.md"),
        )
        .unwrap();
        let missing: Vec<&str> = JointKind::WRITTEN
            .iter()
            .flat_map(|w| std::iter::once(w.name).chain(w.keys.iter().copied()))
            .filter(|w| !docs.contains(&format!("`{w}`")))
            .collect();
        assert!(
            missing.is_empty(),
            "docs/lesson-format.md does not mention {missing:?}"
        );
    }
}
