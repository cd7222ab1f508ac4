//! The numeric panels, as text: one number formatter and one table builder shared by the
//! terminal app and `tumble walk`, so a panel and its text walkthrough never disagree.
//!
//! Numbers are fixed-width and deterministic: 6 decimals between 1e-3 and 1e3, otherwise
//! scientific with 5 significant digits; `-0` prints as `0`; NaN and ∞ are spelled out.
//!
//! A number below the round-off of its own quantity prints as 0 (and so is never highlighted
//! as changed): round-off is [`ROUND_OFF`] of the scale the panel shows (a vector's length, a
//! tensor's largest entry, 1 for q and ‖RᵀR−1‖, the scene's energy for E − E₀), and once a
//! contact has acted the contact solver's own tolerance for velocities, momenta and the
//! energy they carry (its sweeps stop within [`impulse::TOLERANCE`] m/s plus that fraction
//! of the speed):
//!
//! ```text
//! shown(x) = 0   if |x| ≤ ROUND_OFF · scale + solver tolerance (quantities the solver sets)
//! ROUND_OFF = 64 ε ≈ 1.4e-14        (a few dozen roundings of numbers of that size)
//! v: tol = TOLERANCE · (1 + v_scale),  P: M · tol,  E − E₀: |P| · tol
//! ω: tol / k with k = √(tr Ibody / 2M) (the radius of gyration),  L: max |I_ij| · tol / k
//! ```

use crate::physics::collision::impulse;
use crate::physics::joints::written::Measure;
use crate::physics::{Against, ClothView, Contact, Feature, JointView, Snapshot, SpringView};
use nalgebra::{Matrix3, Vector3};

/// Relative round-off of a panel's quantity: 64 ε ≈ 1.4e-14 of its scale.
pub const ROUND_OFF: f64 = 64.0 * f64::EPSILON;

/// `x` as a panel shows it: 0 when at or below `resolution` (the round-off of its quantity).
pub fn resolved(x: f64, resolution: f64) -> f64 {
    if x.abs() <= resolution {
        0.0
    } else {
        x
    }
}

/// Width of every formatted number, in characters.
pub const NUMBER_WIDTH: usize = 12;

/// A number, right-aligned in [`NUMBER_WIDTH`] characters.
pub fn number(x: f64) -> String {
    format!("{:>width$}", number_plain(x), width = NUMBER_WIDTH)
}

/// A number with no padding.
pub fn number_plain(x: f64) -> String {
    if x.is_nan() {
        return "NaN".to_string();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.to_string();
    }
    let magnitude = x.abs();
    let text = if magnitude == 0.0 || (1e-3..1e3).contains(&magnitude) {
        format!("{x:.6}")
    } else {
        format!("{x:.4e}")
    };
    // "-0.000000" (a tiny negative rounded away) prints as zero, without its sign.
    if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_string()
    } else {
        text
    }
}

/// Which frame vectors and tensors are shown in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frame {
    /// World frame (the default).
    World,
    /// Body frame: vectors as Rᵀ v, tensors as I_body and I⁻¹_body.
    Body,
}

impl Frame {
    /// The other frame.
    pub fn toggle(self) -> Frame {
        match self {
            Frame::World => Frame::Body,
            Frame::Body => Frame::World,
        }
    }

    /// "world" or "body".
    pub fn name(self) -> &'static str {
        match self {
            Frame::World => "world",
            Frame::Body => "body",
        }
    }
}

/// One labelled row of numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Label, e.g. `ω` or `I[0]`.
    pub label: String,
    /// Formatted numbers (each [`NUMBER_WIDTH`] wide).
    pub cells: Vec<String>,
    /// Unit, e.g. `rad/s` (may be empty).
    pub unit: &'static str,
}

/// A titled table of rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    pub title: String,
    pub rows: Vec<Row>,
}

/// A vector's row: a component below the round-off of the vector's length (or of `floor`,
/// an absolute resolution) prints as 0.
fn vector_row_at(label: &str, v: &Vector3<f64>, unit: &'static str, floor: f64) -> Row {
    let resolution = (ROUND_OFF * v.norm()).max(floor);
    Row {
        label: label.to_string(),
        cells: v.iter().map(|c| number(resolved(*c, resolution))).collect(),
        unit,
    }
}

fn vector_row(label: &str, v: &Vector3<f64>, unit: &'static str) -> Row {
    vector_row_at(label, v, unit, 0.0)
}

/// A scalar's row: 0 at or below `resolution`.
fn scalar_row_at(label: &str, x: f64, unit: &'static str, resolution: f64) -> Row {
    Row {
        label: label.to_string(),
        cells: vec![number(resolved(x, resolution))],
        unit,
    }
}

fn scalar_row(label: &str, x: f64, unit: &'static str) -> Row {
    scalar_row_at(label, x, unit, 0.0)
}

/// A tensor's rows: an entry below the round-off of its largest entry prints as 0.
fn matrix_rows(label: &str, m: &Matrix3<f64>, unit: &'static str) -> Vec<Row> {
    let resolution = ROUND_OFF * m.amax();
    let m = m.map(|x| resolved(x, resolution));
    (0..3)
        .map(|i| Row {
            label: if i == 0 {
                label.to_string()
            } else {
                String::new()
            },
            cells: (0..3).map(|j| number(m[(i, j)])).collect(),
            unit: if i == 0 { unit } else { "" },
        })
        .collect()
}

/// Every numeric panel of a snapshot, in display order:
/// state, inertia, angular velocity, forces, momentum, angular momentum, energy.
pub fn panels(s: &Snapshot, frame: Frame) -> Vec<Panel> {
    let rt = s.rotation.transpose();
    let to_frame = |v: &Vector3<f64>| match frame {
        Frame::World => *v,
        Frame::Body => rt * v,
    };
    let suffix = match frame {
        Frame::World => "",
        Frame::Body => " (body frame)",
    };
    let q = s.quaternion.quaternion();
    let tolerance = Resolution::of(s);
    let speed_tolerance = tolerance.speed;
    let momentum_scale = tolerance.momentum_scale;
    let state = Panel {
        title: "state".to_string(),
        rows: vec![
            vector_row("x", &s.position, "m"),
            Row {
                label: "q".to_string(),
                cells: [q.w, q.i, q.j, q.k]
                    .iter()
                    .map(|c| number(resolved(*c, ROUND_OFF)))
                    .collect(),
                unit: "w x y z",
            },
            scalar_row_at("‖RᵀR−1‖", s.orthonormality_error, "", ROUND_OFF),
        ],
    };
    let (inertia, inverse, inertia_label, inverse_label) = match frame {
        Frame::World => (s.inertia_world, s.inv_inertia_world, "I", "I⁻¹"),
        Frame::Body => (
            s.inertia_body,
            rt * s.inv_inertia_world * s.rotation,
            "Ibody",
            "Ibody⁻¹",
        ),
    };
    let mut inertia_rows = matrix_rows(inertia_label, &inertia, "kg·m²");
    inertia_rows.extend(matrix_rows(inverse_label, &inverse, "1/(kg·m²)"));
    let inertia_panel = Panel {
        title: format!("inertia tensor{suffix}"),
        rows: inertia_rows,
    };
    let angular_velocity = Panel {
        title: "angular velocity".to_string(),
        rows: vec![
            vector_row_at(
                "ω",
                &s.angular_velocity,
                "rad/s",
                tolerance.angular_velocity,
            ),
            vector_row_at(
                "ωbody",
                &s.angular_velocity_body,
                "rad/s",
                tolerance.angular_velocity,
            ),
            scalar_row_at(
                "|ω|",
                s.angular_velocity.norm(),
                "rad/s",
                tolerance.angular_velocity,
            ),
        ],
    };
    // F, τ: the declared effects'. Fc, τc: the contacts' (impulses over dt of the last collide
    // phase), shown while the body is in a contact.
    let mut force_rows = vec![
        vector_row("F", &to_frame(&s.force), "N"),
        vector_row("τ", &to_frame(&s.torque), "N·m"),
    ];
    if s.contacts.iter().any(|c| involves(c, s.body_index)) {
        force_rows.push(vector_row("Fc", &to_frame(&s.contact_force), "N"));
        force_rows.push(vector_row("τc", &to_frame(&s.contact_torque), "N·m"));
    }
    let forces = Panel {
        title: format!("force and torque{suffix}"),
        rows: force_rows,
    };
    let momentum = Panel {
        title: format!("linear momentum{suffix}"),
        rows: vec![
            vector_row_at(
                "P",
                &to_frame(&s.linear_momentum),
                "kg·m/s",
                tolerance.momentum,
            ),
            vector_row_at("v", &to_frame(&s.velocity), "m/s", speed_tolerance),
        ],
    };
    let angular_momentum = Panel {
        title: format!("angular momentum{suffix}"),
        rows: vec![
            vector_row_at(
                "L",
                &to_frame(&s.angular_momentum),
                "kg·m²/s",
                tolerance.angular_momentum,
            ),
            scalar_row_at(
                "|L|",
                s.angular_momentum.norm(),
                "kg·m²/s",
                tolerance.angular_momentum,
            ),
        ],
    };
    // The scene's energy (every body: contacts pass energy from one to another), E − E₀ split
    // by cause (the energy ledger); only the unbooked remainder is drift.
    let b = &s.energy_balance;
    let e = &s.system.energy;
    let several = s.bodies.len() > 1;
    let energy_scale = tolerance.energy_scale;
    let energy_resolution = ROUND_OFF * energy_scale + momentum_scale * speed_tolerance;
    let mut energy_rows = vec![Row {
        label: "K, V, E".to_string(),
        cells: [e.kinetic, e.potential, e.total]
            .iter()
            .map(|x| number(resolved(*x, ROUND_OFF * energy_scale)))
            .collect(),
        unit: "J",
    }];
    // Energy stored in cloth springs is part of E (not a cause of E − E₀): shown with E.
    if let Some(springs) = b.springs {
        energy_rows.push(scalar_row("U springs", springs, "J"));
    }
    energy_rows.push(scalar_row_at("E − E₀", b.change, "J", energy_resolution));
    for (label, value) in [
        ("  drag work", b.drag_work),
        ("  contacts", b.contacts),
        ("  motor", b.motor),
        ("  hand", b.hand),
    ] {
        if let Some(value) = value {
            energy_rows.push(scalar_row_at(label, value, "J", energy_resolution));
        }
    }
    energy_rows.push(scalar_row_at("  drift", b.drift, "J", energy_resolution));
    // drift/E₀ is the drift over the energy scale: its round-off is the drift's, relative.
    let relative_resolution = if b.drift != 0.0 {
        energy_resolution * (b.relative_drift / b.drift).abs()
    } else {
        0.0
    };
    energy_rows.push(scalar_row_at(
        "drift/E₀",
        b.relative_drift,
        "",
        relative_resolution,
    ));
    let energy = Panel {
        title: if several {
            "energy (all bodies)".to_string()
        } else {
            "energy".to_string()
        },
        rows: energy_rows,
    };
    let mut panels = vec![
        state,
        inertia_panel,
        angular_velocity,
        forces,
        momentum,
        angular_momentum,
        energy,
    ];
    if several {
        panels.push(system_panel(s));
    }
    panels
}

/// The round-off of a snapshot's quantities: at or below it a value prints as 0 (see the
/// module doc). Once a contact has acted, the contact solver's tolerance `tol` at the contact
/// points sets it for the velocities it changes: v and P directly, ω at the body's radius of
/// gyration k = √(tr Ibody / 2M) (ω_tol = tol / k), L through the inertia (I ω_tol).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolution {
    /// m/s: the contact solver's tolerance on v (0 before any contact).
    pub speed: f64,
    /// kg·m/s: on P.
    pub momentum: f64,
    /// rad/s: on ω.
    pub angular_velocity: f64,
    /// kg·m²/s: on L.
    pub angular_momentum: f64,
    /// The largest momentum shown, kg·m/s.
    pub momentum_scale: f64,
    /// J: the scale of the energy rows (their largest term, or Σ M|g||x|: positions carry
    /// a round-off of ε|x|).
    pub energy_scale: f64,
}

impl Resolution {
    pub fn of(s: &Snapshot) -> Resolution {
        // Once a contact has acted (energy booked to contacts, or touching now): before, the
        // solver has set nothing and only floating-point round-off applies.
        let contacts =
            s.energy_balance.contacts.is_some_and(|c| c != 0.0) || !s.contacts.is_empty();
        // M as P/v (0 at rest: then the speed alone sets the scale).
        let mass = if s.velocity.norm() > 0.0 {
            s.linear_momentum.norm() / s.velocity.norm()
        } else {
            0.0
        };
        let momentum_scale = s
            .linear_momentum
            .norm()
            .max(s.system.linear_momentum.norm());
        let speed_scale = if mass > 0.0 {
            momentum_scale / mass
        } else {
            s.velocity.norm()
        };
        let speed = if contacts {
            impulse::TOLERANCE * (1.0 + speed_scale)
        } else {
            0.0
        };
        let body_mass = s
            .bodies
            .get(s.body_index)
            .map(|b| b.mass)
            .filter(|m| m.is_finite() && *m > 0.0)
            .unwrap_or(0.0);
        let gyration = if body_mass > 0.0 {
            (s.inertia_body.trace() / (2.0 * body_mass)).sqrt()
        } else {
            0.0
        };
        let angular_velocity = if gyration > 0.0 {
            speed / gyration
        } else {
            0.0
        };
        let e = &s.system.energy;
        let e0 = &s.system.initial_energy;
        let energy_scale = [
            e.kinetic,
            e.potential,
            e.total,
            e0.kinetic,
            e0.potential,
            e0.total,
        ]
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
        .max(s.bodies.iter().map(|b| b.potential_scale).sum());
        Resolution {
            speed,
            momentum: mass * speed,
            angular_velocity,
            angular_momentum: s.inertia_world.amax() * angular_velocity,
            momentum_scale,
            energy_scale,
        }
    }
}

/// How many of [`panels`] describe the body the snapshot shows (the rest — energy, and the
/// system panel with several bodies — describe the whole scene).
pub const BODY_PANELS: usize = 6;

/// Each body's own energy (several bodies: a heavy body's share would swamp the others in the
/// scene's total), one row per body: K, V, E = K + V.
pub fn body_energy_panel(s: &Snapshot) -> Panel {
    // Round-off of the panel's scale: its largest term, or the largest −M g·x's terms.
    let scale = s.bodies.iter().fold(0.0_f64, |m, b| {
        [b.energy.kinetic, b.energy.potential, b.energy.total]
            .iter()
            .fold(m.max(b.potential_scale), |m, x| m.max(x.abs()))
    });
    Panel {
        title: "energy by body".to_string(),
        rows: s
            .bodies
            .iter()
            .map(|b| {
                let e = [b.energy.kinetic, b.energy.potential, b.energy.total];
                Row {
                    label: b.name.clone(),
                    cells: e
                        .iter()
                        .map(|x| number(resolved(*x, ROUND_OFF * scale)))
                        .collect(),
                    unit: "J (K, V, E)",
                }
            })
            .collect(),
    }
}

/// The whole scene (several bodies): total momenta, which contacts between bodies keep.
///
/// ```text
/// P = Σ P_b        L = Σ (x_b × P_b + L_b)   about the origin, world frame
/// ```
pub fn system_panel(s: &Snapshot) -> Panel {
    Panel {
        title: format!("system: {} bodies", s.bodies.len()),
        rows: vec![
            vector_row("P total", &s.system.linear_momentum, "kg·m/s"),
            vector_row("L about O", &s.system.angular_momentum, "kg·m²/s"),
        ],
    }
}

/// One cloth: its size, how stretched and how fast, its energies, the explicit limit next to
/// the dt in use, its contacts with bodies, and with `attach` the force its attached particles
/// take from their bodies (Σ λ_a / dt over the last step; the bodies take the opposite) and
/// their largest distance from their points.
///
/// ```text
/// max stretch = max over springs of (ℓ − ℓ₀)/ℓ₀ · 100 %
/// T = Σ ½ m_i |v_i|²      U = Σ ½ k (ℓ − ℓ₀)²
/// 2/ω_max: the undamped limit, h* = 4/(γ + √(γ² + 4ω²)) with damping (symplectic-euler
/// is stable for dt < h*; implicit-euler at any dt)
/// ```
pub fn cloth_panel(c: &ClothView, dt: f64) -> Panel {
    let row = |label: &str, cells: &[f64], unit| Row {
        label: label.to_string(),
        cells: cells.iter().map(|x| number(*x)).collect(),
        unit,
    };
    let text = |label: String| Row {
        label,
        cells: Vec::new(),
        unit: "",
    };
    Panel {
        title: format!(
            "cloth {}: {} particles ({} pinned), {} springs · {}",
            c.name, c.particles, c.pinned, c.springs, c.integrator
        ),
        rows: vec![
            row("max stretch", &[c.max_stretch_percent], "%"),
            row("T, U", &[c.kinetic, c.spring], "J"),
            row("max speed", &[c.max_speed], "m/s"),
            row(
                "2/ω_max, h*, dt",
                &[c.stiffness_limit, c.explicit_limit, dt],
                "s",
            ),
            row("dt/h*", &[dt / c.explicit_limit], ""),
            text(format!("contacts with bodies: {}", c.body_contacts)),
        ]
        .into_iter()
        .chain(
            (c.attached > 0)
                .then(|| {
                    [
                        vector_row(
                            &format!("F by {} attached", c.attached),
                            &c.attach_force,
                            "N",
                        ),
                        scalar_row_at("attach error", c.attach_error, "m", 1e-15),
                    ]
                })
                .into_iter()
                .flatten(),
        )
        .collect(),
    }
}

/// One joint: its error |C|, the reaction on its first body (averaged over the last step), its
/// anchors now (and axis or length).
///
/// ```text
/// |C| = |anchor A − anchor B|  (ball, hinge, fixed)      | |anchor A − anchor B| − ℓ |  (distance)
/// F, τ: the joint's Jᵀλ on body A, τ about A's barycenter
/// ```
pub fn joint_panel(j: &JointView) -> Panel {
    let other = j.bodies.1.as_deref().unwrap_or("world");
    let mut rows = vec![
        scalar_row("|C|", j.error, "m"),
        vector_row(&format!("F on {}", j.bodies.0), &j.force, "N"),
        vector_row(&format!("τ on {}", j.bodies.0), &j.torque, "N·m"),
        vector_row("anchor A", &j.anchors[0], "m"),
        vector_row("anchor B", &j.anchors[1], "m"),
    ];
    if let Some(axis) = &j.axis {
        rows.push(vector_row("axis", axis, ""));
    }
    if let Some(length) = j.length {
        rows.push(scalar_row("length", length, "m"));
    }
    rows.extend(drive_rows(j));
    Panel {
        title: format!("joint {}: {} · {} – {other}", j.name, j.kind, j.bodies.0),
        rows,
    }
}

/// A slider's travel (any travel), and a hinge's angle (any angle) when it has a limit or a
/// motor, with its rate; the limits; what the stops and the motor applied over the last step
/// (along the axis, on the first body).
fn drive_rows(j: &JointView) -> Vec<Row> {
    let Some((q, rate)) = j.coordinate else {
        return Vec::new();
    };
    let slider = j.measure == Some(Measure::Travel);
    if !slider && j.limits.is_none() && j.motor.is_none() {
        return Vec::new();
    }
    let (scale, unit, rate_unit, load, load_unit) = if slider {
        (1.0, "m", "m/s", "F", "N")
    } else {
        (1.0_f64.to_degrees(), "°", "rad/s", "τ", "N·m")
    };
    let (name, dot) = if slider {
        ("travel", "ds/dt")
    } else {
        ("angle", "dθ/dt")
    };
    let mut rows = vec![
        scalar_row(name, q * scale, unit),
        scalar_row(dot, rate, rate_unit),
    ];
    if let Some([lo, hi]) = j.limits {
        rows.push(Row {
            label: "limits".to_string(),
            cells: vec![number(lo * scale), number(hi * scale)],
            unit,
        });
        rows.push(scalar_row(
            &format!("limit {load}"),
            j.drive.limit,
            load_unit,
        ));
    }
    if let Some(motor) = j.motor {
        rows.push(Row {
            label: format!("motor {dot}, max"),
            cells: vec![number(motor.speed), number(motor.max)],
            unit: if slider { "m/s, N" } else { "rad/s, N·m" },
        });
        rows.push(scalar_row(
            &format!("motor {load}"),
            j.drive.motor,
            load_unit,
        ));
    }
    rows
}

/// The energy the joints' correction changed since t = 0 (numerical: an ideal joint does no
/// work), J.
pub fn correction_panel(s: &Snapshot) -> Panel {
    Panel {
        title: "joint correction".to_string(),
        rows: vec![scalar_row("work", s.joint_correction_work, "J")],
    }
}

/// One spring: its length against its rest length, Hooke's tension, its energy.
///
/// ```text
/// tension = k (|d| − ℓ₀)      V = ½ k (|d| − ℓ₀)²
/// ```
pub fn spring_panel(sp: &SpringView) -> Panel {
    let other = sp.bodies.1.as_deref().unwrap_or("world");
    Panel {
        title: format!("spring {}: {} – {other}", sp.name, sp.bodies.0),
        rows: vec![
            Row {
                label: "length, ℓ₀".to_string(),
                cells: vec![number(sp.length), number(sp.rest_length)],
                unit: "m",
            },
            scalar_row("tension", sp.tension, "N"),
            scalar_row("V", sp.potential, "J"),
        ],
    }
}

/// The contacts the last *collide* phase handled, and the deepest penetration now: one
/// block of rows per contact (depth, normal velocity before the response, impulse applied).
/// Each contact's obstacle is named by its type (the snapshot's fixed things).
pub fn contact_panel(s: &Snapshot) -> Panel {
    let mut rows = vec![scalar_row("penetration", s.penetration, "m")];
    if s.contacts.is_empty() {
        rows.push(Row {
            label: "no contact".to_string(),
            cells: Vec::new(),
            unit: "",
        });
    }
    if let Some(text) = unconverged_text(&s.contact_report) {
        rows.push(Row {
            label: text,
            cells: Vec::new(),
            unit: "",
        });
    }
    for c in s.contacts.iter().filter(|c| involves(c, s.body_index)) {
        rows.push(Row {
            label: contact_label(c, s, false),
            cells: Vec::new(),
            unit: "",
        });
        rows.push(scalar_row("  depth", c.depth, "m"));
        rows.push(scalar_row("  v·n", c.normal_velocity, "m/s"));
        rows.push(vector_row("  J", &c.impulse, "N·s"));
    }
    Panel {
        title: "contacts (last collide)".to_string(),
        rows,
    }
}

/// What a step that stopped unconverged says (None when it converged): why it stopped (its
/// work budget, 20 medians of the scene's steps so far, or its sweeps' cap) and the residual
/// it stopped at, against the tolerance.
pub fn unconverged_text(report: &impulse::StepReport) -> Option<String> {
    let residual = report.unconverged?;
    let why = if report.work >= report.budget {
        format!(
            "met its work budget ({} of {} row updates)",
            report.work, report.budget
        )
    } else {
        "reached its sweeps' cap".to_string()
    };
    Some(format!(
        "unconverged: the solver {why}, residual {} m/s (converged: < 1e-10)",
        number_plain(residual)
    ))
}

/// A panel as aligned plain-text lines (title first).
pub fn panel_text(panel: &Panel) -> Vec<String> {
    let label_width = panel
        .rows
        .iter()
        .map(|r| r.label.chars().count())
        .max()
        .unwrap_or(0);
    let mut lines = vec![panel.title.clone()];
    for row in &panel.rows {
        let pad = label_width - row.label.chars().count();
        let mut line = format!("  {}{} ", row.label, " ".repeat(pad));
        line.push_str(&row.cells.join(""));
        if !row.unit.is_empty() {
            line.push_str("  ");
            line.push_str(row.unit);
        }
        lines.push(line.trim_end().to_string());
    }
    lines
}

/// Whether a contact row involves body `index` (as A or as B).
pub fn involves(c: &Contact, index: usize) -> bool {
    c.body == index || c.other_body() == Some(index)
}

/// What touches what at a contact: `vertex 3 in ground 0` (the report's vertex test), or
/// `face-face: box1 on box 0`; `short` gives `v3 in ground` and `face-face box1/box2`.
pub fn contact_label(c: &Contact, s: &Snapshot, short: bool) -> String {
    let name = |i: usize| s.bodies.get(i).map_or("?", |b| b.name.as_str());
    let against = match c.against {
        Against::Obstacle(i) => {
            let kind = s.obstacles_fixed().nth(i).map_or("obstacle", |o| o.kind);
            if short {
                kind.to_string()
            } else {
                format!("{kind} {i}")
            }
        }
        Against::Body(j) => name(j).to_string(),
    };
    let feature = match c.feature {
        Feature::Vertex(v) if short => return format!("v{v} in {against}"),
        Feature::Vertex(v) => return format!("vertex {v} in {against}"),
        Feature::Geometry(f) => f.name(),
    };
    if short {
        format!("{feature} {}/{against}", name(c.body))
    } else {
        format!("{feature}: {} on {against}", name(c.body))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_fixed_width_and_no_negative_zero() {
        assert_eq!(number(0.0), "    0.000000");
        assert_eq!(number(-0.0), "    0.000000");
        assert_eq!(number(-1e-9), "  -1.0000e-9");
        assert_eq!(number(9.81), "    9.810000");
        assert_eq!(number(-123456.0), "   -1.2346e5");
        assert_eq!(number(f64::NAN), "         NaN");
        assert_eq!(number(f64::NEG_INFINITY), "        -inf");
        assert_eq!(number_plain(-0.0000001), "-1.0000e-7");
        // The widest texts (exponents within ±99) leave one space, so cells joined without
        // separators stay apart.
        assert_eq!(number(-999.9999994), " -999.999999");
        assert_eq!(number(-18941.203691), "   -1.8941e4");
        assert_eq!(number(-1.2345e-99), " -1.2345e-99");
    }

    #[test]
    fn an_unconverged_step_says_why_it_stopped_and_its_residual() {
        use crate::physics::collision::impulse::StepReport;
        let converged = StepReport {
            work: 100,
            rows: 10,
            budget: 200,
            unconverged: None,
        };
        assert_eq!(super::unconverged_text(&converged), None);
        let at_budget = StepReport {
            work: 3544,
            rows: 30,
            budget: 3520,
            unconverged: Some(3.3e-9),
        };
        assert_eq!(
            super::unconverged_text(&at_budget).unwrap(),
            format!(
                "unconverged: the solver met its work budget (3544 of 3520 row updates), residual {} m/s (converged: < 1e-10)",
                super::number_plain(3.3e-9)
            )
        );
        let capped = StepReport {
            budget: 600_000,
            ..at_budget
        };
        assert!(super::unconverged_text(&capped)
            .unwrap()
            .starts_with("unconverged: the solver reached its sweeps' cap, residual"));
    }
}
