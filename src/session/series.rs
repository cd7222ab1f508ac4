//! The energy series behind the energy graph: kinetic, potential, total and drift (the energy
//! ledger's remainder: E − E₀ less drag work and contacts) per frame,
//! thinned by halves when long, with axes that only ever grow (by doubling) so the graph does
//! not jump while it runs.

use crate::physics::snapshot::Methods;
use crate::physics::{Energy, Snapshot, World};

/// The energy the graph follows in a world now: the first body's, or with cloths the whole
/// scene's (bodies, particles and springs — a sheet's energy is what its lessons are about).
pub fn graphed_energy(world: &World) -> Energy {
    if Methods::of(world).cloths.is_empty() {
        world.energy_of(world.state())
    } else {
        world.total_energy()
    }
}

/// Points kept before the series is thinned to every other point.
const MAX_POINTS: usize = 4096;

/// One recorded frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub t: f64,
    pub kinetic: f64,
    pub potential: f64,
    pub total: f64,
    /// The numerical drift: E − E₀ − drag work − contact energy (the energy ledger's), J.
    pub drift: f64,
    /// The compare world's total energy, if compare mode is on.
    pub compare_total: Option<f64>,
}

/// A growing axis range `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    pub lo: f64,
    pub hi: f64,
}

impl Range {
    /// Grows (by doubling its span towards the side exceeded) until `x` is inside.
    pub fn include(&mut self, x: f64) {
        if !x.is_finite() {
            return;
        }
        for _ in 0..2048 {
            let span = self.hi - self.lo;
            if x > self.hi {
                self.hi += span;
            } else if x < self.lo {
                self.lo -= span;
            } else {
                return;
            }
        }
    }
}

/// The recorded energies and the graph's axes.
#[derive(Debug, Clone)]
pub struct EnergySeries {
    samples: Vec<Sample>,
    /// Record one frame in `stride`.
    stride: u64,
    pub time_axis: Range,
    pub energy_axis: Range,
    pub drift_axis: Range,
    /// Total energy at t = 0, J.
    initial_total: f64,
}

impl EnergySeries {
    /// A series starting with the snapshot at t = 0; `duration` (if any) sets the time axis.
    pub fn new(first: &Snapshot, duration: Option<f64>) -> EnergySeries {
        let (e, now) = if first.cloths.is_empty() {
            (first.initial_energy, first.energy)
        } else {
            (first.system.initial_energy, first.system.energy)
        };
        let values = [e.kinetic, e.potential, e.total, 0.0];
        let lo = values.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let scale = lo.abs().max(hi.abs()).max(1e-9);
        let pad = 0.1 * scale;
        let drift_scale = 1e-6 * scale;
        let t_end = duration.filter(|d| *d > 0.0).unwrap_or(100.0 * first.dt);
        let mut series = EnergySeries {
            samples: Vec::new(),
            stride: 1,
            time_axis: Range { lo: 0.0, hi: t_end },
            energy_axis: Range {
                lo: lo - pad,
                hi: hi + pad,
            },
            drift_axis: Range {
                lo: -drift_scale,
                hi: drift_scale,
            },
            initial_total: e.total,
        };
        series.record(first.step, first.dt, &now, first.energy_balance.drift, None);
        series
    }

    /// Records the energy and the drift after frame `step` (and the compare world's total
    /// energy), keeping one frame in `stride`.
    pub fn record(
        &mut self,
        step: u64,
        dt: f64,
        energy: &Energy,
        drift: f64,
        compare_total: Option<f64>,
    ) {
        let sample = Sample {
            t: step as f64 * dt,
            kinetic: energy.kinetic,
            potential: energy.potential,
            total: energy.total,
            drift,
            compare_total,
        };
        self.time_axis.include(sample.t);
        for x in [sample.kinetic, sample.potential, sample.total] {
            self.energy_axis.include(x);
        }
        if let Some(c) = sample.compare_total {
            self.energy_axis.include(c);
            self.drift_axis.include(c - self.initial_total);
        }
        self.drift_axis.include(sample.drift);
        if !step.is_multiple_of(self.stride) {
            return;
        }
        self.samples.push(sample);
        if self.samples.len() > MAX_POINTS {
            self.stride *= 2;
            let stride = self.stride;
            self.samples
                .retain(|x| ((x.t / dt).round() as u64).is_multiple_of(stride));
        }
    }

    /// Forgets samples after time `t` (stepping back); the axes stay as they were.
    pub fn truncate_after(&mut self, t: f64) {
        self.samples.retain(|x| x.t <= t + 1e-12);
    }

    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// The CSV of what the energy graph plots: `step,t,kinetic,potential,total,drift`, and
    /// `compare_total` in compare mode; every value printed in full (the shortest text that
    /// reads back to the same f64).
    pub fn csv(&self, dt: f64) -> String {
        let compare = self.samples.iter().any(|s| s.compare_total.is_some());
        let mut out = String::from("step,t,kinetic,potential,total,drift");
        if compare {
            out.push_str(",compare_total");
        }
        out.push('\n');
        for s in &self.samples {
            out.push_str(&format!(
                "{},{},{},{},{},{}",
                (s.t / dt).round() as u64,
                s.t,
                s.kinetic,
                s.potential,
                s.total,
                s.drift
            ));
            if compare {
                match s.compare_total {
                    Some(c) => out.push_str(&format!(",{c}")),
                    None => out.push(','),
                }
            }
            out.push('\n');
        }
        out
    }
}
