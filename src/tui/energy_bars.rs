//! The energy bars (a page names `energy-bars`): where the scene's energy is now and where it
//! went since t = 0, one horizontal bar each, read from the energy ledger's balance (the
//! numbers of the energy panel), with the total line:
//!
//! ```text
//! K + V + U + (taken by contacts) + (taken by drag) + (taken by motors) = E₀ + drift
//!
//! K, V, U     kinetic, gravitational potential (−M g·x), springs' stored energy, now
//! taken by    −ΔE_contacts, −W_drag, −W_motor: what each took out since t = 0 (a negative
//!             bar gave energy: a motor driving, a contact that pushed)
//! drift       what no physics books: the integrator's own (0 for an exact one)
//! ```
//!
//! The bars share one scale (the largest of them, the total and E₀), so the stores and the
//! sinks can be compared by eye as in PhET's energy charts; each number is printed beside
//! its bar with the panels' formatter.

use super::theme;
use crate::physics::{Energy, EnergyBalance, Snapshot};
use crate::tables::{number_plain, resolved, ROUND_OFF};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};

/// One bar: its label, its colour, and how it reads its value from the scene's energy and
/// the ledger's balance (None: the scene has no such store or sink, and shows no bar).
pub struct BarKind {
    pub label: &'static str,
    pub colour: Color,
    pub read: fn(&Energy, &EnergyBalance) -> Option<f64>,
}

/// The bars, top to bottom. A new store or sink of the ledger is one more line here.
pub const BARS: &[BarKind] = &[
    BarKind {
        label: "kinetic K",
        colour: theme::KINETIC,
        read: |e, _| Some(e.kinetic),
    },
    BarKind {
        label: "potential V",
        colour: theme::POTENTIAL,
        read: |e, b| Some(e.potential - b.springs.unwrap_or(0.0)),
    },
    BarKind {
        label: "springs U",
        colour: theme::SPRING,
        read: |_, b| b.springs,
    },
    BarKind {
        label: "→ contacts",
        colour: theme::CONTACT,
        read: |_, b| b.contacts.map(|c| -c),
    },
    BarKind {
        label: "→ drag",
        colour: Color::Gray,
        read: |_, b| b.drag_work.map(|w| -w),
    },
    BarKind {
        label: "→ motors",
        colour: Color::Yellow,
        read: |_, b| b.motor.map(|w| -w),
    },
    BarKind {
        label: "→ hand",
        colour: Color::LightYellow,
        read: |_, b| b.hand.map(|w| -w),
    },
];

/// Cells of the longest bar.
pub const BAR_WIDTH: usize = 20;

/// The bars of a scene's energy now: each present bar with its value, J.
pub fn bars(energy: &Energy, balance: &EnergyBalance) -> Vec<(&'static BarKind, f64)> {
    BARS.iter()
        .filter_map(|kind| (kind.read)(energy, balance).map(|v| (kind, v)))
        .collect()
}

/// The total line: the bars' sum, and E₀ and the drift it equals the sum of, J.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Total {
    pub sum: f64,
    pub initial: f64,
    pub drift: f64,
}

pub fn total(energy: &Energy, balance: &EnergyBalance) -> Total {
    Total {
        sum: bars(energy, balance).iter().map(|(_, v)| v).sum(),
        initial: energy.total - balance.change,
        drift: balance.drift,
    }
}

/// A bar of `cells` (fractional) cells from the zero column: eighths to the right, halves to
/// the left (the only left-aligned partial block is the right half, ▐).
fn bar_cells(cells: f64) -> String {
    if cells >= 0.0 {
        let eighths = (cells * 8.0).round() as usize;
        let mut s = "█".repeat(eighths / 8);
        if !eighths.is_multiple_of(8) {
            s.push(['▏', '▎', '▍', '▌', '▋', '▊', '▉'][eighths % 8 - 1]);
        }
        s
    } else {
        let halves = (-cells * 2.0).round() as usize;
        let mut s = String::new();
        if halves % 2 == 1 {
            s.push('▐');
        }
        s + &"█".repeat(halves / 2)
    }
}

/// The panel's lines (its title first) for a snapshot's whole scene.
pub fn lines(s: &Snapshot) -> Vec<Line<'static>> {
    let (energy, balance) = (&s.system.energy, &s.energy_balance);
    let bars = bars(energy, balance);
    let total = total(energy, balance);
    let values = bars.iter().map(|(_, v)| *v);
    let scale = values
        .clone()
        .chain([total.sum, total.initial])
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    // What the panels print as 0 prints as 0 here too.
    let shown = |x: f64| number_plain(resolved(x, ROUND_OFF * scale));
    let lo = values.clone().chain([total.sum]).fold(0.0_f64, f64::min);
    let hi = values.chain([total.sum]).fold(0.0_f64, f64::max);
    let per_joule = if hi > lo {
        BAR_WIDTH as f64 / (hi - lo)
    } else {
        0.0
    };
    // The zero column: room on its left for the most negative bar.
    let zero = ((-lo * per_joule).round() as usize).min(BAR_WIDTH);
    let label_width = BARS
        .iter()
        .map(|b| b.label.chars().count())
        .max()
        .unwrap_or(0);
    let row = |label: &str, value: f64, colour: Color| -> Line<'static> {
        let value = resolved(value, ROUND_OFF * scale);
        let cells = bar_cells(value * per_joule);
        let width = cells.chars().count();
        let (left, right) = if value < 0.0 {
            (zero.saturating_sub(width), BAR_WIDTH.saturating_sub(zero))
        } else {
            (zero, BAR_WIDTH.saturating_sub(zero + width))
        };
        Line::from(vec![
            Span::styled(format!(" {label:<label_width$} "), theme::LABEL),
            Span::raw(" ".repeat(left)),
            Span::styled(cells, Style::new().fg(colour)),
            Span::raw(" ".repeat(right)),
            Span::raw(format!(" {:>12}", shown(value))),
            Span::styled("  J", theme::DIM),
        ])
    };
    let mut out = vec![Line::styled(
        "energy bars (K + V + U + taken = E₀ + drift)",
        theme::TITLE,
    )];
    for (kind, value) in &bars {
        out.push(row(kind.label, *value, kind.colour));
    }
    out.push(row("total", total.sum, theme::TOTAL));
    out.push(Line::styled(
        format!(
            " {:<label_width$}  = E₀ {} + drift {} J",
            "",
            shown(total.initial),
            shown(total.drift)
        ),
        theme::DIM,
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_are_eighths_to_the_right_and_halves_to_the_left() {
        assert_eq!(bar_cells(2.5), "██▌");
        assert_eq!(bar_cells(0.125), "▏");
        assert_eq!(bar_cells(0.0), "");
        assert_eq!(bar_cells(-1.5), "▐█");
        assert_eq!(bar_cells(-2.0), "██");
    }
}
