//! The energy bars (a page's `panels = ["energy-bars"]`): their numbers are the energy
//! ledger's, and they add up to E₀ — checked on a falling body (K + V = E₀, K = ½ M (g t)²)
//! and on a block that friction stops (its kinetic energy booked to the contacts).

use crate::common::screen;
use tumble::tui::energy_bars::{bars, total};
use tumble::tui::App;

fn app(source: &str) -> App {
    crate::common::app_of(source, "energy-bars.toml")
}

/// The value of bar `label` now.
fn bar(app: &App, label: &str) -> Option<f64> {
    let s = &app.session.snapshot;
    bars(&s.system.energy, &s.energy_balance)
        .into_iter()
        .find(|(k, _)| k.label == label)
        .map(|(_, v)| v)
}

const FALL: &str = r#"
title = "A falling box"
[scene]
dt = 0.01
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
[body]
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 2.0
position = [0.0, 10.0, 0.0]
[[page]]
at = 0.0
title = "Energy"
text = "K grows as V falls."
panels = ["energy-bars"]
"#;

#[test]
fn a_falling_bodys_bars_trade_potential_for_kinetic_and_add_up_to_e0() {
    let mut app = app(FALL);
    app.step_frames(100);
    // t = 1 s: v = g t = 9.81 m/s, K = ½ M v² = 96.2361 J; V = −M g·x = M g y, y = 10 − ½ g t².
    let (m, g, t) = (2.0, 9.81, 1.0);
    let k = bar(&app, "kinetic K").unwrap();
    let v = bar(&app, "potential V").unwrap();
    assert!((k - 0.5 * m * (g * t) * (g * t)).abs() < 1e-9, "K = {k}");
    assert!(
        (v - m * g * (10.0 - 0.5 * g * t * t)).abs() < 1e-9,
        "V = {v}"
    );
    // The ledger's numbers, as the energy panel reads them.
    let s = &app.session.snapshot;
    assert_eq!(k, s.system.energy.kinetic);
    assert_eq!(v, s.system.energy.potential);
    // No spring, no contact, no drag: no such bar.
    for absent in ["springs U", "→ contacts", "→ drag", "→ motors"] {
        assert_eq!(bar(&app, absent), None, "{absent}");
    }
    // K + V = E₀ = M g y₀ = 196.2 J (rk4 is exact on constant gravity, up to round-off).
    let sum = total(&s.system.energy, &s.energy_balance);
    assert!((sum.initial - m * g * 10.0).abs() < 1e-12, "{sum:?}");
    assert!((sum.sum - sum.initial).abs() < 1e-9, "{sum:?}");
    assert!(sum.drift.abs() < 1e-9, "{sum:?}");
    // The panel shows them with the panels' numbers.
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("energy bars"), "{shown}");
    assert!(
        shown.contains("kinetic K") && shown.contains("96.236100"),
        "{shown}"
    );
    assert!(
        shown.contains("= E₀ 196.200000 + drift 0.000000 J"),
        "{shown}"
    );
}

const SLIDE: &str = r#"
title = "A block friction stops"
[scene]
dt = 0.001
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.0, friction = 0.5 }
[body]
shape = "box"
size = [0.4, 0.2, 0.4]
mass = 1.5
position = [0.0, 0.1, 0.0]
velocity = [2.0, 0.0, 0.0]
[[obstacle]]
type = "ground"
height = 0.0
[[page]]
at = 0.0
title = "Where the kinetic energy goes"
text = "Friction takes it: watch the contacts' bar grow as K shrinks."
panels = ["energy-bars"]
"#;

#[test]
fn a_sliding_blocks_kinetic_energy_is_booked_to_the_contacts() {
    let mut app = app(SLIDE);
    // μ g = 4.905 m/s²: it stops after v₀/(μ g) = 0.408 s; 0.6 s is past that.
    app.step_frames(600);
    let (m, v0) = (1.5, 2.0);
    let k = bar(&app, "kinetic K").unwrap();
    assert!(k < 1e-9, "stopped: K = {k}");
    let taken = bar(&app, "→ contacts").unwrap();
    // ½ M v₀² = 3 J went to the contacts (V changes by the block's settling only).
    let s = &app.session.snapshot;
    assert_eq!(taken, -s.energy_balance.contacts.unwrap());
    // Stopped where it started its slide's height: E − E₀ = −½ M v₀² = −3 J, all of it
    // booked to the contacts but the integrator's own drift (symplectic Euler's settling on
    // the ground: about −0.04 J here, shown as drift, never as a contact).
    let v = bar(&app, "potential V").unwrap();
    let v0_potential = m * 9.81 * 0.1;
    assert!(
        (v - v0_potential).abs() < 1e-9,
        "V {v} against V₀ {v0_potential}"
    );
    assert!((s.energy_balance.change + 0.5 * m * v0 * v0).abs() < 1e-9);
    let drift = s.energy_balance.drift;
    assert!(
        (taken - 3.0).abs() <= drift.abs() + 1e-9 && drift.abs() < 0.05,
        "contacts took {taken} J of ½ M v₀² = 3 J (drift {drift} J)"
    );
    let sum = total(&s.system.energy, &s.energy_balance);
    assert!(
        (sum.sum - (sum.initial + sum.drift)).abs() < 1e-9,
        "the total line: {sum:?}"
    );
    for (w, h) in [(80, 24), (120, 40)] {
        let shown = screen(&app, w, h);
        assert!(shown.contains("→ contacts"), "{w}x{h}\n{shown}");
        insta::assert_snapshot!(format!("energy_bars_slide_{w}x{h}"), shown);
    }
}
