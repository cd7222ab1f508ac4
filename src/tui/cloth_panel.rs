//! The cloth panel, one per cloth: the numbers of `walk`'s cloth table (`tables::cloth_panel`:
//! max stretch, kinetic and spring energy, max particle speed, the explicit limit next to the
//! dt in use, and with attachments the size of their force |F| and their error), then its contacts and what the limit means for its integrator — above it,
//! `symplectic-euler` diverges; `implicit-euler` is not bounded by it.

use super::panels::PanelView;
use super::theme;
use crate::physics::ClothView;
use crate::tables::{self, Panel, Row};
use ratatui::text::{Line, Span};

/// A cloth's panel as the app shows it: the rows of `tables::cloth_panel` that hold numbers,
/// under a shorter title and with `dt` on a row of its own (the panel column stays narrow:
/// it fits beside the drawing at 80 columns), and its text lines: size, contacts, the limit's
/// verdict.
pub fn panel(c: &ClothView, dt: f64) -> (Panel, Vec<String>) {
    let table = tables::cloth_panel(c, dt);
    let mut rows = Vec::new();
    for row in table.rows.into_iter().filter(|r| !r.cells.is_empty()) {
        // `2/ω_max, h*, dt` as two rows, so the panel fits beside the drawing at 80 columns.
        if let (Some(head), [a, b, dt]) = (row.label.strip_suffix(", dt"), row.cells.as_slice()) {
            rows.push(Row {
                label: head.to_string(),
                cells: vec![a.clone(), b.clone()],
                unit: row.unit,
            });
            rows.push(Row {
                label: "dt".to_string(),
                cells: vec![dt.clone()],
                unit: row.unit,
            });
        } else if row.cells.len() == 3 {
            // `F by N attached` (a vector): its size, so the panel fits at 80 columns (walk's
            // table has the components).
            rows.push(Row {
                label: format!("|{}", row.label.replacen(' ', "| ", 1)),
                cells: vec![tables::number(c.attach_force.norm())],
                unit: row.unit,
            });
        } else {
            rows.push(row);
        }
    }
    let [velocity_pass, position_pass] = c.obstacle_contacts;
    let text = vec![
        format!(
            "{} particles ({} pinned), {} springs",
            c.particles, c.pinned, c.springs
        ),
        format!("contacts with bodies: {}", c.body_contacts),
        format!("with obstacles: {velocity_pass} integrate, {position_pass} collide"),
        verdict(c, dt),
    ];
    (
        Panel {
            title: format!(
                "{} · {}",
                crate::physics::cloth::label(&c.name),
                c.integrator
            ),
            rows,
        },
        text,
    )
}

/// What dt against the explicit limit h* means for the cloth's integrator.
///
/// ```text
/// symplectic-euler: stable for dt < h*, diverges above (h* = 2/ω_max without damping)
/// implicit-euler:   stable at any dt (numerical damping grows with dt)
/// ```
pub fn verdict(c: &ClothView, dt: f64) -> String {
    let ratio = dt / c.explicit_limit;
    if !c.explicit {
        "implicit: not bounded by h*".to_string()
    } else if ratio >= 1.0 {
        format!("above the limit: dt = {ratio:.2} × h*")
    } else {
        format!("below the limit: dt = {ratio:.2} × h*")
    }
}

/// The panel's lines (with the compare world's numbers in compare mode) and its title.
pub fn lines(
    c: &ClothView,
    dt: f64,
    previous: Option<&ClothView>,
    compare: Option<(&ClothView, &str)>,
) -> (Vec<Line<'static>>, String) {
    let (panel, text) = panel(c, dt);
    let before = previous.map(|p| panel_of(p, dt));
    let ghost = compare.map(|(g, name)| (panel_of(g, dt), name));
    let mut lines = PanelView {
        panel: &panel,
        previous: before.as_ref(),
        compare: ghost.as_ref().map(|(p, name)| (p, *name)),
    }
    .lines();
    for t in text {
        let style = if t.starts_with("above the limit") {
            theme::ERROR
        } else {
            theme::DIM
        };
        lines.push(Line::from(vec![Span::raw(" "), Span::styled(t, style)]));
    }
    (lines, panel.title)
}

fn panel_of(c: &ClothView, dt: f64) -> Panel {
    panel(c, dt).0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(integrator: &'static str, explicit: bool) -> ClothView {
        ClothView {
            name: "sheet".into(),
            integrator,
            method: crate::physics::cloth::ClothIntegrator::from_name(integrator).unwrap(),
            grid: [3, 3],
            positions: vec![nalgebra::Vector3::zeros(); 9],
            velocities: vec![nalgebra::Vector3::zeros(); 9],
            pins: vec![true; 9],
            particles: 9,
            springs: 12,
            pinned: 8,
            max_stretch_percent: 0.0,
            kinetic: 0.0,
            spring: 0.0,
            max_speed: 0.0,
            stiffness_limit: 0.02,
            explicit_limit: 0.02,
            body_contacts: 0,
            obstacle_contacts: [0, 0],
            explicit,
            attached: 0,
            attach_force: nalgebra::Vector3::zeros(),
            attach_error: 0.0,
        }
    }

    #[test]
    fn the_verdict_says_above_the_limit_only_for_an_explicit_step_past_h_star() {
        // h* = 0.02 s: dt = 0.022 s is 1.1 × h*, dt = 0.018 s is 0.9 × h*.
        let explicit = view("symplectic-euler", true);
        assert_eq!(verdict(&explicit, 0.022), "above the limit: dt = 1.10 × h*");
        assert_eq!(verdict(&explicit, 0.018), "below the limit: dt = 0.90 × h*");
        let implicit = view("implicit-euler", false);
        assert_eq!(verdict(&implicit, 0.2), "implicit: not bounded by h*");
    }

    #[test]
    fn the_panel_keeps_the_numeric_rows_of_walks_table() {
        // walk's table: max stretch, T U, max speed, 2/ω_max h* dt (split in two rows), dt/h*,
        // and one text row (contacts with bodies) that the app shows as a text line.
        let (panel, text) = panel(&view("implicit-euler", false), 0.001);
        let labels: Vec<_> = panel.rows.iter().map(|r| r.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "max stretch",
                "T, U",
                "max speed",
                "2/ω_max, h*",
                "dt",
                "dt/h*"
            ]
        );
        assert_eq!(
            panel.rows[3].cells,
            [tables::number(0.02), tables::number(0.02)]
        );
        assert_eq!(panel.rows[4].cells, [tables::number(0.001)]);
        assert_eq!(text[0], "9 particles (8 pinned), 12 springs");
        assert_eq!(text[1], "contacts with bodies: 0");
    }
}
