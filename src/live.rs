//! The values of a lesson's live numbers and predictions: the scene simulated once, from
//! t = 0, to every time its pages quote (`{{QUANTITY@T}}`, a page's `at`, a `predict.at`).
//!
//! A time T is read at step `⌈T/dt⌉` (less a round-off margin), the step at which a run of the
//! app pauses for a page at T, so a page's numbers are the ones its panels show when it stops
//! there. Values come from the world's [`Snapshot`], like every panel; they print with the
//! panels' formatter ([`number_plain`]) and the quantity's unit.

use crate::physics::{BodyView, Snapshot, World};
use crate::scene::live::{LiveNumber, Measure, Quantity};
use crate::scene::{Lesson, Page};
use crate::tables::number_plain;
use std::collections::BTreeMap;

/// Most steps simulated to reach a quoted time (a time further away prints as unavailable).
pub const MAX_STEPS: u64 = 20_000_000;

/// The step a time is read at.
pub fn step_at(t: f64, dt: f64) -> u64 {
    (t / dt - 1e-9).ceil().max(0.0) as u64
}

/// A quoted quantity's value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    Number(f64),
    /// The simulation diverged before that time.
    Diverged,
    /// More than [`MAX_STEPS`] steps away.
    TooFar,
    /// `t_contact` read before the body touched anything.
    NoContactYet,
}

/// Every value a lesson's pages need, keyed by (step, quantity).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LiveValues {
    values: BTreeMap<(u64, Quantity), Value>,
    dt: f64,
    /// Still being simulated (the app computes them on a thread): no value yet.
    computing: bool,
}

/// Reads one quantity from a snapshot: body `q.body`'s from its [`BodyView`], scene-wide ones
/// from the totals (see [`value`]).
pub fn read(snapshot: &Snapshot, q: &Quantity) -> f64 {
    value(snapshot, q.body, q.measure)
}

/// The value of `measure` of body `body` (ignored when scene-wide) in a snapshot: the one
/// reader of every live number, prediction and plotted quantity, so a page, a panel and the
/// graph never disagree. NaN for a body or joint the snapshot does not hold.
///
/// ```text
/// x   v = P/M   ω = I⁻¹_world L   L   |L|   speed = |v|
/// kinetic = ½ M v·v + ½ ω·L   potential = −M g·x   energy = kinetic + potential
/// scene: energy (bodies, particles, springs), P = Σ P, t; joint: its position error
/// ```
pub fn value(snapshot: &Snapshot, body: usize, measure: Measure) -> f64 {
    let s = snapshot;
    let of = |f: fn(&BodyView) -> f64| s.bodies.get(body).map_or(f64::NAN, f);
    match measure {
        Measure::Position(i) => s.bodies.get(body).map_or(f64::NAN, |b| b.position[i]),
        Measure::Velocity(i) => s.bodies.get(body).map_or(f64::NAN, |b| b.velocity[i]),
        Measure::AngularVelocity(i) => s
            .bodies
            .get(body)
            .map_or(f64::NAN, |b| b.angular_velocity[i]),
        Measure::AngularMomentum(i) => s
            .bodies
            .get(body)
            .map_or(f64::NAN, |b| b.angular_momentum[i]),
        Measure::AngularMomentumNorm => of(|b| b.angular_momentum.norm()),
        Measure::Speed => of(|b| b.velocity.norm()),
        Measure::Kinetic => of(|b| b.energy.kinetic),
        Measure::Potential => of(|b| b.energy.potential),
        Measure::Energy => of(|b| b.energy.total),
        Measure::SceneEnergy => s.system.energy.total,
        Measure::SceneMomentum(i) => s.system.linear_momentum[i],
        Measure::Time => s.time,
        Measure::JointError(j) => s.joints.get(j).map_or(f64::NAN, |j| j.error),
        // Not a state quantity: `LiveValues::compute` tracks it while stepping.
        Measure::ContactTime => f64::NAN,
    }
}

/// A value as the panels show it: 0 at or below the round-off of its quantity (see
/// [`crate::tables::Resolution`]), so a page never quotes `1.0000e-10 kg·m/s` where its panel
/// shows 0 after a contact.
pub fn shown(snapshot: &Snapshot, q: &Quantity, x: f64) -> f64 {
    use crate::tables::{resolved, Resolution, ROUND_OFF};
    let s = snapshot;
    let r = Resolution::of(s);
    let resolution = match q.measure {
        Measure::Position(_) => ROUND_OFF * s.position.norm(),
        Measure::Velocity(_) | Measure::Speed => (ROUND_OFF * s.velocity.norm()).max(r.speed),
        Measure::AngularVelocity(_) => {
            (ROUND_OFF * s.angular_velocity.norm()).max(r.angular_velocity)
        }
        Measure::AngularMomentum(_) | Measure::AngularMomentumNorm => {
            (ROUND_OFF * s.angular_momentum.norm()).max(r.angular_momentum)
        }
        Measure::Kinetic | Measure::Potential | Measure::Energy | Measure::SceneEnergy => {
            ROUND_OFF * r.energy_scale
        }
        Measure::SceneMomentum(_) => (ROUND_OFF * s.system.linear_momentum.norm()).max(r.momentum),
        Measure::Time | Measure::ContactTime | Measure::JointError(_) => 0.0,
    };
    resolved(x, resolution)
}

impl LiveValues {
    /// No values yet: they are being simulated elsewhere; each prints as "(computing…)".
    pub fn computing() -> LiveValues {
        LiveValues {
            computing: true,
            ..LiveValues::default()
        }
    }

    /// Simulates `world` (at t = 0, with the settings to quote) to every time the lesson's
    /// pages need. A lesson without live numbers or predictions costs nothing.
    pub fn compute(lesson: &Lesson, world: World) -> LiveValues {
        let never = std::sync::atomic::AtomicBool::new(false);
        Self::compute_unless(lesson, world, &never).expect("never cancelled")
    }

    /// [`LiveValues::compute`], given up (None) as soon as `cancel` is set (checked at every
    /// step): for a thread whose values a newer setting has made stale.
    pub fn compute_unless(
        lesson: &Lesson,
        mut world: World,
        cancel: &std::sync::atomic::AtomicBool,
    ) -> Option<LiveValues> {
        let dt = world.dt();
        let mut wanted: BTreeMap<u64, Vec<Quantity>> = BTreeMap::new();
        for page in &lesson.pages {
            for n in &page.live {
                wanted
                    .entry(step_at(n.at, dt))
                    .or_default()
                    .push(n.quantity.clone());
            }
            if let Some(p) = &page.predict {
                wanted
                    .entry(step_at(p.at, dt))
                    .or_default()
                    .push(p.quantity.clone());
            }
        }
        let mut values = BTreeMap::new();
        // t_contact: each body's first contact time, watched only when a page quotes it.
        let watch_contacts = wanted
            .values()
            .flatten()
            .any(|q| q.measure == Measure::ContactTime);
        let mut first_contact: Vec<Option<f64>> = vec![None; world.states().len()];
        for (step, quantities) in wanted {
            if step <= MAX_STEPS {
                while world.step_count() < step && world.divergence().is_none() {
                    if cancel.load(std::sync::atomic::Ordering::Relaxed) {
                        return None;
                    }
                    world.step();
                    if watch_contacts {
                        let t = world.time();
                        // Touching: an impulse acted (a speculative row may hold one at
                        // depth ≤ 0) or the body overlaps.
                        let touching = world
                            .contacts()
                            .iter()
                            .filter(|c| c.depth > 0.0 || c.impulse.norm() > 0.0);
                        for c in touching {
                            for b in std::iter::once(c.body).chain(c.other_body()) {
                                if let Some(slot @ None) = first_contact.get_mut(b) {
                                    *slot = Some(t);
                                }
                            }
                        }
                    }
                }
            }
            let value_of = |world: &World, q: &Quantity| -> Value {
                if step > MAX_STEPS {
                    return Value::TooFar;
                }
                if world.divergence().is_some() {
                    return Value::Diverged;
                }
                if q.measure == Measure::ContactTime {
                    return first_contact
                        .get(q.body)
                        .copied()
                        .flatten()
                        .map_or(Value::NoContactYet, Value::Number);
                }
                let snapshot = world.snapshot_of(q.body);
                Value::Number(shown(&snapshot, q, read(&snapshot, q)))
            };
            for q in quantities {
                let v = value_of(&world, &q);
                values.insert((step, q), v);
            }
        }
        Some(LiveValues {
            values,
            dt,
            computing: false,
        })
    }

    /// The value of a quantity at time t (None if the lesson does not quote it there).
    pub fn value(&self, q: &Quantity, t: f64) -> Option<Value> {
        self.values.get(&(step_at(t, self.dt), q.clone())).copied()
    }

    /// A live number as printed: the panels' formatter, then the unit.
    pub fn text(&self, n: &LiveNumber) -> String {
        self.describe(&n.quantity, n.at)
    }

    /// The value of a quantity at time t as printed, or why there is none.
    pub fn describe(&self, q: &Quantity, t: f64) -> String {
        if self.computing {
            return "(computing…)".to_string();
        }
        text_of(self.value(q, t), q.measure)
    }

    /// A page's text with its live numbers filled in.
    pub fn page_text(&self, page: &Page) -> String {
        crate::scene::live::fill(&page.text, &page.live, |n| self.text(n))
    }

    /// The prediction's line: `predict: cube.y at t = 1 s → 0.250000 m`.
    pub fn prediction_line(&self, page: &Page) -> Option<String> {
        let p = page.predict.as_ref()?;
        Some(format!(
            "predict: {} at t = {} s → {}",
            p.quantity.text,
            number_plain(p.at),
            self.describe(&p.quantity, p.at)
        ))
    }
}

/// A value with its unit (or why there is none).
pub fn text_of(value: Option<Value>, measure: Measure) -> String {
    match value {
        Some(Value::Number(x)) => format!("{} {}", number_plain(x), measure.unit()),
        Some(Value::Diverged) => "(diverged before then)".to_string(),
        Some(Value::TooFar) => format!("(more than {MAX_STEPS} steps away)"),
        Some(Value::NoContactYet) => "(no contact yet)".to_string(),
        None => "(not computed)".to_string(),
    }
}

/// The relative error of a guess against the simulated value, `|guess − value| / |value|`
/// (the absolute error when the value is 0).
pub fn relative_error(guess: f64, value: f64) -> f64 {
    if value == 0.0 {
        (guess - value).abs()
    } else {
        (guess - value).abs() / value.abs()
    }
}
