//! The panels a page names, `panels = ["energy", "momentum"]`: the app shows them first at any
//! terminal size (with the panels of the page's live numbers), and the rest yields. In the
//! stage layout their rows join the essentials.

/// A panel a page can name, by the name it is written with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PagePanel {
    /// x, q, ‖RᵀR−1‖.
    State,
    /// I and I⁻¹.
    Inertia,
    /// ω, ωbody, |ω|.
    AngularVelocity,
    /// F, τ, and the contacts' Fc, τc.
    Forces,
    /// P, v.
    Momentum,
    /// L, |L|.
    AngularMomentum,
    /// The scene's energy and its ledger.
    Energy,
    /// Each body's kinetic, potential and total energy (several bodies).
    BodyEnergy,
    /// Total momenta of several bodies.
    System,
    /// The cloth panels.
    Cloth,
    /// The joint and spring panels.
    Joints,
    /// The stopwatch on simulated time (a page's `stopwatch` table, or keys `w` `o`).
    Stopwatch,
    /// The period timer (a page's `period` table, or key `T`).
    Period,
    /// The ruler (a page's `ruler` table, or keys `m` `M`).
    Ruler,
    /// The protractor (a page's `protractor` table, or keys `A` `V`).
    Protractor,
    /// The energy bars: kinetic, potential, springs, and what contacts, drag and motors took.
    EnergyBars,
}

impl PagePanel {
    /// Every name, in the order the panels are stacked.
    pub const ALL: [(PagePanel, &'static str); 16] = [
        (PagePanel::State, "state"),
        (PagePanel::Inertia, "inertia"),
        (PagePanel::AngularVelocity, "angular-velocity"),
        (PagePanel::Forces, "forces"),
        (PagePanel::Momentum, "momentum"),
        (PagePanel::AngularMomentum, "angular-momentum"),
        (PagePanel::Energy, "energy"),
        (PagePanel::BodyEnergy, "body-energy"),
        (PagePanel::System, "system"),
        (PagePanel::Cloth, "cloth"),
        (PagePanel::Joints, "joints"),
        (PagePanel::Stopwatch, "stopwatch"),
        (PagePanel::Period, "period"),
        (PagePanel::Ruler, "ruler"),
        (PagePanel::Protractor, "protractor"),
        (PagePanel::EnergyBars, "energy-bars"),
    ];

    /// The measuring tools (`measure`), in the order their panels are stacked.
    pub const TOOLS: [PagePanel; 4] = [
        PagePanel::Stopwatch,
        PagePanel::Period,
        PagePanel::Ruler,
        PagePanel::Protractor,
    ];

    /// One of the measuring tools.
    pub fn is_tool(self) -> bool {
        PagePanel::TOOLS.contains(&self)
    }

    /// The panel written `name`, or an error listing the names.
    pub fn from_name(name: &str) -> Result<PagePanel, String> {
        PagePanel::ALL
            .iter()
            .find(|(_, n)| *n == name)
            .map(|(p, _)| *p)
            .ok_or_else(|| {
                let names: Vec<&str> = PagePanel::ALL.iter().map(|(_, n)| *n).collect();
                format!("unknown panel `{name}` (panels: {})", names.join(", "))
            })
    }

    pub fn name(self) -> &'static str {
        PagePanel::ALL
            .iter()
            .find(|(p, _)| *p == self)
            .map_or("", |(_, n)| n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_reads_back_and_an_unknown_one_lists_them() {
        for (panel, name) in PagePanel::ALL {
            assert_eq!(PagePanel::from_name(name), Ok(panel));
            assert_eq!(panel.name(), name);
        }
        let e = PagePanel::from_name("energie").unwrap_err();
        assert!(e.contains("`energie`") && e.contains("body-energy"), "{e}");
    }
}
