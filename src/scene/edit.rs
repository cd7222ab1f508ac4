//! The settings a teacher can change on a loaded scene (the app's settings form): applied to a
//! [`Scene`] in memory, and written back into the scene file's text with every other key,
//! comment and page kept as written.
//!
//! ```text
//! dt                     [scene] dt
//! restitution, friction  [scene] contact = { restitution, friction }   (scenes with obstacles)
//! mass M                 [body] mass; with `masses`, each point mass × M'/M (their sum is M')
//! position x             [body] position
//! orientation            [body] orientation = { axis, degrees } (written only when changed)
//! velocity v             [body] velocity
//! angular velocity ω     [body] angular_velocity (world frame; replaces angular_velocity_body)
//! gravity g              [scene] gravity (absent stays absent until a component is changed)
//! drag k, k_a            [scene] drag = { linear, angular } (likewise)
//! cloth NAME integrator  [[cloth]] integrator of the cloth named NAME (written only when it
//!                        differs from what the file gives the cloth, its own or the scene's)
//! cloth NAME stretch,    [[cloth]] stretch, shear, bend (written only when changed)
//!   shear, bend
//! spring NAME k, c, ℓ₀   [[spring]] stiffness, damping, rest_length (written only when changed)
//! joint NAME limits,     [[joint]] limits (hinge: degrees), motor = { speed, max_torque |
//!   motor speed, bound     max_force } (hinges and sliders that have them; only when changed)
//! ```
//!
//! A scene of cloths only has no body values: `body` is None and dt, the contact values,
//! gravity, drag and the cloths' values are edited. The values pass the loader's range rules
//! ([`SceneEdits::problem`]) and the edited scene passes [`Scene::check_rules`], the rules
//! the file and the command-line flags pass.
//!
//! In memory the body keeps its points and its inertia scales with the mass
//! (`I_body' = (M'/M) I_body`, see [`Body::with_mass`]); the initial momenta follow from the
//! new velocities: `P₀ = M' v`, `L₀ = R I_body' Rᵀ ω`. Loading the written file gives the same
//! scene (the tests check it).
//!
//! [`Body::with_mass`]: crate::physics::Body::with_mass

use super::{Naming, Scene};
use crate::physics::cloth::ClothIntegrator;
use crate::physics::collision::geometry::Shape;
use crate::physics::derive::derive;
use crate::physics::effects::{Effect, Effects};
use crate::physics::joints::written::Measure;
use crate::physics::state::Orientation;
use crate::physics::Body;
use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};
use std::path::Path;
use toml_edit::{Array, DocumentMut, Item, TableLike, Value};

/// The values the settings form edits.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneEdits {
    /// Which body the body values belong to (its index in the scene); None for a scene of
    /// cloths only (then mass and velocities are not used).
    pub body: Option<usize>,
    /// Time step, s (> 0).
    pub dt: f64,
    /// Coefficient of restitution, 0 ≤ e ≤ 1 (None: the scene has no contact model).
    pub restitution: Option<f64>,
    /// Coulomb friction coefficient ≥ 0 (None: no contact model).
    pub friction: Option<f64>,
    /// Total mass of the body, kg (> 0).
    pub mass: f64,
    /// Initial position of the barycenter, m.
    pub position: Vector3<f64>,
    /// Initial orientation, body → world.
    pub orientation: UnitQuaternion<f64>,
    /// Initial velocity of the barycenter, m/s.
    pub velocity: Vector3<f64>,
    /// Initial angular velocity, world frame, rad/s.
    pub angular_velocity: Vector3<f64>,
    /// Uniform gravity g, m/s² (None: the scene declares none).
    pub gravity: Option<Vector3<f64>>,
    /// Drag coefficients (linear kg/s, angular kg·m²/s), each ≥ 0 (None: no drag declared).
    pub drag: Option<(f64, f64)>,
    /// Each cloth's particle integrator and stiffnesses, in scene order.
    pub cloths: Vec<ClothEdit>,
    /// Each spring's stiffness, damping and rest length, in scene order.
    pub springs: Vec<SpringEdit>,
    /// Each hinge's and slider's limits and motor (those that have one), in scene order.
    pub joints: Vec<JointEdit>,
    /// The body's size, by its shape ([`size_names`]): a box's sides x, y, z; a
    /// sphere's radius; a capsule's or cylinder's radius and length, m (empty: a body of
    /// points or a mesh, or a fixed one, or no body).
    pub size: Vec<f64>,
}

/// The edited values of one spring (`[[spring]]`).
#[derive(Debug, Clone, PartialEq)]
pub struct SpringEdit {
    /// Its index among the scene's springs, and its name.
    pub index: usize,
    pub name: String,
    /// k, N/m (> 0).
    pub stiffness: f64,
    /// c, N·s/m (≥ 0).
    pub damping: f64,
    /// ℓ₀, m (≥ 0).
    pub rest_length: f64,
}

/// The edited limits and motor of one hinge or slider (`[[joint]]`).
#[derive(Debug, Clone, PartialEq)]
pub struct JointEdit {
    /// Its index among the scene's joints, and its name.
    pub index: usize,
    pub name: String,
    /// A hinge, or any joint whose coordinate is an angle (limits in degrees, motor in rad/s and
    /// N·m), else a slider's travel (m, m/s and N).
    pub hinge: bool,
    /// `[lo, hi]` from the t = 0 pose, as the file writes them (hinge: degrees), lo ≤ 0 ≤ hi.
    pub limits: Option<[f64; 2]>,
    /// The motor's speed and its bound (max_torque or max_force, > 0).
    pub motor: Option<(f64, f64)>,
}

/// The edited value of one cloth.
#[derive(Debug, Clone, PartialEq)]
pub struct ClothEdit {
    /// The cloth's name (unique in the scene).
    pub name: String,
    pub integrator: ClothIntegrator,
    /// Spring stiffnesses, N/m: along x and z (> 0), diagonal and second-neighbour (≥ 0).
    pub stretch: f64,
    pub shear: f64,
    pub bend: f64,
}

/// A particle integrator by name, with the loader's own message (and its "did you mean")
/// when there is none by that name.
pub fn cloth_integrator(word: &str) -> Result<ClothIntegrator, String> {
    ClothIntegrator::from_name(word).ok_or_else(|| super::cloth::unknown_cloth_integrator(word))
}

impl SceneEdits {
    /// The values a scene has now, for its first body.
    pub fn of(scene: &Scene) -> SceneEdits {
        SceneEdits::of_body(scene, 0)
    }

    /// The values a scene has now, for body `index` (none if the scene has no such body:
    /// a scene of cloths only).
    pub fn of_body(scene: &Scene, index: usize) -> SceneEdits {
        let cloths = scene
            .cloths
            .iter()
            .map(|c| ClothEdit {
                name: c.name.clone(),
                integrator: c.integrator,
                stretch: c.stretch,
                shear: c.shear,
                bend: c.bend,
            })
            .collect();
        let drag = scene.effects.list().iter().find_map(|e| match e {
            Effect::Drag { linear, angular } => Some((*linear, *angular)),
            Effect::Gravity(_) => None,
        });
        let springs = (scene.links.springs.iter().enumerate())
            .map(|(index, s)| SpringEdit {
                index,
                name: s.name.clone(),
                stiffness: s.stiffness,
                damping: s.damping,
                rest_length: s.rest_length,
            })
            .collect();
        let joints = (scene.links.joints.iter().enumerate())
            .filter(|(_, j)| j.limits.is_some() || j.motor.is_some())
            .map(|(index, j)| {
                let hinge = j.kind.measure() == Some(Measure::Angle);
                let unit = |x: f64| if hinge { x.to_degrees() } else { x };
                JointEdit {
                    index,
                    name: j.name.clone(),
                    hinge,
                    limits: j.limits.map(|[lo, hi]| [unit(lo), unit(hi)]),
                    motor: j.motor.map(|m| (m.speed, m.max)),
                }
            })
            .collect();
        let mut edits = SceneEdits {
            size: Vec::new(),
            springs,
            joints,
            body: None,
            dt: scene.dt,
            restitution: scene.contact.map(|c| c.restitution),
            friction: scene.contact.map(|c| c.friction),
            mass: 0.0,
            position: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
            gravity: scene.effects.gravity(),
            drag,
            cloths,
        };
        if let Some(b) = scene.bodies.get(index) {
            let kinematics = derive(&b.body, &b.initial);
            edits.body = Some(index);
            edits.size = size_of(&b.body);
            edits.mass = b.body.mass;
            edits.position = b.initial.position;
            edits.orientation = b.initial.orientation.quaternion();
            edits.velocity = kinematics.velocity;
            edits.angular_velocity = kinematics.angular_velocity;
        }
        edits
    }

    /// Why these values cannot make a scene (the loader's own rules), if they cannot.
    pub fn problem(&self) -> Option<String> {
        let finite = |v: &Vector3<f64>| v.iter().all(|c| c.is_finite());
        if !(self.dt > 0.0 && self.dt.is_finite()) {
            return Some(format!("dt must be > 0, found {}", self.dt));
        }
        if self.body.is_some() && !(self.mass > 0.0 && self.mass.is_finite()) {
            return Some(format!("mass must be > 0, found {}", self.mass));
        }
        if let Some(e) = self.restitution {
            if !(0.0..=1.0).contains(&e) {
                return Some(format!("restitution must be between 0 and 1, found {e}"));
            }
        }
        if let Some(mu) = self.friction {
            if !(mu >= 0.0 && mu.is_finite()) {
                return Some(format!("friction must be ≥ 0, found {mu}"));
            }
        }
        if self.body.is_some() && (!finite(&self.velocity) || !finite(&self.angular_velocity)) {
            return Some("velocities must be finite".into());
        }
        if self.body.is_some()
            && (!finite(&self.position) || !self.orientation.coords.iter().all(|c| c.is_finite()))
        {
            return Some("position and orientation must be finite".into());
        }
        if self.gravity.is_some_and(|g| !finite(&g)) {
            return Some("gravity must be finite".into());
        }
        if let Some((linear, angular)) = self.drag {
            for (what, k) in [("drag.linear", linear), ("drag.angular", angular)] {
                if !(k >= 0.0 && k.is_finite()) {
                    return Some(format!("{what} must be ≥ 0, found {k}"));
                }
            }
        }
        if let Some(x) = self.size.iter().find(|x| !(**x > 0.0 && x.is_finite())) {
            return Some(format!("sizes must be > 0, found {x}"));
        }
        for s in &self.springs {
            if !(s.stiffness > 0.0 && s.stiffness.is_finite()) {
                return Some(format!(
                    "spring {}: stiffness must be > 0, found {}",
                    s.name, s.stiffness
                ));
            }
            for (what, x) in [("damping", s.damping), ("rest_length", s.rest_length)] {
                if !(x >= 0.0 && x.is_finite()) {
                    return Some(format!("spring {}: {what} must be ≥ 0, found {x}", s.name));
                }
            }
        }
        for j in &self.joints {
            if let Some([lo, hi]) = j.limits {
                if !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && 0.0 <= hi) {
                    return Some(format!(
                        "joint {}: `limits` must hold 0 (the t = 0 pose): lo ≤ 0 ≤ hi, found \
                         [{lo}, {hi}]",
                        j.name
                    ));
                }
                if j.hinge && hi - lo >= 360.0 {
                    return Some(format!(
                        "joint {}: hinge `limits` must be less than a full turn apart",
                        j.name
                    ));
                }
            }
            if let Some((speed, max)) = j.motor {
                if !(speed.is_finite() && max > 0.0 && max.is_finite()) {
                    return Some(format!(
                        "joint {}: the motor needs a finite speed and a bound > 0, found \
                         {speed} and {max}",
                        j.name
                    ));
                }
            }
        }
        for c in &self.cloths {
            if !(c.stretch > 0.0 && c.stretch.is_finite()) {
                return Some(format!(
                    "{}: stretch must be > 0, found {}",
                    crate::physics::cloth::label(&c.name),
                    c.stretch
                ));
            }
            for (what, k) in [("shear", c.shear), ("bend", c.bend)] {
                if !(k >= 0.0 && k.is_finite()) {
                    return Some(format!(
                        "{}: {what} must be ≥ 0, found {k}",
                        crate::physics::cloth::label(&c.name)
                    ));
                }
            }
        }
        None
    }

    /// The scene's effects with these values: gravity and drag replaced where the scene
    /// declares them, added where it did not and they are given.
    fn effects(&self, effects: &Effects) -> Effects {
        let mut list: Vec<Effect> = effects.list().to_vec();
        let (mut gravity, mut drag) = (self.gravity, self.drag);
        for effect in &mut list {
            match effect {
                Effect::Gravity(g) => {
                    if let Some(new) = gravity.take() {
                        *g = new;
                    }
                }
                Effect::Drag { linear, angular } => {
                    if let Some((l, a)) = drag.take() {
                        (*linear, *angular) = (l, a);
                    }
                }
            }
        }
        list.extend(gravity.map(Effect::Gravity));
        list.extend(drag.map(|(linear, angular)| Effect::Drag { linear, angular }));
        Effects::new(list)
    }

    /// The scene with these values (the body rescaled to the new mass, the initial momenta
    /// recomputed from the velocities).
    pub fn apply(&self, scene: &Scene) -> Result<Scene, String> {
        if let Some(problem) = self.problem() {
            return Err(problem);
        }
        let mut out = scene.clone();
        out.dt = self.dt;
        out.effects = self.effects(&scene.effects);
        if let Some(contact) = &mut out.contact {
            if let Some(e) = self.restitution {
                contact.restitution = e;
            }
            if let Some(mu) = self.friction {
                contact.friction = mu;
            }
        }
        for edit in &self.cloths {
            let cloth = out
                .cloths
                .iter_mut()
                .find(|c| c.name == edit.name)
                .ok_or_else(|| format!("the scene has no cloth named `{}`", edit.name))?;
            cloth.integrator = edit.integrator;
            cloth.stretch = edit.stretch;
            cloth.shear = edit.shear;
            cloth.bend = edit.bend;
        }
        for edit in &self.springs {
            if let Some(spring) = out.links.springs.get_mut(edit.index) {
                spring.stiffness = edit.stiffness;
                spring.damping = edit.damping;
                spring.rest_length = edit.rest_length;
            }
        }
        for edit in &self.joints {
            if let Some(joint) = out.links.joints.get_mut(edit.index) {
                // Limits the form left as shown keep their value exactly (degrees → radians
                // → degrees need not give back the same last bit).
                let shown = |x: f64| if edit.hinge { x.to_degrees() } else { x };
                let unit = |x: f64| if edit.hinge { x.to_radians() } else { x };
                if joint.limits.map(|[lo, hi]| [shown(lo), shown(hi)]) != edit.limits {
                    joint.limits = edit.limits.map(|[lo, hi]| [unit(lo), unit(hi)]);
                }
                if let (Some(motor), Some((speed, max))) = (&mut joint.motor, edit.motor) {
                    (motor.speed, motor.max) = (speed, max);
                }
            }
        }
        if let Some(index) = self.body {
            self.apply_body(&mut out, index)?;
        }
        // The rules the file and the command-line flags pass.
        out.check_rules(Naming::File)
            .map_err(|(_, message)| message)?;
        Ok(out)
    }

    /// The body values into body `index` of `out`.
    fn apply_body(&self, out: &mut Scene, index: usize) -> Result<(), String> {
        let edited = out
            .bodies
            .get_mut(index)
            .ok_or_else(|| format!("the scene has no body number {}", index + 1))?;
        if !self.size.is_empty() && self.size != size_of(&edited.body) {
            edited.body = resized(&edited.body, &self.size).map_err(|e| e.to_string())?;
        }
        edited.body = edited
            .body
            .with_mass(self.mass)
            .map_err(|e| e.to_string())?;
        edited.initial.position = self.position;
        if edited.initial.orientation.quaternion() != self.orientation {
            edited.initial.orientation = Orientation::Quaternion(self.orientation);
        }
        let rotation = edited.initial.orientation.matrix();
        let inertia_world = rotation * edited.body.inertia_body * rotation.transpose();
        edited.initial.linear_momentum = self.velocity * edited.body.mass;
        edited.initial.angular_momentum = inertia_world * self.angular_velocity;
        Ok(())
    }

    /// The scene file's text with these values written in; everything else (keys, comments,
    /// pages) stays as written. `body` is the index of the edited body in `[[body]]` (0 for a
    /// single `[body]`; unused when [`SceneEdits::body`] is None). With `mesh_from`, a relative mesh `file` is rewritten as an absolute
    /// path from that folder (the written file may live elsewhere).
    pub fn write_into(
        &self,
        source: &str,
        body: usize,
        mesh_from: Option<&Path>,
    ) -> Result<String, String> {
        if let Some(problem) = self.problem() {
            return Err(problem);
        }
        let mut doc: DocumentMut = source
            .parse()
            .map_err(|e: toml_edit::TomlError| format!("the scene file is not TOML: {e}"))?;
        let scene = doc
            .get_mut("scene")
            .and_then(Item::as_table_like_mut)
            .ok_or("the scene file has no [scene] table")?;
        set(scene, "dt", Value::from(self.dt));
        if let Some(g) = self.gravity {
            if numbers(scene.get("gravity")) != Some(g.iter().copied().collect()) {
                set(scene, "gravity", vector(&g));
            }
        }
        if let Some((linear, angular)) = self.drag {
            match scene.get_mut("drag").and_then(Item::as_table_like_mut) {
                Some(drag) => {
                    for (key, k) in [("linear", linear), ("angular", angular)] {
                        if drag.get(key).and_then(Item::as_value).and_then(number) != Some(k) {
                            set(drag, key, Value::from(k));
                        }
                    }
                }
                None => {
                    let mut drag = toml_edit::InlineTable::new();
                    drag.insert("linear", Value::from(linear));
                    drag.insert("angular", Value::from(angular));
                    set(scene, "drag", Value::InlineTable(drag));
                }
            }
        }
        if let Some(contact) = scene.get_mut("contact").and_then(Item::as_table_like_mut) {
            if let Some(e) = self.restitution {
                set(contact, "restitution", Value::from(e));
            }
            if let Some(mu) = self.friction {
                set(contact, "friction", Value::from(mu));
            }
        }
        self.write_cloths(&mut doc)?;
        self.write_links(&mut doc)?;
        if let Some(body) = self.body.map(|_| body) {
            self.write_body(&mut doc, body, mesh_from)?;
        }
        Ok(doc.to_string())
    }

    /// Each cloth's `integrator`, where it differs from what the file gives the cloth.
    fn write_cloths(&self, doc: &mut DocumentMut) -> Result<(), String> {
        if self.cloths.is_empty() {
            return Ok(());
        }
        let scene_integrator = doc
            .get("scene")
            .and_then(|s| s.get("integrator"))
            .and_then(Item::as_str)
            .map(str::to_owned);
        let tables = doc
            .get_mut("cloth")
            .and_then(Item::as_array_of_tables_mut)
            .ok_or("the scene file has no [[cloth]]")?;
        for edit in &self.cloths {
            let table = tables
                .iter_mut()
                .enumerate()
                .find(|(k, t)| {
                    t.get("name")
                        .and_then(Item::as_str)
                        .map_or_else(|| format!("cloth{}", k + 1), str::to_owned)
                        == edit.name
                })
                .map(|(_, t)| t)
                .ok_or_else(|| format!("the scene file has no cloth named `{}`", edit.name))?;
            let current = table
                .get("integrator")
                .and_then(Item::as_str)
                .or(scene_integrator.as_deref());
            if current != Some(edit.integrator.name()) {
                set(table, "integrator", Value::from(edit.integrator.name()));
            }
            for (key, k, absent) in [
                ("stretch", edit.stretch, None),
                ("shear", edit.shear, Some(0.0)),
                ("bend", edit.bend, Some(0.0)),
            ] {
                let current = table
                    .get(key)
                    .and_then(Item::as_value)
                    .and_then(number)
                    .or(absent);
                if current != Some(k) {
                    set(table, key, Value::from(k));
                }
            }
        }
        Ok(())
    }

    /// Each spring's stiffness, damping and rest length, each joint's limits and motor, where
    /// they differ from what the file gives (a `[[spring]]` or `[[joint]]` found by its name,
    /// or its default name `spring1`, `joint2`, …).
    fn write_links(&self, doc: &mut DocumentMut) -> Result<(), String> {
        fn table<'a>(
            doc: &'a mut DocumentMut,
            kind: &str,
            name: &str,
        ) -> Result<&'a mut toml_edit::Table, String> {
            doc.get_mut(kind)
                .and_then(Item::as_array_of_tables_mut)
                .and_then(|tables| {
                    tables.iter_mut().enumerate().find_map(|(k, t)| {
                        let named = t
                            .get("name")
                            .and_then(Item::as_str)
                            .map_or_else(|| format!("{kind}{}", k + 1), str::to_owned);
                        (named == name).then_some(t)
                    })
                })
                .ok_or_else(|| format!("the scene file has no {kind} named `{name}`"))
        }
        let value_of =
            |t: &toml_edit::Table, key: &str| t.get(key).and_then(Item::as_value).and_then(number);
        for edit in &self.springs {
            let t = table(doc, "spring", &edit.name)?;
            if value_of(t, "stiffness") != Some(edit.stiffness) {
                set(t, "stiffness", Value::from(edit.stiffness));
            }
            if value_of(t, "damping").unwrap_or(0.0) != edit.damping {
                set(t, "damping", Value::from(edit.damping));
            }
            // Absent, the rest length is the anchors' distance at t = 0.
            let given = value_of(t, "rest_length").or_else(|| {
                let anchors = t.get("anchors")?.as_array()?;
                let ends: Vec<Vec<f64>> = anchors
                    .iter()
                    .map(|a| a.as_array().map(|a| a.iter().filter_map(number).collect()))
                    .collect::<Option<_>>()?;
                let [a, b] = &ends[..] else { return None };
                Some(
                    a.iter()
                        .zip(b)
                        .map(|(x, y)| (x - y).powi(2))
                        .sum::<f64>()
                        .sqrt(),
                )
            });
            if given != Some(edit.rest_length) {
                set(t, "rest_length", Value::from(edit.rest_length));
            }
        }
        for edit in &self.joints {
            let t = table(doc, "joint", &edit.name)?;
            if let Some([lo, hi]) = edit.limits {
                let close = |file: Vec<f64>| {
                    file.len() == 2
                        && (file[0] - lo).abs() <= 1e-9 * lo.abs()
                        && (file[1] - hi).abs() <= 1e-9 * hi.abs()
                };
                if !numbers(t.get("limits")).is_some_and(close) {
                    set(t, "limits", Value::Array([lo, hi].into_iter().collect()));
                }
            }
            if let Some((speed, max)) = edit.motor {
                let bound = if edit.hinge {
                    "max_torque"
                } else {
                    "max_force"
                };
                if let Some(motor) = t.get_mut("motor").and_then(Item::as_table_like_mut) {
                    for (key, x) in [("speed", speed), (bound, max)] {
                        if motor.get(key).and_then(Item::as_value).and_then(number) != Some(x) {
                            set(motor, key, Value::from(x));
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The body values into `[body]` or the `body`-th `[[body]]`.
    fn write_body(
        &self,
        doc: &mut DocumentMut,
        body: usize,
        mesh_from: Option<&Path>,
    ) -> Result<(), String> {
        let body_table: &mut dyn TableLike = match doc.get_mut("body") {
            Some(Item::ArrayOfTables(bodies)) => bodies
                .get_mut(body)
                .map(|t| t as &mut dyn TableLike)
                .ok_or_else(|| format!("the scene file has no body number {}", body + 1))?,
            Some(item) => item.as_table_like_mut().ok_or("[body] is not a table")?,
            None => return Err("the scene file has no [body]".into()),
        };
        let masses = body_table
            .get("masses")
            .and_then(Item::as_array)
            .map(|a| a.iter().filter_map(number).collect::<Vec<f64>>());
        match masses {
            Some(masses) if !masses.is_empty() => {
                let ratio = self.mass / masses.iter().sum::<f64>();
                let scaled: Array = masses.iter().map(|m| m * ratio).collect();
                set(body_table, "masses", Value::Array(scaled));
                if body_table.contains_key("mass") {
                    set(body_table, "mass", Value::from(self.mass));
                }
            }
            _ => set(body_table, "mass", Value::from(self.mass)),
        }
        let size_keys: &[&str] = match self.size.len() {
            3 => &["size"],
            1 => &["radius"],
            2 => &["radius", "length"],
            _ => &[],
        };
        if size_keys == ["size"] {
            if numbers(body_table.get("size")) != Some(self.size.clone()) {
                set(
                    body_table,
                    "size",
                    Value::Array(self.size.iter().copied().collect()),
                );
            }
        } else {
            for (key, x) in size_keys.iter().zip(&self.size) {
                if body_table
                    .get(key)
                    .and_then(Item::as_value)
                    .and_then(number)
                    != Some(*x)
                {
                    set(body_table, key, Value::from(*x));
                }
            }
        }
        if numbers(body_table.get("position")).unwrap_or_else(|| vec![0.0; 3])
            != self.position.iter().copied().collect::<Vec<f64>>()
        {
            set(body_table, "position", vector(&self.position));
        }
        if file_orientation(body_table.get("orientation")) != Some(self.orientation) {
            let (axis, angle) = self
                .orientation
                .axis_angle()
                .map_or((Vector3::z(), 0.0), |(axis, angle)| {
                    (axis.into_inner(), angle)
                });
            let mut table = toml_edit::InlineTable::new();
            table.insert("axis", vector(&axis));
            table.insert("degrees", Value::from(angle.to_degrees()));
            set(body_table, "orientation", Value::InlineTable(table));
        }
        set(body_table, "velocity", vector(&self.velocity));
        body_table.remove("angular_velocity_body");
        set(
            body_table,
            "angular_velocity",
            vector(&self.angular_velocity),
        );
        if let Some(folder) = mesh_from {
            if let Some(file) = body_table.get("file").and_then(Item::as_str) {
                let path = Path::new(file);
                if path.is_relative() {
                    let absolute = std::path::absolute(folder.join(path))
                        .map_err(|e| format!("mesh `{file}`: {e}"))?;
                    set(
                        body_table,
                        "file",
                        Value::from(absolute.to_string_lossy().into_owned()),
                    );
                }
            }
        }
        Ok(())
    }
}

/// What the form calls each entry of [`SceneEdits::size`] for a body of this size.
pub fn size_names(size: &[f64]) -> &'static [&'static str] {
    match size.len() {
        3 => &["size x", "size y", "size z"],
        1 => &["radius"],
        2 => &["radius", "length"],
        _ => &[],
    }
}

/// A body's size as the form edits it (see [`SceneEdits::size`]).
fn size_of(body: &Body) -> Vec<f64> {
    if body.fixed {
        return Vec::new();
    }
    match &body.shape {
        // A box of mass points has its corners as points: 8 of them.
        Some(Shape::Box { half }) => (2.0 * half).iter().copied().collect(),
        Some(Shape::Ball { radius }) => vec![*radius],
        Some(Shape::Capsule {
            radius,
            half_length,
        })
        | Some(Shape::Cylinder {
            radius,
            half_length,
        }) => vec![*radius, 2.0 * half_length],
        _ => Vec::new(),
    }
}

/// The same body (same mass, same inertia model) at another size: a solid box or a box of
/// corner points, a solid ball or a shell, a solid cylinder or a tube, a capsule — the model
/// read off the inertia the body has (`I = ⅔ M r²` is a shell, `I_axis = M r²` a tube, a box
/// whose tensor is not the solid one's is its corners).
fn resized(body: &Body, size: &[f64]) -> Result<Body, crate::physics::BodyError> {
    let m = body.mass;
    let i = &body.inertia_body;
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
    match (&body.shape, size) {
        (Some(Shape::Box { half }), &[x, y, z]) => {
            let (a, b, c) = (2.0 * half.x, 2.0 * half.y, 2.0 * half.z);
            let solid = near(i[(0, 0)], m * (b * b + c * c) / 12.0)
                && near(i[(1, 1)], m * (a * a + c * c) / 12.0);
            let size = Vector3::new(x, y, z);
            if solid {
                Body::solid_box(size, m)
            } else {
                Body::box_of_corners(size, m)
            }
        }
        (Some(Shape::Ball { radius }), &[r]) => {
            Body::sphere(r, m, near(i[(0, 0)], 2.0 / 3.0 * m * radius * radius))
        }
        (Some(Shape::Cylinder { radius, .. }), &[r, l]) => {
            Body::cylinder(r, l, m, near(i[(1, 1)], m * radius * radius))
        }
        (Some(Shape::Capsule { .. }), &[r, l]) => Body::capsule(r, l, m),
        _ => Ok(body.clone()),
    }
}

/// A number as TOML holds it (an integer counts).
fn number(v: &Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

/// An array of numbers as TOML holds it (None: absent, or not all numbers).
fn numbers(item: Option<&Item>) -> Option<Vec<f64>> {
    item?
        .as_array()?
        .iter()
        .map(number)
        .collect::<Option<Vec<f64>>>()
}

/// The orientation an `orientation` table gives, computed as the loader does (None: absent or
/// not one the loader reads; identity when absent is the caller's, see `write_body`).
fn file_orientation(item: Option<&Item>) -> Option<UnitQuaternion<f64>> {
    let Some(item) = item else {
        return Some(UnitQuaternion::identity());
    };
    let table = item.as_table_like()?;
    if let Some(q) = numbers(table.get("quaternion")) {
        let [w, x, y, z] = q[..] else { return None };
        return Some(UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)));
    }
    let axis = numbers(table.get("axis"))?;
    let [x, y, z] = axis[..] else { return None };
    let degrees = table
        .get("degrees")
        .and_then(Item::as_value)
        .and_then(number)?;
    let unit = Unit::try_new(Vector3::new(x, y, z), 1e-12)?;
    Some(UnitQuaternion::from_axis_angle(&unit, degrees.to_radians()))
}

/// `[x, y, z]` as a TOML array.
fn vector(v: &Vector3<f64>) -> Value {
    Value::Array(v.iter().copied().collect())
}

/// Sets `key` to `value`, keeping the comment and spacing around the old value if there was one.
fn set(table: &mut dyn TableLike, key: &str, mut value: Value) {
    match table.get_mut(key) {
        Some(Item::Value(old)) => {
            let decor = old.decor().clone();
            *value.decor_mut() = decor;
            *old = value;
        }
        _ => {
            table.insert(key, Item::Value(value));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::parse;

    const SOURCE: &str = r#"# A teacher's file: comments stay.
title = "Drop"

[scene]
dt = 0.01   # s
duration = 2.0
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.5, friction = 0.3 }

[body]
shape = "box"
size = [0.6, 0.3, 0.2]
mass = 2.0
position = [0.0, 1.5, 0.0]
orientation = { axis = [0.0, 0.0, 1.0], degrees = 30.0 }
angular_velocity_body = [0.0, 0.0, 2.0]

[[obstacle]]
type = "ground"
height = 0.0

[[page]]
at = 0.0
title = "Page"
text = """Two
lines."""
"#;

    fn edits() -> SceneEdits {
        SceneEdits {
            body: Some(0),
            dt: 0.005,
            restitution: Some(0.8),
            friction: Some(0.0),
            mass: 3.0,
            position: Vector3::new(0.0, 1.5, 0.0),
            orientation: UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians()),
            velocity: Vector3::new(1.0, 2.0, 0.0),
            angular_velocity: Vector3::new(0.5, 0.0, -1.0),
            gravity: Some(Vector3::new(0.0, -9.81, 0.0)),
            drag: None,
            cloths: Vec::new(),
            springs: Vec::new(),
            joints: Vec::new(),
            size: Vec::new(),
        }
    }

    #[test]
    fn the_written_file_loads_as_the_scene_applied_in_memory() {
        let path = Path::new("drop.toml");
        let lesson = parse(SOURCE, path).unwrap();
        let edits = edits();
        let text = edits.write_into(SOURCE, 0, None).unwrap();
        let written = parse(&text, path).unwrap_or_else(|e| panic!("{e}\n{text}"));
        let applied = edits.apply(&lesson.scene).unwrap();
        assert_eq!(SceneEdits::of(&written.scene).dt, 0.005);
        assert_eq!(written.scene.contact, applied.contact);
        let (a, b) = (&written.scene.bodies[0].initial, &applied.bodies[0].initial);
        assert!((a.linear_momentum - b.linear_momentum).norm() < 1e-12);
        assert!(
            (a.angular_momentum - b.angular_momentum).norm() < 1e-12,
            "{} vs {}",
            a.angular_momentum,
            b.angular_momentum
        );
        let inertia = (written.scene.bodies[0].body.inertia_body
            - applied.bodies[0].body.inertia_body)
            .norm();
        assert!(inertia < 1e-12, "inertia differs by {inertia}");
        // P₀ = M' v = 3 (1, 2, 0).
        assert_eq!(a.linear_momentum, Vector3::new(3.0, 6.0, 0.0));
        // Everything else is kept as written.
        assert!(
            text.starts_with("# A teacher's file: comments stay."),
            "{text}"
        );
        assert!(text.contains("dt = 0.005   # s"), "{text}");
        assert!(!text.contains("angular_velocity_body"), "{text}");
        assert_eq!(written.pages, lesson.pages);
        assert_eq!(written.title, "Drop");
    }

    #[test]
    fn point_masses_scale_to_the_new_total() {
        // Masses 1, 2, 1 (total 4) → total 2: each halves, 0.5, 1, 0.5.
        let source = r#"title = "Pair"
[scene]
dt = 0.01
integrator = "rk4"
[body]
shape = "points"
points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
masses = [1.0, 2.0, 1.0]
"#;
        let lesson = parse(source, Path::new("pair.toml")).unwrap();
        let edits = SceneEdits {
            mass: 2.0,
            ..SceneEdits::of(&lesson.scene)
        };
        let text = edits.write_into(source, 0, None).unwrap();
        assert!(text.contains("masses = [0.5, 1.0, 0.5]"), "{text}");
        let written = parse(&text, Path::new("pair.toml")).unwrap();
        assert_eq!(written.scene.bodies[0].body.mass, 2.0);
        let applied = edits.apply(&lesson.scene).unwrap();
        let diff = (written.scene.bodies[0].body.inertia_body
            - applied.bodies[0].body.inertia_body)
            .norm();
        assert!(diff < 1e-12, "{diff}");
    }

    /// A sheet alone; it takes the scene's particle integrator (no `integrator` of its own).
    const SHEET: &str = r#"# The explicit limit, by hand.
title = "Sheet"

[scene]
dt = 0.0014352   # 1.1 × 2/ω_max
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.4, friction = 0.5 }

[[cloth]]
name = "sheet"   # the only one
size = [1.0, 1.0]
count = [11, 11]
position = [0.0, 1.0, 0.0]
mass = 0.5
stretch = 2000.0
shear = 500.0
pinned = "edges"
"#;

    #[test]
    fn a_cloth_integrator_is_written_into_its_table_and_reads_back() {
        let path = Path::new("sheet.toml");
        let lesson = parse(SHEET, path).unwrap();
        let mut edits = SceneEdits::of(&lesson.scene);
        assert_eq!(edits.body, None, "a scene of cloths only");
        assert_eq!(edits.cloths[0].integrator, ClothIntegrator::SymplecticEuler);
        // Unchanged: the file is written as it was (no `integrator` added to the cloth).
        let same = edits.write_into(SHEET, 0, None).unwrap();
        assert_eq!(same, SHEET);
        edits.cloths[0].integrator = ClothIntegrator::ImplicitEuler;
        edits.dt = 0.013;
        let text = edits.write_into(SHEET, 0, None).unwrap();
        assert!(text.contains("integrator = \"implicit-euler\""), "{text}");
        assert!(text.contains("name = \"sheet\"   # the only one"), "{text}");
        assert!(text.contains("dt = 0.013   # 1.1 × 2/ω_max"), "{text}");
        assert!(!text.contains("[body]"), "{text}");
        let written = parse(&text, path).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(
            written.scene.cloths[0].integrator,
            ClothIntegrator::ImplicitEuler
        );
        assert_eq!(written.scene.dt, 0.013);
        let applied = edits.apply(&lesson.scene).unwrap();
        assert_eq!(applied.cloths, written.scene.cloths);
        // Back to the scene's own integrator: the cloth's key is rewritten, not dropped.
        edits.cloths[0].integrator = ClothIntegrator::SymplecticEuler;
        let back = edits.write_into(&text, 0, None).unwrap();
        let cloth_table = back.split("[[cloth]]").nth(1).unwrap();
        assert!(
            cloth_table.contains("integrator = \"symplectic-euler\""),
            "{back}"
        );
        assert_eq!(
            parse(&back, path).unwrap().scene.cloths[0].integrator,
            ClothIntegrator::SymplecticEuler
        );
    }

    #[test]
    fn values_the_loader_refuses_are_refused_here_too() {
        let lesson = parse(SOURCE, Path::new("drop.toml")).unwrap();
        for (bad, message) in [
            (
                SceneEdits {
                    restitution: Some(1.5),
                    ..SceneEdits::of(&lesson.scene)
                },
                "restitution must be between 0 and 1",
            ),
            (
                SceneEdits {
                    dt: 0.0,
                    ..SceneEdits::of(&lesson.scene)
                },
                "dt must be > 0",
            ),
            (
                SceneEdits {
                    mass: -1.0,
                    ..SceneEdits::of(&lesson.scene)
                },
                "mass must be > 0",
            ),
        ] {
            let error = bad.apply(&lesson.scene).unwrap_err();
            assert!(error.contains(message), "{error}");
            assert!(bad.write_into(SOURCE, 0, None).is_err());
        }
    }
}
