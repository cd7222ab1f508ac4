//! `soft-step`'s passes over the rows: the warm start, the soft biased solve and the rigid
//! relax, one Gauss–Seidel sweep each (module doc of `soft_step`, "One soft row"; the
//! restitution is `bounce`'s). Each pass goes run by run (the rows between the same two
//! bodies), the two bodies' motions copied in once; a run without a B end takes a path that
//! reads no B.
//!
//! A row's normal rate and impulse, with the row's precomputed `r×n`, `I⁻¹(r×d)` and 1/k:
//!
//! ```text
//! u = n·v_A + (r_A×n)·ω_A − n·v_B + (r_B×(−n))·ω_B
//! v_A += j n/M_A,  ω_A += j I_A⁻¹(r_A×n),  v_B −= j n/M_B,  ω_B += j I_B⁻¹(r_B×(−n))
//! ```
//!
//! Friction reads the point's relative velocity `v_A + ω_A×r_A − v_B − ω_B×r_B` once for both
//! tangents and applies both at once.

use super::bodies::Motion;
use super::rows::{Row, Rows, Run, Totals};
use super::{clamp_disk, Softness, MAX_PUSH};

/// A pass over the rows: what it does to one row with the run's two motions (`PAIR`: the
/// run has a B end; else B is at rest and not read).
trait Pass {
    fn row<const PAIR: bool>(
        &mut self,
        row: &mut Row,
        totals: &mut Totals,
        soft: &Softness,
        a: &mut Motion,
        b: &mut Motion,
    );
}

/// Runs `pass` on every row, run by run, with the run's two motions copied in once (B: at
/// rest and not written back when the run has no B end).
#[inline(always)]
fn each_row<P: Pass>(rows: &mut Rows, motions: &mut [Motion], pass: &mut P) {
    let Rows { rows, totals, runs } = rows;
    for run in runs.iter() {
        let mut a = motions[run.a];
        let range = run.rows.clone();
        let pairs = rows[range.clone()].iter_mut().zip(&mut totals[range]);
        match run.b {
            Some(i) => {
                let mut b = motions[i];
                for (row, t) in pairs {
                    pass.row::<true>(row, t, &run.soft, &mut a, &mut b);
                }
                motions[i] = b;
            }
            None => {
                let mut b = Motion::default();
                for (row, t) in pairs {
                    pass.row::<false>(row, t, &run.soft, &mut a, &mut b);
                }
            }
        }
        motions[run.a] = a;
    }
}

/// The rate along the normal, A relative to B.
#[inline(always)]
pub(super) fn normal_rate(row: &Row, a: &Motion, b: &Motion, pair: bool) -> f64 {
    let mut u = row.normal.dot(&a.v) + row.rn[0].dot(&a.omega);
    if pair {
        u += -row.normal.dot(&b.v) + row.rn[1].dot(&b.omega);
    }
    u
}

/// Applies the impulse j along axis `i` (0: n, 1: t₁, 2: t₂).
#[inline(always)]
pub(super) fn push(row: &Row, i: usize, j: f64, a: &mut Motion, b: &mut Motion, pair: bool) {
    let d = if i == 0 {
        row.normal
    } else {
        row.tangents[i - 1]
    };
    a.v += d * (j * a.inv_mass);
    a.omega += row.w_a[i] * j;
    if pair {
        b.v += d * (-j * b.inv_mass);
        b.omega += row.w_b[i] * j;
    }
}

/// The first sub-step's warm start: every row's impulse of last step applied again.
#[inline(always)]
pub(super) fn warm_start(rows: &mut Rows, motions: &mut [Motion]) {
    struct Warm;
    impl Pass for Warm {
        #[inline(always)]
        fn row<const PAIR: bool>(
            &mut self,
            row: &mut Row,
            _: &mut Totals,
            _: &Softness,
            a: &mut Motion,
            b: &mut Motion,
        ) {
            push(row, 0, row.lambda, a, b, PAIR);
            push(row, 1, row.lambda_tangent[0], a, b, PAIR);
            push(row, 2, row.lambda_tangent[1], a, b, PAIR);
        }
    }
    each_row(rows, motions, &mut Warm);
}

/// One run's rows, solved in order with its two motions (the scalar sweep, `lanes` takes
/// the runs in its schedule): the soft, biased solve (`biased`) or the rigid relax.
#[inline(always)]
pub(super) fn solve_run(
    run: &Run,
    rows: &mut [Row],
    motions: &mut [Motion],
    friction: f64,
    h: f64,
    biased: bool,
) {
    let mut a = motions[run.a];
    let rows = &mut rows[run.rows.clone()];
    match run.b {
        Some(i) => {
            let mut b = motions[i];
            for row in rows {
                solve::<true>(row, &run.soft, &mut a, &mut b, friction, h, biased);
            }
            motions[i] = b;
        }
        None => {
            let mut b = Motion::default();
            for row in rows {
                solve::<false>(row, &run.soft, &mut a, &mut b, friction, h, biased);
            }
        }
    }
    motions[run.a] = a;
}

/// The bias, mass scale and impulse scale of a row at separation `s`: rigid with bias `s/h`
/// when speculative (s > 0), soft when `biased`, rigid without bias in the relax.
#[inline(always)]
pub(super) fn coefficients(s: f64, soft: &Softness, h: f64, biased: bool) -> (f64, f64, f64) {
    if s > 0.0 {
        (s / h, 1.0, 0.0)
    } else if biased {
        (
            (soft.bias_rate * s).max(-MAX_PUSH),
            soft.mass_scale,
            soft.impulse_scale,
        )
    } else {
        (0.0, 1.0, 0.0)
    }
}

/// One row's soft (or relax) normal update, then its friction in the disk `|λ_t| ≤ μ λ`
/// (`PAIR`: the row has a B end).
#[inline(always)]
pub(super) fn solve<const PAIR: bool>(
    row: &mut Row,
    soft: &Softness,
    a: &mut Motion,
    b: &mut Motion,
    friction: f64,
    h: f64,
    biased: bool,
) {
    let pair = PAIR;
    let (bias, mass_scale, impulse_scale) = coefficients(row.gap, soft, h, biased);
    let u = normal_rate(row, a, b, pair);
    let j = -row.inv_k[0] * mass_scale * (u + bias) - impulse_scale * row.lambda;
    let new = (row.lambda + j).max(0.0);
    let change = new - row.lambda;
    row.lambda = new;
    row.max_lambda = row.max_lambda.max(new);
    if change != 0.0 {
        push(row, 0, change, a, b, pair);
    }
    if friction > 0.0 {
        let bound = friction * row.lambda;
        let [t1, t2] = &row.tangents;
        let old = row.lambda_tangent;
        let mut slip = a.v + a.omega.cross(&row.lever);
        if pair {
            slip = slip - b.v - b.omega.cross(&row.lever_other);
        }
        let mut new = [
            old[0] - row.inv_k[1] * t1.dot(&slip),
            old[1] - row.inv_k[2] * t2.dot(&slip),
        ];
        clamp_disk(&mut new, bound);
        let step = [new[0] - old[0], new[1] - old[1]];
        if step != [0.0; 2] {
            // Both tangents at once: Δv_A = (t₁ s₁ + t₂ s₂)/M_A, Δω_A = I_A⁻¹(r_A×t₁) s₁ + …
            let p = t1 * step[0] + t2 * step[1];
            a.v += p * a.inv_mass;
            a.omega += row.w_a[1] * step[0] + row.w_a[2] * step[1];
            if pair {
                b.v -= p * b.inv_mass;
                b.omega += row.w_b[1] * step[0] + row.w_b[2] * step[1];
            }
            row.lambda_tangent = new;
        }
    }
}
