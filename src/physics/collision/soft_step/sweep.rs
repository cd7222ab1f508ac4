//! `soft-step`'s passes over the rows: the warm start, the soft biased solve and the rigid
//! relax, one Gauss–Seidel sweep each (module doc of `soft_step`, "One soft row"; the
//! restitution is `bounce`'s). Each pass goes run by run (the rows between the same two
//! bodies), the two bodies' motions copied in once: the run's normal rows, then its
//! manifolds' friction (`patch`); a run without a B end takes a path that reads no B.
//!
//! A row's normal rate and impulse, with the row's precomputed `r×n`, `I⁻¹(r×n)` and 1/k:
//!
//! ```text
//! u = n·v_A + (r_A×n)·ω_A − n·v_B + (r_B×(−n))·ω_B
//! v_A += j n/M_A,  ω_A += j I_A⁻¹(r_A×n),  v_B −= j n/M_B,  ω_B += j I_B⁻¹(r_B×(−n))
//! ```

use super::bodies::Motion;
use super::patch::Patch;
use super::rows::{Row, Rows, Run};
use super::{Softness, MAX_PUSH};

/// The rate along the normal, A relative to B.
#[inline(always)]
pub(super) fn normal_rate(row: &Row, a: &Motion, b: &Motion, pair: bool) -> f64 {
    let mut u = row.normal.dot(&a.v) + row.rn[0].dot(&a.omega);
    if pair {
        u += -row.normal.dot(&b.v) + row.rn[1].dot(&b.omega);
    }
    u
}

/// Applies the impulse j along the normal.
#[inline(always)]
pub(super) fn push(row: &Row, j: f64, a: &mut Motion, b: &mut Motion, pair: bool) {
    a.v += row.normal * (j * a.inv_mass);
    a.omega += row.w_a * j;
    if pair {
        b.v += row.normal * (-j * b.inv_mass);
        b.omega += row.w_b * j;
    }
}

/// The first sub-step's warm start: every row's and manifold's impulse of last step applied
/// again, run by run.
#[inline(always)]
pub(super) fn warm_start(rows: &mut Rows, motions: &mut [Motion]) {
    let Rows {
        rows, runs, patches, ..
    } = rows;
    for run in runs.iter() {
        let mut a = motions[run.a];
        let mut b = run.b.map_or_else(Motion::default, |i| motions[i]);
        let pair = run.b.is_some();
        for row in &rows[run.rows.clone()] {
            push(row, row.lambda, &mut a, &mut b, pair);
        }
        for p in &patches[run.patches.clone()] {
            p.push(p.lambda, &mut a, &mut b, pair);
        }
        motions[run.a] = a;
        if let Some(i) = run.b {
            motions[i] = b;
        }
    }
}

/// One run's rows, solved in order with its two motions, then its manifolds' friction (the
/// scalar sweep, `lanes` takes the runs in its schedule): the soft, biased solve (`biased`)
/// or the rigid relax.
#[inline(always)]
pub(super) fn solve_run(
    run: &Run,
    (rows, patches): (&mut [Row], &mut [Patch]),
    motions: &mut [Motion],
    friction: f64,
    h: f64,
    biased: bool,
) {
    let mut a = motions[run.a];
    match run.b {
        Some(i) => {
            let mut b = motions[i];
            for row in &mut rows[run.rows.clone()] {
                solve::<true>(row, &run.soft, &mut a, &mut b, h, biased);
            }
            run_friction::<true>(run, (rows, patches), (&mut a, &mut b), friction);
            motions[i] = b;
        }
        None => {
            let mut b = Motion::default();
            for row in &mut rows[run.rows.clone()] {
                solve::<false>(row, &run.soft, &mut a, &mut b, h, biased);
            }
            run_friction::<false>(run, (rows, patches), (&mut a, &mut b), friction);
        }
    }
    motions[run.a] = a;
}

/// The friction of `run`'s manifolds, after its normal rows (none when μ = 0).
#[inline(always)]
pub(super) fn run_friction<const PAIR: bool>(
    run: &Run,
    (rows, patches): (&[Row], &mut [Patch]),
    (a, b): (&mut Motion, &mut Motion),
    friction: f64,
) {
    if friction > 0.0 {
        for p in &mut patches[run.patches.clone()] {
            p.solve::<PAIR>(rows, a, b, friction);
        }
    }
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

/// One row's soft (or relax) normal update (`PAIR`: the row has a B end).
#[inline(always)]
pub(super) fn solve<const PAIR: bool>(
    row: &mut Row,
    soft: &Softness,
    a: &mut Motion,
    b: &mut Motion,
    h: f64,
    biased: bool,
) {
    let pair = PAIR;
    let (bias, mass_scale, impulse_scale) = coefficients(row.gap, soft, h, biased);
    let u = normal_rate(row, a, b, pair);
    let j = -row.inv_k * mass_scale * (u + bias) - impulse_scale * row.lambda;
    let new = (row.lambda + j).max(0.0);
    let change = new - row.lambda;
    row.lambda = new;
    row.max_lambda = row.max_lambda.max(new);
    if change != 0.0 {
        push(row, change, a, b, pair);
    }
}
