//! The settings form's state (key `e`): one text field per value of [`SceneEdits`] — restitution,
//! friction, mass, dt, and the body's initial velocity and angular velocity component by
//! component. Typing replaces the selected field's value (then appends); the values are read
//! and checked only when the form is applied or written, with the loader's own rules.

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
}

impl FieldKind {
    /// The field's label and unit.
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
        add(FieldKind::Mass, base.mass);
        add(FieldKind::Dt, base.dt);
        for i in 0..3 {
            add(FieldKind::Velocity(i), base.velocity[i]);
        }
        for i in 0..3 {
            add(FieldKind::AngularVelocity(i), base.angular_velocity[i]);
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
        }
    }

    /// The values typed, checked with the loader's rules; the error names the field. A field
    /// whose text was left as shown keeps its value exactly (not its rounded text).
    pub fn edits(&self) -> Result<SceneEdits, String> {
        let mut edits = self.base;
        for field in &self.fields {
            if field.text == tidy(self.base_value(field.kind)) {
                continue;
            }
            let label = field.kind.label().0;
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
        note("mass", b.mass, edits.mass, "kg");
        note("dt", b.dt, edits.dt, "s");
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
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
    use nalgebra::Vector3;

    fn base() -> SceneEdits {
        SceneEdits {
            body: 0,
            dt: 0.01,
            restitution: Some(0.5),
            friction: Some(0.3),
            mass: 2.0,
            velocity: Vector3::new(0.3, 1.0, 0.0),
            angular_velocity: Vector3::new(0.5, 1.0, 2.0),
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

    #[test]
    fn values_show_tidily() {
        assert_eq!(tidy(0.1 + 0.2), "0.3");
        assert_eq!(tidy(-0.0), "0");
        assert_eq!(tidy(1e-4), "0.0001");
        assert_eq!(tidy(2.0), "2");
    }
}
