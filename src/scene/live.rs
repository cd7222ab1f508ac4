//! Live numbers in page text: `{{QUANTITY}}` (the value at the page's `at`) and
//! `{{QUANTITY@T}}` (at time T, s), and the `predict = { quantity, at }` of a page.
//!
//! ```text
//! QUANTITY = BODY.NAME | NAME (the first body) | energy | Px | Py | Pz | t (the whole scene)
//! NAME     = x y z vx vy vz wx wy wz Lx Ly Lz speed kinetic potential energy t_contact
//! ```
//!
//! This module only reads the names and checks them against the scene's bodies; the values
//! come from simulating the scene ([`crate::live`]).

use std::ops::Range;

/// What a quantity measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Measure {
    /// Barycenter position component (0, 1, 2), m.
    Position(usize),
    /// Velocity component, m/s.
    Velocity(usize),
    /// Angular velocity component (world frame), rad/s.
    AngularVelocity(usize),
    /// Angular momentum component (world frame, about the barycenter), kg·m²/s.
    AngularMomentum(usize),
    /// |L|, kg·m²/s (the plot's `BODY.|L|`; not a page's name).
    AngularMomentumNorm,
    /// |v|, m/s.
    Speed,
    /// ½ M v·v + ½ ω·L, J.
    Kinetic,
    /// −M g·x, J.
    Potential,
    /// Kinetic + potential, J.
    Energy,
    /// The whole scene's energy (bodies, particles, springs), J.
    SceneEnergy,
    /// The whole scene's linear momentum component, kg·m/s.
    SceneMomentum(usize),
    /// The time of the step the value is read at, s.
    Time,
    /// The time of the body's first contact with an obstacle or another body (by then), s.
    ContactTime,
    /// Joint `j`'s position error, m (the plot's `JOINT.error`; not a page's name).
    JointError(usize),
}

impl Measure {
    /// The unit printed after the value.
    pub fn unit(self) -> &'static str {
        match self {
            Measure::Position(_) => "m",
            Measure::Velocity(_) | Measure::Speed => "m/s",
            Measure::AngularVelocity(_) => "rad/s",
            Measure::AngularMomentum(_) | Measure::AngularMomentumNorm => "kg·m²/s",
            Measure::Kinetic | Measure::Potential | Measure::Energy | Measure::SceneEnergy => "J",
            Measure::SceneMomentum(_) => "kg·m/s",
            Measure::Time | Measure::ContactTime => "s",
            Measure::JointError(_) => "m",
        }
    }

    /// Whether it describes the whole scene rather than a body.
    pub fn scene_wide(self) -> bool {
        matches!(
            self,
            Measure::SceneEnergy
                | Measure::SceneMomentum(_)
                | Measure::Time
                | Measure::JointError(_)
        )
    }
}

/// The per-body names, in the contract's order.
pub const BODY_NAMES: [&str; 17] = [
    "x",
    "y",
    "z",
    "vx",
    "vy",
    "vz",
    "wx",
    "wy",
    "wz",
    "Lx",
    "Ly",
    "Lz",
    "speed",
    "kinetic",
    "potential",
    "energy",
    "t_contact",
];

/// The scene-wide names.
pub const SCENE_NAMES: [&str; 5] = ["energy", "Px", "Py", "Pz", "t"];

fn body_measure(name: &str) -> Option<Measure> {
    let i = BODY_NAMES.iter().position(|n| *n == name)?;
    Some(match i {
        0..=2 => Measure::Position(i),
        3..=5 => Measure::Velocity(i - 3),
        6..=8 => Measure::AngularVelocity(i - 6),
        9..=11 => Measure::AngularMomentum(i - 9),
        12 => Measure::Speed,
        13 => Measure::Kinetic,
        14 => Measure::Potential,
        15 => Measure::Energy,
        _ => Measure::ContactTime,
    })
}

fn scene_measure(name: &str) -> Option<Measure> {
    Some(match name {
        "energy" => Measure::SceneEnergy,
        "Px" => Measure::SceneMomentum(0),
        "Py" => Measure::SceneMomentum(1),
        "Pz" => Measure::SceneMomentum(2),
        "t" => Measure::Time,
        _ => return None,
    })
}

/// A quantity a page quotes: what, and of which body.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Quantity {
    /// The body's index in the scene (0 for a bare NAME; ignored when scene-wide).
    pub body: usize,
    pub measure: Measure,
    /// As written, e.g. `cube.y`.
    pub text: String,
}

/// Reads a quantity's name against the scene's body names; the error says what is accepted.
pub fn quantity(text: &str, bodies: &[String]) -> Result<Quantity, String> {
    let text = text.trim();
    let unknown = |what: &str| {
        format!(
            "unknown quantity `{what}`: expected BODY.NAME or NAME with NAME one of {}, \
             or the scene's {}",
            BODY_NAMES.join(" "),
            SCENE_NAMES.join(" ")
        )
    };
    if let Some((body, name)) = text.split_once('.') {
        let Some(index) = bodies.iter().position(|b| b == body) else {
            let known = if bodies.is_empty() {
                "this scene has no body".to_string()
            } else {
                format!("its bodies are {}", bodies.join(", "))
            };
            let hint = super::did_you_mean(body, bodies.iter().map(String::as_str))
                .map_or_else(String::new, |s| format!(" (did you mean `{s}`?)"));
            return Err(format!("unknown body `{body}` in `{text}`{hint}: {known}"));
        };
        let measure = body_measure(name).ok_or_else(|| unknown(text))?;
        return Ok(Quantity {
            body: index,
            measure,
            text: text.to_string(),
        });
    }
    if let Some(measure) = scene_measure(text) {
        return Ok(Quantity {
            body: 0,
            measure,
            text: text.to_string(),
        });
    }
    let measure = body_measure(text).ok_or_else(|| unknown(text))?;
    if bodies.is_empty() {
        return Err(format!(
            "`{text}` is a body's quantity and this scene has no body: use energy, Px, Py, Pz or t"
        ));
    }
    Ok(Quantity {
        body: 0,
        measure,
        text: text.to_string(),
    })
}

/// One `{{…}}` of a page's text.
#[derive(Debug, Clone, PartialEq)]
pub struct LiveNumber {
    /// Byte range of the whole `{{…}}` in the page's text.
    pub range: Range<usize>,
    pub quantity: Quantity,
    /// When, s: the page's `at` or the `@T` given.
    pub at: f64,
}

/// `predict = { quantity, at }`: the student guesses the quantity's value at `at`.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    pub quantity: Quantity,
    pub at: f64,
}

/// Every `{{…}}` of `text` (a page at `page_at` s); an error gives the byte offset in `text`
/// of the placeholder at fault and the message.
pub fn live_numbers(
    text: &str,
    page_at: f64,
    bodies: &[String],
) -> Result<Vec<LiveNumber>, (usize, String)> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(open) = text[from..].find("{{").map(|i| i + from) {
        let Some(close) = text[open + 2..].find("}}").map(|i| i + open + 2) else {
            return Err((
                open,
                "`{{` without its `}}`: write {{QUANTITY}} or {{QUANTITY@T}}".into(),
            ));
        };
        let inner = &text[open + 2..close];
        let (name, at) = match inner.split_once('@') {
            Some((name, time)) => {
                let t = time.trim().parse::<f64>().ok().filter(|t| t.is_finite());
                match t {
                    Some(t) if t >= 0.0 => (name, t),
                    _ => {
                        return Err((
                            open,
                            format!(
                                "`{{{{{inner}}}}}`: the time after @ must be a number of seconds ≥ 0, found `{}`",
                                time.trim()
                            ),
                        ))
                    }
                }
            }
            None => (inner, page_at),
        };
        let quantity = quantity(name, bodies).map_err(|e| (open, e))?;
        out.push(LiveNumber {
            range: open..close + 2,
            quantity,
            at,
        });
        from = close + 2;
    }
    Ok(out)
}

/// `text` with each live number replaced by what `value` gives for it.
pub fn fill(
    text: &str,
    numbers: &[LiveNumber],
    mut value: impl FnMut(&LiveNumber) -> String,
) -> String {
    let mut out = String::with_capacity(text.len());
    let mut from = 0;
    for n in numbers {
        out.push_str(&text[from..n.range.start]);
        out.push_str(&value(n));
        from = n.range.end;
    }
    out.push_str(&text[from..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bodies() -> Vec<String> {
        vec!["cube".to_string(), "ball".to_string()]
    }

    #[test]
    fn names_resolve_to_a_body_and_a_measure() {
        let q = quantity("ball.vy", &bodies()).unwrap();
        assert_eq!((q.body, q.measure), (1, Measure::Velocity(1)));
        // A bare body name is the first body's; a bare `energy` is the whole scene's.
        assert_eq!(
            quantity("Lz", &bodies()).unwrap().measure,
            Measure::AngularMomentum(2)
        );
        assert_eq!(
            quantity("energy", &bodies()).unwrap().measure,
            Measure::SceneEnergy
        );
        assert_eq!(
            quantity("cube.energy", &bodies()).unwrap().measure,
            Measure::Energy
        );
        assert_eq!(quantity("t", &[]).unwrap().measure, Measure::Time);
    }

    #[test]
    fn unknown_names_and_bodies_are_refused_with_what_is_accepted() {
        let e = quantity("cube.height", &bodies()).unwrap_err();
        assert!(
            e.contains("unknown quantity `cube.height`") && e.contains("speed"),
            "{e}"
        );
        let e = quantity("cub.y", &bodies()).unwrap_err();
        assert!(
            e.contains("unknown body `cub`") && e.contains("did you mean `cube`"),
            "{e}"
        );
        let e = quantity("y", &[]).unwrap_err();
        assert!(e.contains("no body"), "{e}");
    }

    #[test]
    fn placeholders_are_found_with_their_times_and_filled() {
        let text = "y = {{cube.y}} then {{ y@1.5 }} and {{t}}.";
        let n = live_numbers(text, 0.25, &bodies()).unwrap();
        assert_eq!(n.len(), 3);
        assert_eq!((n[0].at, n[1].at, n[2].at), (0.25, 1.5, 0.25));
        assert_eq!(&text[n[1].range.clone()], "{{ y@1.5 }}");
        let filled = fill(text, &n, |n| n.quantity.text.to_uppercase());
        assert_eq!(filled, "y = CUBE.Y then Y and T.");
    }

    #[test]
    fn a_broken_placeholder_names_its_offset() {
        let (at, e) = live_numbers("ok {{y@-1}}", 0.0, &bodies()).unwrap_err();
        assert_eq!(at, 3);
        assert!(e.contains("≥ 0"), "{e}");
        let (at, _) = live_numbers("a {{y", 0.0, &bodies()).unwrap_err();
        assert_eq!(at, 2);
    }
}
