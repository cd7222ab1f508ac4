//! The settings form's state (key `e`): one text field per value of [`SceneEdits`] — restitution,
//! friction, mass, dt, the initial position, orientation (axis and degrees), velocity and
//! angular velocity component by component of the body the panels show (Tab picks it; the
//! form's title names it), gravity and drag, each spring's k, c and ℓ₀, each hinge's or
//! slider's limits and motor (speed and bound), and each cloth's particle integrator by name
//! and its stiffnesses. A scene of cloths only has no body fields. Typing replaces the
//! selected field's value (then appends); the values are read and checked only when the form
//! is applied or written, with the loader's own rules.
//!
//! Continuous values ([`FieldKind::is_live`]: g, drag, e, μ, a spring's k, a motor's speed)
//! apply while the run goes on ([`SettingsForm::tunings`], `World::tune`), as PhET's sliders
//! do; any other change restarts the scene at t = 0.

use crate::physics::Tuning;
use crate::scene::edit::cloth_integrator;
use crate::scene::SceneEdits;
use nalgebra::{Unit, UnitQuaternion, Vector3};

/// What a field holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldKind {
    Restitution,
    Friction,
    Mass,
    Dt,
    /// Initial position of the barycenter, component 0, 1 or 2.
    Position(usize),
    /// The axis of the initial orientation (any length but 0), component 0, 1 or 2.
    OrientationAxis(usize),
    /// The angle of the initial orientation about its axis, degrees.
    OrientationDegrees,
    /// Initial velocity, component 0, 1 or 2 (x, y, z).
    Velocity(usize),
    /// Initial angular velocity (world frame), component 0, 1 or 2.
    AngularVelocity(usize),
    /// Gravity g, component 0, 1 or 2.
    Gravity(usize),
    /// Drag: linear coefficient k (F = −k v).
    DragLinear,
    /// Drag: angular coefficient k_a (τ = −k_a ω).
    DragAngular,
    /// The particle integrator of cloth `i` (its index in [`SceneEdits::cloths`]), by name.
    ClothIntegrator(usize),
    /// Cloth `i`'s stiffnesses: along x and z, diagonal, second neighbour.
    ClothStretch(usize),
    ClothShear(usize),
    ClothBend(usize),
    /// Entry `i` of the body's size ([`SceneEdits::size`]: a box's side, a radius, a length).
    Size(usize),
    /// Spring `i`'s (its index in [`SceneEdits::springs`]) stiffness k, damping c, rest
    /// length ℓ₀.
    SpringStiffness(usize),
    SpringDamping(usize),
    SpringRestLength(usize),
    /// Joint `i`'s (its index in [`SceneEdits::joints`]) lower and upper limit.
    JointLimitLo(usize),
    JointLimitHi(usize),
    /// Joint `i`'s motor: its speed and its bound (max torque or force).
    MotorSpeed(usize),
    MotorMax(usize),
}

impl FieldKind {
    /// The field's label and unit (a cloth's field: see [`SettingsForm::label`]).
    pub fn label(self) -> (&'static str, &'static str) {
        match self {
            FieldKind::Restitution => ("restitution e", ""),
            FieldKind::Friction => ("friction μ", ""),
            FieldKind::Mass => ("mass M", "kg"),
            FieldKind::Dt => ("time step dt", "s"),
            FieldKind::Position(i) => (["position x₀ x", "x₀ y", "x₀ z"][i], "m"),
            FieldKind::OrientationAxis(i) => (["orientation axis x", "axis y", "axis z"][i], ""),
            FieldKind::OrientationDegrees => ("angle about the axis", "°"),
            FieldKind::Gravity(i) => (["gravity g x", "g y", "g z"][i], "m/s²"),
            FieldKind::DragLinear => ("drag k (F = −k v)", "kg/s"),
            FieldKind::DragAngular => ("drag k_a (τ = −k_a ω)", "kg·m²/s"),
            FieldKind::Velocity(i) => (["velocity v₀ x", "v₀ y", "v₀ z"][i], "m/s"),
            FieldKind::AngularVelocity(i) => (
                ["angular velocity ω₀ x", "ω₀ y", "ω₀ z"][i],
                ["rad/s (world frame)", "rad/s", "rad/s"][i],
            ),
            FieldKind::ClothIntegrator(_) => ("cloth integrator", ""),
            FieldKind::ClothStretch(_) => ("stretch", "N/m"),
            FieldKind::ClothShear(_) => ("shear", "N/m"),
            FieldKind::ClothBend(_) => ("bend", "N/m"),
            FieldKind::Size(_) => ("size", "m"),
            FieldKind::SpringStiffness(_) => ("stiffness k", "N/m"),
            FieldKind::SpringDamping(_) => ("damping c", "N·s/m"),
            FieldKind::SpringRestLength(_) => ("rest length ℓ₀", "m"),
            FieldKind::JointLimitLo(_) => ("lower limit", ""),
            FieldKind::JointLimitHi(_) => ("upper limit", ""),
            FieldKind::MotorSpeed(_) => ("motor speed", ""),
            FieldKind::MotorMax(_) => ("motor max", ""),
        }
    }

    /// A continuous value applied while the scene runs, without a restart (as PhET's
    /// sliders): g, drag, e, μ, a spring's k, a motor's speed. The others restart the scene.
    pub fn is_live(self) -> bool {
        matches!(
            self,
            FieldKind::Restitution
                | FieldKind::Friction
                | FieldKind::Gravity(_)
                | FieldKind::DragLinear
                | FieldKind::DragAngular
                | FieldKind::SpringStiffness(_)
                | FieldKind::MotorSpeed(_)
        )
    }
}

/// One field: what it holds and its text as typed.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub kind: FieldKind,
    pub text: String,
}

/// The form: its fields, the selected one, and the last problem found.
#[derive(Debug, Clone, PartialEq)]
pub struct SettingsForm {
    /// The values the form started from (the scene as it runs).
    pub base: SceneEdits,
    pub fields: Vec<Field>,
    pub selected: usize,
    /// The next character typed replaces the selected field's text.
    pub fresh: bool,
    /// Why the values could not be applied or written.
    pub error: Option<String>,
    /// The name of the body the body fields edit (None: no body).
    pub body_name: Option<String>,
}

/// An orientation as an axis (unit length; z for none) and an angle in degrees.
pub fn axis_degrees(q: &UnitQuaternion<f64>) -> (Vector3<f64>, f64) {
    q.axis_angle().map_or((Vector3::z(), 0.0), |(axis, angle)| {
        (axis.into_inner(), angle.to_degrees())
    })
}

/// A value as the form shows it: the shortest text that reads back as the value rounded to 12
/// significant digits (so 0.30000000000000004 shows as 0.3).
pub fn tidy(x: f64) -> String {
    let rounded: f64 = format!("{x:.11e}").parse().unwrap_or(x);
    let text = format!("{rounded}");
    if text == "-0" {
        "0".into()
    } else {
        text
    }
}

impl SettingsForm {
    /// A form showing `base`. Restitution and friction appear only when the scene has a contact
    /// model (obstacles).
    pub fn new(base: SceneEdits) -> SettingsForm {
        let fields = std::cell::RefCell::new(Vec::new());
        let add_text = |kind, text: String| fields.borrow_mut().push(Field { kind, text });
        let add = |kind, value: f64| add_text(kind, tidy(value));
        if let Some(e) = base.restitution {
            add(FieldKind::Restitution, e);
        }
        if let Some(mu) = base.friction {
            add(FieldKind::Friction, mu);
        }
        let body = base.body.is_some();
        if body {
            add(FieldKind::Mass, base.mass);
            for (i, x) in base.size.iter().enumerate() {
                add(FieldKind::Size(i), *x);
            }
        }
        add(FieldKind::Dt, base.dt);
        if body {
            let (axis, degrees) = axis_degrees(&base.orientation);
            for i in 0..3 {
                add(FieldKind::Position(i), base.position[i]);
            }
            for i in 0..3 {
                add(FieldKind::OrientationAxis(i), axis[i]);
            }
            add(FieldKind::OrientationDegrees, degrees);
            for i in 0..3 {
                add(FieldKind::Velocity(i), base.velocity[i]);
            }
            for i in 0..3 {
                add(FieldKind::AngularVelocity(i), base.angular_velocity[i]);
            }
        }
        let g = base.gravity.unwrap_or_else(Vector3::zeros);
        for i in 0..3 {
            add(FieldKind::Gravity(i), g[i]);
        }
        let (linear, angular) = base.drag.unwrap_or((0.0, 0.0));
        add(FieldKind::DragLinear, linear);
        add(FieldKind::DragAngular, angular);
        for (i, spring) in base.springs.iter().enumerate() {
            add(FieldKind::SpringStiffness(i), spring.stiffness);
            add(FieldKind::SpringDamping(i), spring.damping);
            add(FieldKind::SpringRestLength(i), spring.rest_length);
        }
        for (i, joint) in base.joints.iter().enumerate() {
            if let Some([lo, hi]) = joint.limits {
                add(FieldKind::JointLimitLo(i), lo);
                add(FieldKind::JointLimitHi(i), hi);
            }
            if let Some((speed, max)) = joint.motor {
                add(FieldKind::MotorSpeed(i), speed);
                add(FieldKind::MotorMax(i), max);
            }
        }
        for (i, cloth) in base.cloths.iter().enumerate() {
            add_text(
                FieldKind::ClothIntegrator(i),
                cloth.integrator.name().into(),
            );
            add(FieldKind::ClothStretch(i), cloth.stretch);
            add(FieldKind::ClothShear(i), cloth.shear);
            add(FieldKind::ClothBend(i), cloth.bend);
        }
        let fields = fields.into_inner();
        SettingsForm {
            base,
            fields,
            selected: 0,
            fresh: true,
            error: None,
            body_name: None,
        }
    }

    /// The previous field (wrapping).
    pub fn up(&mut self) {
        let n = self.fields.len();
        self.selected = (self.selected + n - 1) % n;
        self.fresh = true;
    }

    /// The next field (wrapping).
    pub fn down(&mut self) {
        self.selected = (self.selected + 1) % self.fields.len();
        self.fresh = true;
    }

    /// A typed character: replaces the field's text if it was just selected, else appends.
    pub fn type_char(&mut self, c: char) {
        let field = &mut self.fields[self.selected];
        if self.fresh {
            field.text.clear();
            self.fresh = false;
        }
        if field.text.chars().count() < 24 {
            field.text.push(c);
        }
        self.error = None;
    }

    /// Backspace.
    pub fn erase(&mut self) {
        self.fields[self.selected].text.pop();
        self.fresh = false;
        self.error = None;
    }

    /// A field's label and unit: a cloth's names the cloth, "cloth NAME integrator".
    pub fn label(&self, field: &Field) -> (String, &'static str) {
        let cloth = |i: usize| {
            crate::physics::cloth::label(self.base.cloths.get(i).map_or("?", |c| c.name.as_str()))
        };
        let spring = |i: usize| self.base.springs.get(i).map_or("?", |s| s.name.as_str());
        let joint = self.base.joints.get(match field.kind {
            FieldKind::JointLimitLo(i)
            | FieldKind::JointLimitHi(i)
            | FieldKind::MotorSpeed(i)
            | FieldKind::MotorMax(i) => i,
            _ => usize::MAX,
        });
        let joint_name = joint.map_or("?", |j| j.name.as_str());
        let hinge = joint.is_some_and(|j| j.hinge);
        match field.kind {
            FieldKind::Size(i) => (
                crate::scene::edit::size_names(&self.base.size)
                    .get(i)
                    .map_or("size", |n| n)
                    .to_string(),
                "m",
            ),
            FieldKind::SpringStiffness(i)
            | FieldKind::SpringDamping(i)
            | FieldKind::SpringRestLength(i) => {
                let (label, unit) = field.kind.label();
                (format!("spring {} {label}", spring(i)), unit)
            }
            FieldKind::JointLimitLo(_) | FieldKind::JointLimitHi(_) => {
                let (label, _) = field.kind.label();
                (
                    format!("joint {joint_name} {label}"),
                    if hinge { "°" } else { "m" },
                )
            }
            FieldKind::MotorSpeed(_) => (
                format!("joint {joint_name} motor speed"),
                if hinge { "rad/s" } else { "m/s" },
            ),
            FieldKind::MotorMax(_) => (
                format!(
                    "joint {joint_name} motor {}",
                    if hinge { "max torque" } else { "max force" }
                ),
                if hinge { "N·m" } else { "N" },
            ),
            FieldKind::ClothIntegrator(i) => (format!("{} integrator", cloth(i)), ""),
            FieldKind::ClothStretch(i) | FieldKind::ClothShear(i) | FieldKind::ClothBend(i) => {
                let (label, unit) = field.kind.label();
                (format!("{} {label}", cloth(i)), unit)
            }
            kind => {
                let (label, unit) = kind.label();
                (label.to_string(), unit)
            }
        }
    }

    /// The text a field started from.
    fn base_text(&self, kind: FieldKind) -> String {
        match kind {
            FieldKind::ClothIntegrator(i) => self
                .base
                .cloths
                .get(i)
                .map_or_else(String::new, |c| c.integrator.name().to_string()),
            kind => tidy(self.base_value(kind)),
        }
    }

    /// The value a field started from.
    fn base_value(&self, kind: FieldKind) -> f64 {
        let b = &self.base;
        match kind {
            FieldKind::Restitution => b.restitution.unwrap_or(0.0),
            FieldKind::Friction => b.friction.unwrap_or(0.0),
            FieldKind::Mass => b.mass,
            FieldKind::Dt => b.dt,
            FieldKind::Position(i) => b.position[i],
            FieldKind::OrientationAxis(i) => axis_degrees(&b.orientation).0[i],
            FieldKind::OrientationDegrees => axis_degrees(&b.orientation).1,
            FieldKind::Velocity(i) => b.velocity[i],
            FieldKind::AngularVelocity(i) => b.angular_velocity[i],
            FieldKind::Gravity(i) => b.gravity.map_or(0.0, |g| g[i]),
            FieldKind::DragLinear => b.drag.map_or(0.0, |d| d.0),
            FieldKind::DragAngular => b.drag.map_or(0.0, |d| d.1),
            FieldKind::ClothIntegrator(_) => f64::NAN,
            FieldKind::ClothStretch(i) => b.cloths.get(i).map_or(f64::NAN, |c| c.stretch),
            FieldKind::ClothShear(i) => b.cloths.get(i).map_or(f64::NAN, |c| c.shear),
            FieldKind::ClothBend(i) => b.cloths.get(i).map_or(f64::NAN, |c| c.bend),
            FieldKind::Size(i) => b.size.get(i).copied().unwrap_or(f64::NAN),
            FieldKind::SpringStiffness(i) => b.springs.get(i).map_or(f64::NAN, |s| s.stiffness),
            FieldKind::SpringDamping(i) => b.springs.get(i).map_or(f64::NAN, |s| s.damping),
            FieldKind::SpringRestLength(i) => b.springs.get(i).map_or(f64::NAN, |s| s.rest_length),
            FieldKind::JointLimitLo(i) | FieldKind::JointLimitHi(i) => b
                .joints
                .get(i)
                .and_then(|j| j.limits)
                .map_or(f64::NAN, |[lo, hi]| {
                    if matches!(kind, FieldKind::JointLimitLo(_)) {
                        lo
                    } else {
                        hi
                    }
                }),
            FieldKind::MotorSpeed(i) => b
                .joints
                .get(i)
                .and_then(|j| j.motor)
                .map_or(f64::NAN, |m| m.0),
            FieldKind::MotorMax(i) => b
                .joints
                .get(i)
                .and_then(|j| j.motor)
                .map_or(f64::NAN, |m| m.1),
        }
    }

    /// Whether the values typed change only what applies live ([`FieldKind::is_live`]).
    pub fn live_only(&self) -> bool {
        self.fields
            .iter()
            .all(|f| f.kind.is_live() || f.text == self.base_text(f.kind))
    }

    /// The live changes `edits` (this form's [`SettingsForm::edits`]) make, one per changed
    /// parameter, as the world takes them ([`World::tune`]).
    ///
    /// [`World::tune`]: crate::physics::World::tune
    pub fn tunings(&self, edits: &SceneEdits) -> Vec<Tuning> {
        let mut out: Vec<Tuning> = Vec::new();
        for field in &self.fields {
            if !field.kind.is_live() || field.text == self.base_text(field.kind) {
                continue;
            }
            let tuning = match field.kind {
                FieldKind::Restitution => edits.restitution.map(Tuning::Restitution),
                FieldKind::Friction => edits.friction.map(Tuning::Friction),
                FieldKind::Gravity(_) => Some(Tuning::Gravity(edits.gravity)),
                FieldKind::DragLinear | FieldKind::DragAngular => Some(Tuning::Drag(edits.drag)),
                FieldKind::SpringStiffness(i) => {
                    edits.springs.get(i).map(|s| Tuning::SpringStiffness {
                        spring: s.index,
                        stiffness: s.stiffness,
                    })
                }
                FieldKind::MotorSpeed(i) => edits.joints.get(i).and_then(|j| {
                    j.motor.map(|(speed, _)| Tuning::MotorSpeed {
                        joint: j.index,
                        speed,
                    })
                }),
                _ => None,
            };
            if let Some(t) = tuning.filter(|t| !out.contains(t)) {
                out.push(t);
            }
        }
        out
    }

    /// The values typed, checked with the loader's rules; the error names the field. A field
    /// whose text was left as shown keeps its value exactly (not its rounded text).
    pub fn edits(&self) -> Result<SceneEdits, String> {
        let mut edits = self.base.clone();
        let (mut axis, mut degrees) = axis_degrees(&self.base.orientation);
        let mut turned = false;
        for field in &self.fields {
            if field.text == self.base_text(field.kind) {
                continue;
            }
            let label = self.label(field).0;
            if let FieldKind::ClothIntegrator(i) = field.kind {
                let integrator =
                    cloth_integrator(field.text.trim()).map_err(|e| format!("{label}: {e}"))?;
                if let Some(cloth) = edits.cloths.get_mut(i) {
                    cloth.integrator = integrator;
                }
                continue;
            }
            let value: f64 = field
                .text
                .trim()
                .parse()
                .map_err(|_| format!("{label}: `{}` is not a number", field.text))?;
            match field.kind {
                FieldKind::Restitution => edits.restitution = Some(value),
                FieldKind::Friction => edits.friction = Some(value),
                FieldKind::Mass => edits.mass = value,
                FieldKind::Dt => edits.dt = value,
                FieldKind::Position(i) => edits.position[i] = value,
                FieldKind::OrientationAxis(i) => (axis[i], turned) = (value, true),
                FieldKind::OrientationDegrees => (degrees, turned) = (value, true),
                FieldKind::Velocity(i) => edits.velocity[i] = value,
                FieldKind::AngularVelocity(i) => edits.angular_velocity[i] = value,
                FieldKind::Gravity(i) => {
                    edits.gravity.get_or_insert_with(Vector3::zeros)[i] = value;
                }
                FieldKind::DragLinear => edits.drag.get_or_insert((0.0, 0.0)).0 = value,
                FieldKind::DragAngular => edits.drag.get_or_insert((0.0, 0.0)).1 = value,
                FieldKind::ClothStretch(i) | FieldKind::ClothShear(i) | FieldKind::ClothBend(i) => {
                    if let Some(cloth) = edits.cloths.get_mut(i) {
                        *match field.kind {
                            FieldKind::ClothStretch(_) => &mut cloth.stretch,
                            FieldKind::ClothShear(_) => &mut cloth.shear,
                            _ => &mut cloth.bend,
                        } = value;
                    }
                }
                FieldKind::Size(i) => {
                    if let Some(x) = edits.size.get_mut(i) {
                        *x = value;
                    }
                }
                FieldKind::SpringStiffness(i)
                | FieldKind::SpringDamping(i)
                | FieldKind::SpringRestLength(i) => {
                    if let Some(spring) = edits.springs.get_mut(i) {
                        *match field.kind {
                            FieldKind::SpringStiffness(_) => &mut spring.stiffness,
                            FieldKind::SpringDamping(_) => &mut spring.damping,
                            _ => &mut spring.rest_length,
                        } = value;
                    }
                }
                FieldKind::JointLimitLo(i) | FieldKind::JointLimitHi(i) => {
                    if let Some([lo, hi]) = edits.joints.get_mut(i).and_then(|j| j.limits.as_mut())
                    {
                        *if matches!(field.kind, FieldKind::JointLimitLo(_)) {
                            lo
                        } else {
                            hi
                        } = value;
                    }
                }
                FieldKind::MotorSpeed(i) | FieldKind::MotorMax(i) => {
                    if let Some((speed, max)) =
                        edits.joints.get_mut(i).and_then(|j| j.motor.as_mut())
                    {
                        *if matches!(field.kind, FieldKind::MotorSpeed(_)) {
                            speed
                        } else {
                            max
                        } = value;
                    }
                }
                FieldKind::ClothIntegrator(_) => {}
            }
        }
        if turned {
            // The loader's words for the same values in a file.
            if !degrees.is_finite() {
                return Err(format!(
                    "orientation degrees must be finite, found {degrees}"
                ));
            }
            let unit = Unit::try_new(axis, 1e-12)
                .ok_or("orientation axis has zero length: give a non-zero axis")?;
            edits.orientation = UnitQuaternion::from_axis_angle(&unit, degrees.to_radians());
        }
        match edits.problem() {
            Some(problem) => Err(problem),
            None => Ok(edits),
        }
    }

    /// What changed from the values the form started with, e.g. `mass 2 → 3 kg, dt 0.01 → 0.005 s`.
    pub fn changes(&self, edits: &SceneEdits) -> String {
        let mut parts: Vec<String> = Vec::new();
        let note = |parts: &mut Vec<String>, name: &str, old: f64, new: f64, unit: &str| {
            if old != new {
                let unit = if unit.is_empty() {
                    String::new()
                } else {
                    format!(" {unit}")
                };
                parts.push(format!("{name} {} → {}{unit}", tidy(old), tidy(new)));
            }
        };
        let b = &self.base;
        if let (Some(old), Some(new)) = (b.restitution, edits.restitution) {
            note(&mut parts, "e", old, new, "");
        }
        if let (Some(old), Some(new)) = (b.friction, edits.friction) {
            note(&mut parts, "μ", old, new, "");
        }
        let body = b.body.is_some();
        if body {
            note(&mut parts, "mass", b.mass, edits.mass, "kg");
            let names = crate::scene::edit::size_names(&b.size);
            for ((name, old), new) in names.iter().zip(&b.size).zip(&edits.size) {
                note(&mut parts, name, *old, *new, "m");
            }
        }
        note(&mut parts, "dt", b.dt, edits.dt, "s");
        const AXES: [&str; 3] = ["x", "y", "z"];
        if body {
            for (i, axis) in AXES.into_iter().enumerate() {
                let name = format!("x₀{axis}");
                note(&mut parts, &name, b.position[i], edits.position[i], "m");
            }
            if b.orientation != edits.orientation {
                let (axis, degrees) = axis_degrees(&edits.orientation);
                parts.push(format!(
                    "orientation → {}° about ({}, {}, {})",
                    tidy(degrees),
                    tidy(axis.x),
                    tidy(axis.y),
                    tidy(axis.z)
                ));
            }
            for (i, axis) in AXES.into_iter().enumerate() {
                let (v, w) = (format!("v₀{axis}"), format!("ω₀{axis}"));
                note(&mut parts, &v, b.velocity[i], edits.velocity[i], "m/s");
                let (old, new) = (b.angular_velocity[i], edits.angular_velocity[i]);
                note(&mut parts, &w, old, new, "rad/s");
            }
        }
        let g = |e: &SceneEdits| e.gravity.unwrap_or_else(Vector3::zeros);
        for (i, axis) in AXES.into_iter().enumerate() {
            note(
                &mut parts,
                &format!("g{axis}"),
                g(b)[i],
                g(edits)[i],
                "m/s²",
            );
        }
        let drag = |e: &SceneEdits| e.drag.unwrap_or((0.0, 0.0));
        note(&mut parts, "drag k", drag(b).0, drag(edits).0, "kg/s");
        note(&mut parts, "drag k_a", drag(b).1, drag(edits).1, "kg·m²/s");
        for (old, new) in b.cloths.iter().zip(&edits.cloths) {
            if old.integrator != new.integrator {
                parts.push(format!(
                    "{} {} → {}",
                    crate::physics::cloth::label(&old.name),
                    old.integrator.name(),
                    new.integrator.name()
                ));
            }
            for (what, o, n) in [
                ("stretch", old.stretch, new.stretch),
                ("shear", old.shear, new.shear),
                ("bend", old.bend, new.bend),
            ] {
                note(
                    &mut parts,
                    &format!("{} {what}", crate::physics::cloth::label(&old.name)),
                    o,
                    n,
                    "N/m",
                );
            }
        }
        for (old, new) in b.springs.iter().zip(&edits.springs) {
            for (what, o, n, unit) in [
                ("k", old.stiffness, new.stiffness, "N/m"),
                ("c", old.damping, new.damping, "N·s/m"),
                ("ℓ₀", old.rest_length, new.rest_length, "m"),
            ] {
                note(
                    &mut parts,
                    &format!("spring {} {what}", old.name),
                    o,
                    n,
                    unit,
                );
            }
        }
        for (old, new) in b.joints.iter().zip(&edits.joints) {
            let (limit, speed) = if old.hinge {
                ("°", "rad/s")
            } else {
                ("m", "m/s")
            };
            if let (Some(o), Some(n)) = (old.limits, new.limits) {
                note(&mut parts, &format!("{} lo", old.name), o[0], n[0], limit);
                note(&mut parts, &format!("{} hi", old.name), o[1], n[1], limit);
            }
            if let (Some(o), Some(n)) = (old.motor, new.motor) {
                note(&mut parts, &format!("{} motor", old.name), o.0, n.0, speed);
                let bound = if old.hinge { "N·m" } else { "N" };
                note(&mut parts, &format!("{} max", old.name), o.1, n.1, bound);
            }
        }
        if parts.is_empty() {
            "no value changed".into()
        } else {
            parts.join(", ")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::cloth::ClothIntegrator;
    use crate::scene::ClothEdit;
    use nalgebra::Vector3;

    fn base() -> SceneEdits {
        SceneEdits {
            body: Some(0),
            dt: 0.01,
            restitution: Some(0.5),
            friction: Some(0.3),
            mass: 2.0,
            position: Vector3::new(0.0, 1.5, 0.0),
            orientation: UnitQuaternion::identity(),
            velocity: Vector3::new(0.3, 1.0, 0.0),
            angular_velocity: Vector3::new(0.5, 1.0, 2.0),
            gravity: Some(Vector3::new(0.0, -9.81, 0.0)),
            drag: None,
            cloths: Vec::new(),
            springs: Vec::new(),
            joints: Vec::new(),
            size: Vec::new(),
        }
    }

    #[test]
    fn typing_replaces_then_appends_and_the_values_read_back() {
        let mut form = SettingsForm::new(base());
        // e, μ, mass, dt, x₀ (3), axis (3), angle, v₀ (3), ω₀ (3), g (3), drag k and k_a.
        assert_eq!(form.fields.len(), 22);
        form.down();
        form.down(); // mass
        for c in "3.5".chars() {
            form.type_char(c);
        }
        form.down(); // dt
        for c in "1e-3".chars() {
            form.type_char(c);
        }
        let edits = form.edits().unwrap();
        assert_eq!(edits.mass, 3.5);
        assert_eq!(edits.dt, 1e-3);
        assert_eq!(edits.velocity, base().velocity);
        assert_eq!(form.changes(&edits), "mass 2 → 3.5 kg, dt 0.01 → 0.001 s");
    }

    #[test]
    fn a_bad_value_names_its_field_and_nothing_is_applied() {
        let mut form = SettingsForm::new(base());
        form.type_char('2'); // restitution 2
        assert_eq!(
            form.edits().unwrap_err(),
            "restitution must be between 0 and 1, found 2"
        );
        form.erase();
        form.type_char('-');
        assert_eq!(
            form.edits().unwrap_err(),
            "restitution e: `-` is not a number"
        );
    }

    #[test]
    fn without_obstacles_there_is_no_restitution_or_friction_field() {
        let form = SettingsForm::new(SceneEdits {
            restitution: None,
            friction: None,
            ..base()
        });
        assert_eq!(form.fields.len(), 20);
        assert_eq!(form.fields[0].kind, FieldKind::Mass);
    }

    fn cloths_only() -> SceneEdits {
        SceneEdits {
            body: None,
            mass: 0.0,
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
            cloths: vec![ClothEdit {
                name: "sheet".into(),
                integrator: ClothIntegrator::SymplecticEuler,
                stretch: 2000.0,
                shear: 500.0,
                bend: 0.0,
            }],
            ..base()
        }
    }

    #[test]
    fn a_scene_of_cloths_only_has_dt_and_a_field_per_cloth_but_no_body_field() {
        let mut form = SettingsForm::new(cloths_only());
        let kinds: Vec<FieldKind> = form.fields.iter().map(|f| f.kind).collect();
        assert_eq!(
            kinds,
            vec![
                FieldKind::Restitution,
                FieldKind::Friction,
                FieldKind::Dt,
                FieldKind::Gravity(0),
                FieldKind::Gravity(1),
                FieldKind::Gravity(2),
                FieldKind::DragLinear,
                FieldKind::DragAngular,
                FieldKind::ClothIntegrator(0),
                FieldKind::ClothStretch(0),
                FieldKind::ClothShear(0),
                FieldKind::ClothBend(0),
            ]
        );
        assert_eq!(form.label(&form.fields[8]).0, "cloth sheet integrator");
        assert_eq!(form.fields[8].text, "symplectic-euler");
        assert_eq!(
            form.label(&form.fields[9]),
            ("cloth sheet stretch".to_string(), "N/m")
        );
        assert_eq!(form.fields[9].text, "2000");
        // Untouched, nothing changes (the absent body's zero mass is not checked).
        assert_eq!(form.edits().unwrap(), cloths_only());
        form.down();
        form.down(); // dt
        for c in "0.013".chars() {
            form.type_char(c);
        }
        form.selected = 8; // the cloth's integrator
        form.fresh = true;
        for c in "implicit-euler".chars() {
            form.type_char(c);
        }
        form.down(); // stretch
        for c in "500".chars() {
            form.type_char(c);
        }
        let edits = form.edits().unwrap();
        assert_eq!(edits.cloths[0].integrator, ClothIntegrator::ImplicitEuler);
        assert_eq!(edits.cloths[0].stretch, 500.0);
        assert_eq!(
            form.changes(&edits),
            "dt 0.01 → 0.013 s, cloth sheet symplectic-euler → implicit-euler, \
             cloth sheet stretch 2000 → 500 N/m"
        );
        form.down(); // shear
        form.type_char('-');
        form.type_char('1');
        assert_eq!(
            form.edits().unwrap_err(),
            "cloth sheet: shear must be ≥ 0, found -1"
        );
    }

    #[test]
    fn a_misspelt_integrator_is_refused_with_the_loaders_words() {
        let mut form = SettingsForm::new(cloths_only());
        form.selected = 8;
        for c in "implict-euler".chars() {
            form.type_char(c);
        }
        assert_eq!(
            form.edits().unwrap_err(),
            "cloth sheet integrator: unknown cloth integrator `implict-euler` (did you mean \
             `implicit-euler`?); valid cloth integrators: symplectic-euler, implicit-euler"
        );
    }

    /// Types `text` into the field of kind `kind`.
    fn type_into(form: &mut SettingsForm, kind: FieldKind, text: &str) {
        form.selected = form.fields.iter().position(|f| f.kind == kind).unwrap();
        form.fresh = true;
        for c in text.chars() {
            form.type_char(c);
        }
    }

    #[test]
    fn position_orientation_gravity_and_drag_are_edited() {
        let mut form = SettingsForm::new(base());
        // The identity shows as 0° about z.
        let at = |form: &SettingsForm, kind| {
            form.fields
                .iter()
                .find(|f| f.kind == kind)
                .unwrap()
                .text
                .clone()
        };
        assert_eq!(at(&form, FieldKind::OrientationAxis(2)), "1");
        assert_eq!(at(&form, FieldKind::OrientationDegrees), "0");
        assert_eq!(at(&form, FieldKind::Gravity(1)), "-9.81");
        assert_eq!(at(&form, FieldKind::DragLinear), "0");
        type_into(&mut form, FieldKind::Position(1), "2");
        type_into(&mut form, FieldKind::OrientationDegrees, "90");
        type_into(&mut form, FieldKind::Gravity(1), "-1.62");
        type_into(&mut form, FieldKind::DragLinear, "0.1");
        let edits = form.edits().unwrap();
        assert_eq!(edits.position, Vector3::new(0.0, 2.0, 0.0));
        // 90° about z takes x to y.
        let x = edits.orientation * Vector3::x();
        assert!((x - Vector3::y()).norm() < 1e-15, "{x}");
        assert_eq!(edits.gravity, Some(Vector3::new(0.0, -1.62, 0.0)));
        // No drag before: the angular coefficient the form showed, 0.
        assert_eq!(edits.drag, Some((0.1, 0.0)));
        assert_eq!(
            form.changes(&edits),
            "x₀y 1.5 → 2 m, orientation → 90° about (0, 0, 1), gy -9.81 → -1.62 m/s², \
             drag k 0 → 0.1 kg/s"
        );
        // The loader's words for a zero axis and a negative drag.
        type_into(&mut form, FieldKind::OrientationAxis(2), "0");
        assert_eq!(
            form.edits().unwrap_err(),
            "orientation axis has zero length: give a non-zero axis"
        );
        type_into(&mut form, FieldKind::OrientationAxis(2), "1");
        type_into(&mut form, FieldKind::DragAngular, "-2");
        assert_eq!(
            form.edits().unwrap_err(),
            "drag.angular must be ≥ 0, found -2"
        );
    }

    #[test]
    fn values_show_tidily() {
        assert_eq!(tidy(0.1 + 0.2), "0.3");
        assert_eq!(tidy(-0.0), "0");
        assert_eq!(tidy(1e-4), "0.0001");
        assert_eq!(tidy(2.0), "2");
    }
}
