//! Impacts among touching bodies: the two laws a scene can choose
//! (`contact = { response = "impulse", impacts = "propagate" | "simultaneous" }`).
//!
//! # Why simultaneous impact has no unique answer
//!
//! An impact is over in an instant, and rigid bodies say nothing about what happens inside
//! that instant. With one contact, Newton's law `u_n⁺ = −e u_n⁻` (or Poisson's: the
//! restitution impulse is e times the compression impulse, the same thing for one
//! frictionless contact) fixes the answer. With several contacts touching at once it does
//! not: five balls touching in a row, the first arriving at v₀, keep momentum and (at e = 1)
//! energy with the last ball leaving at v₀ *and* with infinitely many other outcomes. Which
//! one happens depends on how the compression wave travels through the bodies (their
//! stiffness, the exact gaps), which the rigid model has thrown away. A law of impact is an
//! assumption about that wave.
//!
//! # `simultaneous`: every contact of the step at once
//!
//! The inelastic impulses Λ ≥ 0 of all the step's contacts together minimise the kinetic
//! energy `K(Λ) = K₀ + Λ·u₀ + ½ Λᵀ A Λ` (A the contact-space inverse mass) subject to
//! `u = u₀ + A Λ ≥ 0`, `Λ·u = 0` (one linear complementarity problem); then Poisson's
//! restitution adds `e Λ` at the contacts that approached (stage 3 of [`super`]). It assumes
//! the bodies are infinitely stiff *together*: the wave crosses the whole touching cluster
//! before anything separates. A touching row then acts as one block: in a touching Newton's
//! cradle of five at e = 1 the first ball's impulse is shared by the whole row, the first
//! ball bounces back and the other four leave together (30 % of the energy lost).
//!
//! # `propagate`: the impulse travels from contact to contact (the default)
//!
//! Generalized Reflections (Smith, Kaufman, Vouga, Tamstorf, Grinspun, "Reflections on
//! simultaneous impact", SIGGRAPH 2012), realised with the same stages. Repeat, at most
//! [`IMPACT_ROUNDS`] times:
//!
//! ```text
//! active set  S = every pair of bodies (a body and an obstacle) with a touching row that
//!                 approaches:  u_n + g/dt < −u_t,  u_t = max(BOUNCE_STEPS·|g|·dt, tol)
//! impact      the stages on S's rows alone: Λ_S ≥ 0 minimising K with u_S ≥ 0, Λ_S·u_S = 0;
//!             friction in |λ_t| ≤ μ λ_n; Poisson restitution e Λ_S, K clamped to the round's
//!             start (the first round: K₀ less the push-out's lift)
//! ```
//!
//! until no row approaches; then the simultaneous solve on every row, for resting contact
//! (nothing approaches faster than u_t any more, so nothing bounces in it). A pair is one
//! impact: all its rows (a face's four corners) take part together, so a single body landing
//! has all its rows in the first round and comes out exactly as under `simultaneous`.
//! Contacts that merely touch (u_n ≈ 0) take no part in a round: the impulse reaches them in
//! the next round, through the bodies the round moved. So a touching cradle propagates ball by
//! ball: round k is one pair, `v_k, v_{k+1} ← v_{k+1}, v_k` at e = 1, and the last ball leaves
//! with v₀. Contacts that approach together are solved together, so a symmetric rack breaks
//! symmetrically (a sequence of single-pair impacts in some order would not).
//!
//! Each round keeps momentum (equal and opposite impulses) and never adds kinetic energy. At
//! e = 1 without friction a round keeps K exactly: with Λ* the inelastic impulses and
//! `w = u₀ + A Λ* ≥ 0`, `Λ*·w = 0`,
//!
//! ```text
//! K(2Λ*) = K₀ + 2Λ*·u₀ + 2Λ*ᵀAΛ* = K₀ + 2Λ*·w = K₀
//! ```
//!
//! (the reflection of the velocities across the active constraints). For 0 < e < 1 the rounds
//! shrink the approach speeds by about e per round; what is left after [`IMPACT_ROUNDS`] (a
//! counted, unconverged step: [`Counters::impacts_unconverged`]) goes to the final
//! simultaneous solve, which bounces it with e as today. At **e = 0 the propagation is skipped**
//! by definition: a perfectly plastic cradle would otherwise need infinitely many rounds
//! (v₀/2, v₀/4 … trickling back), converging to the simultaneous answer, every ball at v₀/5;
//! so both laws give the same result at e = 0, and resting contact is the same solve.
//!
//! [`Counters::impacts_unconverged`]: super::Counters::impacts_unconverged

use super::{friction, normal, Row, Settings, Stage};
use crate::physics::collision::solver_body::SolverBody;
use crate::physics::collision::warm::WarmCache;
use crate::physics::collision::Contact;
use nalgebra::Vector3;
use std::collections::HashSet;

/// At most this many impact rounds a step (a touching row of n bodies at e = 1 takes n − 1;
/// a rack of 15 balls about 20).
pub const IMPACT_ROUNDS: usize = 256;

/// How `impulse` answers an impact among touching bodies (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Impacts {
    /// The impulse travels from contact to contact (Generalized Reflections).
    #[default]
    Propagate,
    /// Every contact of the step at once (one complementarity problem).
    Simultaneous,
}

impl Impacts {
    /// Every law, the default first.
    pub const ALL: [Impacts; 2] = [Impacts::Propagate, Impacts::Simultaneous];

    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Impacts::Propagate => "propagate",
            Impacts::Simultaneous => "simultaneous",
        }
    }

    /// The law with this name.
    pub fn from_name(name: &str) -> Option<Impacts> {
        Impacts::ALL.into_iter().find(|i| i.name() == name)
    }

    /// Every valid name, comma-separated.
    pub fn names() -> String {
        Impacts::ALL.map(Impacts::name).join(", ")
    }
}

/// What the rounds did at one contact: its most negative approach in a round it took part
/// in, and the impulses it received over the rounds.
#[derive(Debug, Clone, Copy)]
pub(super) struct Record {
    pub approach: f64,
    pub impulse: Vector3<f64>,
    pub hit: bool,
}

/// The rounds' buffers, reused from step to step.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    pub records: Vec<Record>,
    pairs: HashSet<(usize, usize)>,
    index: Vec<usize>,
    rows: Vec<Row>,
    contacts: Vec<Contact>,
}

/// A pair of solver bodies (two bodies, or a body and an obstacle's static entry), whichever
/// way round its rows name it.
fn pair(c: &Contact) -> (usize, usize) {
    (c.body.min(c.other), c.body.max(c.other))
}

/// The speeds and energy the impact rounds work to.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bounds {
    /// A contact approaching faster than this (m/s, its bias counted) is an impact.
    pub threshold: f64,
    /// The sweeps' tolerance, m/s.
    pub tolerance: f64,
    /// K₀ less the push-out's lift, J: the first round may keep no more.
    pub kinetic_allowed: f64,
}

/// The impact rounds (module doc) on `contacts`, whose rows `rows` were prepared at the
/// start of the step, within `bounds`. Fills in `scratch.records`; returns whether the
/// rounds ended with nothing approaching faster than `bounds.threshold` (else
/// [`IMPACT_ROUNDS`] ran).
pub(super) fn rounds(
    settings: &Settings,
    contacts: &[Contact],
    rows: &[Row],
    previous: &WarmCache,
    bounds: Bounds,
    stage: &mut Stage,
    scratch: &mut Scratch,
) -> bool {
    let Bounds {
        threshold,
        tolerance,
        kinetic_allowed,
    } = bounds;
    let Scratch {
        records,
        pairs,
        index,
        rows: sub_rows,
        contacts: sub_contacts,
    } = scratch;
    records.clear();
    records.resize(
        contacts.len(),
        Record {
            approach: f64::INFINITY,
            impulse: Vector3::zeros(),
            hit: false,
        },
    );
    for round in 0..IMPACT_ROUNDS {
        pairs.clear();
        for (c, r) in contacts.iter().zip(rows.iter()) {
            if r.normal.axis.velocity(stage.motions) + r.normal.bias < -threshold {
                pairs.insert(pair(c));
            }
        }
        if pairs.is_empty() {
            return true;
        }
        stage.counters.impact_rounds += 1;
        index.clear();
        index.extend((0..contacts.len()).filter(|&i| pairs.contains(&pair(&contacts[i]))));
        sub_contacts.clear();
        sub_contacts.extend(index.iter().map(|&i| contacts[i]));
        sub_rows.clear();
        sub_rows.extend(
            sub_contacts
                .iter()
                .map(|c| normal::prepare(c, previous, settings.dt, stage.motions)),
        );
        // The first round pays the push-out's lift (as the simultaneous solve does); a later
        // round may not add kinetic energy to what the last one left.
        let allowed = if round == 0 {
            kinetic_allowed
        } else {
            stage.motions.iter().map(SolverBody::kinetic).sum()
        };
        super::stages(settings, sub_rows, sub_contacts, tolerance, allowed, stage);
        normal::store(sub_contacts, sub_rows);
        friction::store(sub_contacts, sub_rows, stage.tangents);
        for ((&i, c), r) in index.iter().zip(sub_contacts.iter()).zip(sub_rows.iter()) {
            let record = &mut records[i];
            record.approach = record.approach.min(r.approach);
            record.impulse += c.impulse;
            record.hit = true;
        }
    }
    stage.counters.impacts_unconverged += 1;
    false
}

/// Adds the rounds' impulses to each contact the final solve stored, and reports the
/// approach of the round that hit it (the loop strip's uₙ, and no warm start from a bounce).
pub(super) fn add(contacts: &mut [Contact], records: &[Record]) {
    for (c, r) in contacts.iter_mut().zip(records.iter()) {
        if r.hit {
            c.normal_velocity = r.approach;
            c.impulse += r.impulse;
        }
    }
}
