//! The settings form's state (key `e`): one text field per value of [`SceneEdits`] — restitution,
//! friction, mass, dt, the body's initial velocity and angular velocity component by
//! component, and each cloth's particle integrator by name. A scene of cloths only has no body
//! fields. Typing replaces the selected field's value (then appends); the values are read and
//! checked only when the form is applied or written, with the loader's own rules.

use crate::scene::edit::cloth_integrator;
use crate::scene::SceneEdits;

/// What a field holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldKind {
    Restitution,
    Friction,
    Mass,
    Dt,
    /// Initial velocity, component 0, 1 or 2 (x, y, z).
    Velocity(usize),
    /// Initial angular velocity (world frame), component 0, 1 or 2.
    AngularVelocity(usize),
    /// The particle integrator of cloth `i` (its index in [`SceneEdits::cloths`]), by name.
    ClothIntegrator(usize),
}

impl FieldKind {
    /// The field's label and unit (a cloth's field: see [`SettingsForm::label`]).
    pub fn label(self) -> (&'static str, &'static str) {
        match self {
            FieldKind::Restitution => ("restitution e", ""),
            FieldKind::Friction => ("friction μ", ""),
            FieldKind::Mass => ("mass M", "kg"),
            FieldKind::Dt => ("time step dt", "s"),
            FieldKind::Velocity(i) => (["velocity v₀ x", "v₀ y", "v₀ z"][i], "m/s"),
            FieldKind::AngularVelocity(i) => (
                ["angular velocity ω₀ x", "ω₀ y", "ω₀ z"][i],
                ["rad/s (world frame)", "rad/s", "rad/s"][i],
            ),
            FieldKind::ClothIntegrator(_) => ("cloth integrator", ""),
        }
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
        let mut fields = Vec::new();
        let mut add = |kind, value: f64| {
            fields.push(Field {
                kind,
                text: tidy(value),
            })
        };
        if let Some(e) = base.restitution {
            add(FieldKind::Restitution, e);
        }
        if let Some(mu) = base.friction {
            add(FieldKind::Friction, mu);
        }
        let body = base.body.is_some();
        if body {
            add(FieldKind::Mass, base.mass);
        }
        add(FieldKind::Dt, base.dt);
        if body {
            for i in 0..3 {
                add(FieldKind::Velocity(i), base.velocity[i]);
            }
            for i in 0..3 {
                add(FieldKind::AngularVelocity(i), base.angular_velocity[i]);
            }
        }
        for (i, cloth) in base.cloths.iter().enumerate() {
            fields.push(Field {
                kind: FieldKind::ClothIntegrator(i),
                text: cloth.integrator.name().into(),
            });
        }
        SettingsForm {
            base,
            fields,
            selected: 0,
            fresh: true,
            error: None,
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
        match field.kind {
            FieldKind::ClothIntegrator(i) => (
                format!(
                    "cloth {} integrator",
                    self.base.cloths.get(i).map_or("?", |c| c.name.as_str())
                ),
                "",
            ),
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
            FieldKind::Velocity(i) => b.velocity[i],
            FieldKind::AngularVelocity(i) => b.angular_velocity[i],
            FieldKind::ClothIntegrator(_) => f64::NAN,
        }
    }

    /// The values typed, checked with the loader's rules; the error names the field. A field
    /// whose text was left as shown keeps its value exactly (not its rounded text).
    pub fn edits(&self) -> Result<SceneEdits, String> {
        let mut edits = self.base.clone();
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
                FieldKind::Velocity(i) => edits.velocity[i] = value,
                FieldKind::AngularVelocity(i) => edits.angular_velocity[i] = value,
                FieldKind::ClothIntegrator(_) => {}
            }
        }
        match edits.problem() {
            Some(problem) => Err(problem),
            None => Ok(edits),
        }
    }

    /// What changed from the values the form started with, e.g. `mass 2 → 3 kg, dt 0.01 → 0.005 s`.
    pub fn changes(&self, edits: &SceneEdits) -> String {
        let mut parts = Vec::new();
        let mut note = |name: &str, old: f64, new: f64, unit: &str| {
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
            note("e", old, new, "");
        }
        if let (Some(old), Some(new)) = (b.friction, edits.friction) {
            note("μ", old, new, "");
        }
        if b.body.is_some() {
            note("mass", b.mass, edits.mass, "kg");
        }
        note("dt", b.dt, edits.dt, "s");
        for (i, axis) in ["x", "y", "z"]
            .into_iter()
            .enumerate()
            .filter(|_| b.body.is_some())
        {
            note(
                &format!("v₀{axis}"),
                b.velocity[i],
                edits.velocity[i],
                "m/s",
            );
            note(
                &format!("ω₀{axis}"),
                b.angular_velocity[i],
                edits.angular_velocity[i],
                "rad/s",
            );
        }
        for (old, new) in b.cloths.iter().zip(&edits.cloths) {
            if old.integrator != new.integrator {
                parts.push(format!(
                    "cloth {} {} → {}",
                    old.name,
                    old.integrator.name(),
                    new.integrator.name()
                ));
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
            velocity: Vector3::new(0.3, 1.0, 0.0),
            angular_velocity: Vector3::new(0.5, 1.0, 2.0),
            cloths: Vec::new(),
        }
    }

    #[test]
    fn typing_replaces_then_appends_and_the_values_read_back() {
        let mut form = SettingsForm::new(base());
        assert_eq!(form.fields.len(), 10);
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
        assert_eq!(form.fields.len(), 8);
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
                FieldKind::ClothIntegrator(0)
            ]
        );
        assert_eq!(form.label(&form.fields[3]).0, "cloth sheet integrator");
        assert_eq!(form.fields[3].text, "symplectic-euler");
        // Untouched, nothing changes (the absent body's zero mass is not checked).
        assert_eq!(form.edits().unwrap(), cloths_only());
        form.down();
        form.down(); // dt
        for c in "0.013".chars() {
            form.type_char(c);
        }
        form.down(); // the cloth's integrator
        for c in "implicit-euler".chars() {
            form.type_char(c);
        }
        let edits = form.edits().unwrap();
        assert_eq!(edits.cloths[0].integrator, ClothIntegrator::ImplicitEuler);
        assert_eq!(
            form.changes(&edits),
            "dt 0.01 → 0.013 s, cloth sheet symplectic-euler → implicit-euler"
        );
    }

    #[test]
    fn a_misspelt_integrator_is_refused_with_the_loaders_words() {
        let mut form = SettingsForm::new(cloths_only());
        form.selected = 3;
        for c in "implict-euler".chars() {
            form.type_char(c);
        }
        assert_eq!(
            form.edits().unwrap_err(),
            "cloth sheet integrator: unknown cloth integrator `implict-euler` (did you mean \
             `implicit-euler`?); valid cloth integrators: symplectic-euler, implicit-euler"
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
