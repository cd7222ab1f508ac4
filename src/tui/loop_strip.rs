//! The loop strip: derive → forces → integrate → collide, the phase just run highlighted and
//! its formulas written out with the numbers it produced (for a collision, the impulse
//! arithmetic of each contact). With cloths, integrate also shows each cloth's particle step
//! (its integrator's formulas) and collide the particles' contacts with obstacles and bodies;
//! a scene of cloths only has no body phases to show.

use super::app::App;
use super::theme;
use crate::physics::{Effect, Phase, Response, Snapshot};
use crate::tables::{contact_label, number_plain};
use nalgebra::Vector3;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Widget};

const FORMULA: Style = theme::FORMULA;

/// A vector as `(x, y, z)` with the shared number formatter; a component below the round-off
/// of the vector's length prints as 0 (as in the panels, [`crate::tables::ROUND_OFF`]).
pub fn vector(v: &Vector3<f64>) -> String {
    let r = crate::tables::ROUND_OFF * v.norm();
    let c = |x: f64| number_plain(crate::tables::resolved(x, r));
    format!("({}, {}, {})", c(v.x), c(v.y), c(v.z))
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let s = &app.session.snapshot;
    let title = match s.phase {
        Some(p) => format!(" the loop — frame {}, after {} ", frame_number(s), p),
        None => " the loop — t = 0, nothing has run yet ".to_string(),
    };
    let block = Block::new()
        .borders(Borders::TOP)
        .border_style(theme::DIM)
        .title(Line::styled(title, theme::STRIP_TITLE));
    let inner = block.inner(area);
    block.render(area, buf);
    Paragraph::new(fit(lines(app), inner.width)).render(inner, buf);
}

/// The strip's lines before wrapping: the phase line, then the formulas with their numbers.
pub fn lines(app: &App) -> Vec<Line<'static>> {
    let s = &app.session.snapshot;
    let mut lines = vec![phase_line(s)];
    lines.extend(formulas(s));
    lines
}

/// Lines wider than `width` are wrapped at spaces (formula-aware, like lesson pages), so no
/// number or unit is cut at the pane's edge; the pieces lose their colours.
pub fn fit(lines: Vec<Line<'static>>, width: u16) -> Vec<Line<'static>> {
    let mut out = Vec::new();
    for line in lines {
        if line.width() <= usize::from(width) {
            out.push(line);
            continue;
        }
        let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        out.extend(
            super::lesson_pane::wrap_with(&text, usize::from(width), false)
                .into_iter()
                .map(Line::from),
        );
    }
    out
}

/// The frame the last phase belongs to (1-based).
fn frame_number(s: &Snapshot) -> u64 {
    match s.phase {
        Some(Phase::Derive) | Some(Phase::Forces) => s.step + 1,
        _ => s.step,
    }
}

fn phase_line(s: &Snapshot) -> Line<'static> {
    let mut spans = vec![Span::raw(" ")];
    for (i, phase) in Phase::ALL.iter().enumerate() {
        if i > 0 {
            spans.push(Span::styled(" → ", theme::DIM));
        }
        let style = if s.phase == Some(*phase) {
            theme::SELECTED
        } else if s.next_phase == *phase {
            theme::ACCENT
        } else {
            theme::SOFT
        };
        let marker = if s.phase == Some(*phase) {
            "■"
        } else if s.next_phase == *phase {
            "▸"
        } else {
            " "
        };
        spans.push(Span::styled(format!("{marker} {}", phase.name()), style));
    }
    spans.push(Span::styled(
        format!("      next: {}  (n)", s.next_phase),
        theme::DIM,
    ));
    Line::from(spans)
}

fn line(formula: impl Into<String>, numbers: impl Into<String>) -> Line<'static> {
    Line::from(vec![
        Span::raw("   "),
        Span::styled(formula.into(), FORMULA),
        Span::raw(numbers.into()),
    ])
}

fn formulas(s: &Snapshot) -> Vec<Line<'static>> {
    if s.bodies.is_empty() {
        return cloth_formulas(s);
    }
    let mut lines = match s.phase {
        None => vec![
            line("derive ", "I⁻¹ = R·Ibody⁻¹·Rᵀ, ω = I⁻¹·L, v = P/M        forces  F and τ of the declared effects"),
            line("integrate ", format!(
                "one {} step of (x, orientation, P, L)   collide  {}",
                s.integrator.name(),
                s.contact_model.as_ref().map_or("no contact declared", |m| m.response.descriptor().brief)
            )),
            line("Press n to run one phase, → a whole frame, space to run; ? lists every key.", ""),
        ],
        Some(Phase::Derive) => vec![
            line(
                "I⁻¹ = R·Ibody⁻¹·Rᵀ",
                "   (the inertia panel; R from the orientation q)",
            ),
            line(
                "ω = I⁻¹·L",
                format!(" = {} rad/s", vector(&s.angular_velocity)),
            ),
            line(
                "v = P/M",
                format!(
                    " = {} / {} = {} m/s",
                    vector(&s.linear_momentum),
                    number_plain(body_mass(s)),
                    vector(&s.velocity)
                ),
            ),
        ],
        Some(Phase::Forces) => forces(s),
        Some(Phase::Integrate) => integrate(s),
        Some(Phase::Collide) => collide(s),
    };
    // The cloths' particle step (integrate: under the body's method, before its numbers, so
    // that a short strip shows both methods) and contacts (collide, after the body's).
    match s.phase {
        Some(Phase::Integrate) => {
            let at = lines.len().min(1);
            lines.splice(at..at, cloth_steps(s));
        }
        // With no rigid contact the cloths' counts come first: a short strip (80 × 24) then
        // shows the particles under the cube resting on its sheet.
        Some(Phase::Collide) if s.contacts.is_empty() => {
            let (formulas, counts) = cloth_contacts(s);
            lines.splice(0..0, counts);
            lines.extend(formulas);
        }
        Some(Phase::Collide) => {
            let (formulas, counts) = cloth_contacts(s);
            lines.extend(formulas.into_iter().chain(counts));
        }
        _ => {}
    }
    lines
}

/// The mass of the body the panels show.
fn body_mass(s: &Snapshot) -> f64 {
    s.bodies.get(s.body_index).map_or(0.0, |b| b.mass)
}

/// A scene of cloths only: derive and forces have no body to work on; integrate is the
/// particle step, collide the particles' contacts.
fn cloth_formulas(s: &Snapshot) -> Vec<Line<'static>> {
    match s.phase {
        None => vec![
            line(
                "no rigid body in this scene: ",
                "derive and forces have nothing to do; the particles' forces are found inside their step",
            ),
            line(
                "integrate ",
                "one step of every cloth's particle integrator        collide  particles against obstacles",
            ),
            line("Press n to run one phase, → a whole frame, space to run; ? lists every key.", ""),
        ],
        Some(Phase::Derive) | Some(Phase::Forces) => vec![line(
            "no rigid body: nothing to do in this phase",
            "   (the springs', gravity's and drag's forces on the particles are found inside the particle step, in integrate)",
        )],
        Some(Phase::Integrate) => cloth_steps(s),
        // The counts first, as beside a body with no rigid contact (`formulas`).
        Some(Phase::Collide) => {
            let (formulas, counts) = cloth_contacts(s);
            counts.into_iter().chain(formulas).collect()
        }
    }
}

/// Integrate: each cloth's particle step, its formulas and what it produced.
fn cloth_steps(s: &Snapshot) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    for view in &s.cloths {
        lines.push(line(
            format!("{}: ", crate::physics::cloth::label(&view.name)),
            format!(
                "{} on its {} free particles, h = dt = {} s   (f: springs, damping, effects)",
                view.integrator,
                view.particles - view.pinned,
                number_plain(s.dt)
            ),
        ));
        for formula in view.method.formula() {
            lines.push(line(format!("  {formula}"), ""));
        }
        if !s.bodies.is_empty() && s.contact_model.as_ref().is_some() {
            lines.push(line(
                "  before x moves: a particle headed into a body gets +J, the body −J, so that \
                 vₚ·n ≥ −gap/h (it ends on the surface)",
                "",
            ));
        }
        let [stopped, _] = view.obstacle_contacts;
        let obstacles = if s.obstacles_fixed().next().is_none() {
            String::new()
        } else {
            format!(", {stopped} stopped at an obstacle's surface")
        };
        lines.push(line(
            "  ",
            format!(
                "max speed = {} m/s, max stretch = {} %, T = {} J, U = {} J{obstacles}",
                number_plain(view.max_speed),
                number_plain(view.max_stretch_percent),
                number_plain(view.kinetic),
                number_plain(view.spring)
            ),
        ));
    }
    lines
}

/// Collide: each cloth's particles against obstacles (pushed out) and bodies (both ways):
/// the formulas, and a line of counts per cloth.
fn cloth_contacts(s: &Snapshot) -> (Vec<Line<'static>>, Vec<Line<'static>>) {
    let (mut lines, mut counts) = (Vec::new(), Vec::new());
    if s.cloths.is_empty() {
        return (lines, counts);
    }
    if s.contact_model.as_ref().is_none() {
        let none = "cloths: no contact declared: nothing to detect, the phase costs nothing";
        return (vec![line(none, "")], counts);
    }
    let (obstacles, bodies) = (s.obstacles_fixed().next().is_some(), !s.bodies.is_empty());
    // The response's particle law says its formulas (`collision::particle`).
    let [in_obstacle, in_body] = s
        .contact_model
        .as_ref()
        .map_or(Response::Impulse, |m| m.response)
        .particle()
        .formulas();
    if obstacles {
        lines.push(line(in_obstacle, ""));
    }
    if bodies {
        lines.push(line(in_body, ""));
    }
    for view in &s.cloths {
        let [_, pushed] = view.obstacle_contacts;
        let mut what = Vec::new();
        if obstacles {
            what.push(format!("{pushed} pushed out of obstacles"));
        }
        if bodies {
            what.push(match view.body_contacts {
                1 => "1 particle touching a body".to_string(),
                n => format!("{n} particles touching bodies"),
            });
        }
        if what.is_empty() {
            what.push("nothing to touch".to_string());
        }
        counts.push(line(
            format!("{}: ", crate::physics::cloth::label(&view.name)),
            what.join(", "),
        ));
    }
    (lines, counts)
}

fn forces(s: &Snapshot) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    let mass = body_mass(s);
    if s.effects.list().is_empty() {
        lines.push(line("no effects declared: F = 0, τ = 0", ""));
    }
    for effect in s.effects.list() {
        match *effect {
            Effect::Gravity(g) => lines.push(line(
                "gravity  F = M·g",
                format!(
                    " = {} · {} = {} N",
                    number_plain(mass),
                    vector(&g),
                    vector(&(g * mass))
                ),
            )),
            Effect::Drag { linear, angular } => lines.push(line(
                "drag  F −= k·v,  τ −= kₐ·ω",
                format!(
                    "   k = {}, kₐ = {}: −{}, −{}",
                    number_plain(linear),
                    number_plain(angular),
                    vector(&(s.velocity * linear)),
                    vector(&(s.angular_velocity * angular))
                ),
            )),
        }
    }
    lines.push(line(
        "F, τ",
        format!(
            " = {} N, {} N·m   (τ about the barycenter)",
            vector(&s.force),
            vector(&s.torque)
        ),
    ));
    let rate = s.integrator.descriptor().rate;
    lines.push(line(rate, ""));
    lines
}

fn integrate(s: &Snapshot) -> Vec<Line<'static>> {
    let method = s.integrator.descriptor().formula;
    vec![
        line(method, ""),
        line(
            "x, P",
            format!(
                " = {} m, {} kg·m/s   (dt = {} s)",
                vector(&s.position),
                vector(&s.linear_momentum),
                number_plain(s.dt)
            ),
        ),
        line(
            "L",
            format!(
                " = {} kg·m²/s,   ‖RᵀR−1‖ = {}",
                vector(&s.angular_momentum),
                number_plain(crate::tables::resolved(
                    s.orthonormality_error,
                    crate::tables::ROUND_OFF
                ))
            ),
        ),
    ]
}

fn collide(s: &Snapshot) -> Vec<Line<'static>> {
    let obstacles = s.obstacles_fixed().count();
    let bodies = s.bodies.len();
    if obstacles == 0 && bodies < 2 && s.cloths.is_empty() {
        return vec![line(
            "no obstacles declared: nothing to detect, the phase costs nothing",
            "",
        )];
    }
    if s.contacts.is_empty() {
        let mut what = match (obstacles, bodies) {
            // The deepest penetration beside it is measured on the shape; the solver may stop
            // a body short of, or slightly inside, a surface without a contact in this phase.
            (0, 1) => "no obstacle and one body: no rigid contact".to_string(),
            (n, 1) => format!("{n} obstacle(s), no contact this step"),
            (0, b) => format!("{b} bodies, no pair touching"),
            (n, b) => format!("{n} obstacle(s) and {b} bodies, nothing touching"),
        };
        // With cloths there is still work here (their particles' lines).
        if s.cloths.is_empty() {
            what.push_str(": nothing to do");
        }
        let lines = vec![line(
            what,
            format!("   (deepest penetration {} m)", number_plain(s.penetration)),
        )];
        return lines;
    }
    let model = s.contact_model.as_ref();
    let mut lines = Vec::new();
    let chosen = model.map_or(Response::Seed, |m| m.response);
    let response = chosen.descriptor();
    if response.impulses {
        let e = model.map_or(0.0, |m| m.restitution);
        let parameters = match chosen {
            Response::SoftStep(p) => format!(
                "   e = {}, hertz = {}, ζ = {}, n = {}",
                number_plain(e),
                number_plain(p.hertz),
                number_plain(p.damping_ratio),
                p.substeps
            ),
            _ => format!("   e = {}", number_plain(e)),
        };
        lines.push(line(
            if bodies > 1 {
                response.formula_bodies
            } else {
                response.formula
            },
            parameters,
        ));
        for c in s.contacts.iter().take(2) {
            lines.push(line(
                format!("{}:", contact_label(c, s, true)),
                format!(
                    " n = {}, uₙ = {}, k = {}, J = {} N·s",
                    vector(&c.normal),
                    number_plain(c.normal_velocity),
                    number_plain(c.denominator),
                    vector(&c.impulse)
                ),
            ));
        }
    } else {
        lines.push(line(response.formula, ""));
        for c in s.contacts.iter().take(2) {
            lines.push(line(
                format!("{}:", contact_label(c, s, true)),
                format!(
                    " d = {} m, n = {}, ΔP = −1.4·P = {} N·s",
                    number_plain(c.depth),
                    vector(&c.normal),
                    vector(&c.impulse)
                ),
            ));
        }
    }
    if s.contacts.len() > 2 {
        lines.push(line(
            format!("… and {} more contacts", s.contacts.len() - 2),
            "",
        ));
    }
    // A step that met the solver's work budget unconverged says so, with its residual.
    if let Some(text) = crate::tables::unconverged_text(&s.contact_report) {
        lines.push(Line::from(vec![Span::styled(
            format!(" {text}"),
            theme::NOTICE,
        )]));
    }
    lines
}
