//! The tests' own ODE solver, independent of tumble's integrators: Gragg–Bulirsch–Stoer
//! extrapolation, adaptive in its step, for the minimal-coordinate equations the study and
//! `walk --error` are checked against (the pendulum, the double pendulum, the spring, the free
//! top).
//!
//! ```text
//! modified midpoint over H in n substeps (h = H/n):
//!     z₀ = y,  z₁ = z₀ + h f(z₀),  z_{m+1} = z_{m−1} + 2h f(z_m),
//!     M(n) = ½ (z_n + z_{n−1} + h f(z_n))            error = Σ c_j h^{2j}  (even powers only)
//! Richardson (Neville) in h², n_k = 2k:
//!     T_{k,0} = M(n_k),  T_{k,j} = T_{k,j−1} + (T_{k,j−1} − T_{k−1,j−1}) / ((n_k/n_{k−j})² − 1)
//! accept the step when max_i |T_{k,k} − T_{k,k−1}|_i / (1 + |y_i|) ≤ tol (order 2k);
//! else, after K_MAX rows, halve H and retry; after an accepted step H grows by 1.5.
//! ```

/// Rows of the extrapolation table at most (order 2·K_MAX).
const K_MAX: usize = 9;

/// One modified-midpoint pass over `big` in `n` substeps.
fn midpoint<const N: usize>(
    f: &dyn Fn(&[f64; N]) -> [f64; N],
    y: &[f64; N],
    big: f64,
    n: usize,
) -> [f64; N] {
    let h = big / n as f64;
    let mut previous = *y;
    let k = f(y);
    let mut current = [0.0; N];
    for i in 0..N {
        current[i] = y[i] + h * k[i];
    }
    for _ in 1..n {
        let k = f(&current);
        let mut next = [0.0; N];
        for i in 0..N {
            next[i] = previous[i] + 2.0 * h * k[i];
        }
        previous = current;
        current = next;
    }
    let k = f(&current);
    let mut out = [0.0; N];
    for i in 0..N {
        out[i] = 0.5 * (current[i] + previous[i] + h * k[i]);
    }
    out
}

/// One extrapolated step over `big`: `Some(y(t + big))` when the table converged to `tol`.
fn step<const N: usize>(
    f: &dyn Fn(&[f64; N]) -> [f64; N],
    y: &[f64; N],
    big: f64,
    tol: f64,
) -> Option<[f64; N]> {
    let mut table: Vec<Vec<[f64; N]>> = Vec::with_capacity(K_MAX);
    for k in 0..K_MAX {
        let n_k = 2 * (k + 1);
        let mut row = vec![midpoint(f, y, big, n_k)];
        for j in 1..=k {
            let ratio = (n_k as f64 / (2 * (k - j + 1)) as f64).powi(2);
            let (a, b) = (row[j - 1], table[k - 1][j - 1]);
            let mut t = [0.0; N];
            for i in 0..N {
                t[i] = a[i] + (a[i] - b[i]) / (ratio - 1.0);
            }
            row.push(t);
        }
        if k >= 2 {
            let (best, before) = (row[k], row[k - 1]);
            let error = (0..N)
                .map(|i| (best[i] - before[i]).abs() / (1.0 + y[i].abs()))
                .fold(0.0, f64::max);
            if error <= tol {
                return Some(best);
            }
        }
        table.push(row);
    }
    None
}

/// y(t) from y(0) = `y0`, each step's estimated error at most `tol` (relative to 1 + |y|).
pub fn solve<const N: usize>(
    f: &dyn Fn(&[f64; N]) -> [f64; N],
    y0: [f64; N],
    t: f64,
    tol: f64,
) -> [f64; N] {
    let (mut y, mut now, mut big) = (y0, 0.0, (t / 4.0).min(0.05));
    while now < t {
        let h = big.min(t - now);
        match step(f, &y, h, tol) {
            Some(next) => {
                y = next;
                now += h;
                big = 1.5 * h.max(big);
            }
            None => {
                big = 0.5 * h;
                assert!(
                    big > 1e-12 * t.max(1.0),
                    "the test's solver cannot converge"
                );
            }
        }
    }
    y
}

/// The solution at each of `times` (increasing), solved to `tol` and checked against a second
/// solve to `tol / 100`: the two agree to `check` in every component of `measure(y)` (what the
/// test compares, e.g. positions, m).
pub fn samples<const N: usize>(
    f: &dyn Fn(&[f64; N]) -> [f64; N],
    y0: [f64; N],
    times: &[f64],
    tol: f64,
    measure: &dyn Fn(&[f64; N]) -> Vec<f64>,
    check: f64,
) -> Vec<[f64; N]> {
    let run = |tol: f64| {
        let (mut y, mut before) = (y0, 0.0);
        times
            .iter()
            .map(|&t| {
                y = solve(f, y, t - before, tol);
                before = t;
                y
            })
            .collect::<Vec<_>>()
    };
    let (coarse, fine) = (run(tol), run(tol / 100.0));
    for (a, b) in coarse.iter().zip(&fine) {
        for (p, q) in measure(a).iter().zip(measure(b)) {
            assert!(
                (p - q).abs() <= check,
                "the test's own solution is not converged: {:e}",
                (p - q).abs()
            );
        }
    }
    fine
}

#[test]
fn the_solver_meets_closed_forms_to_1e_12() {
    // y'' = −ω² y, ω = 10: y = cos ωt over 1 s (1.6 periods); and y' = y: eᵗ.
    let spring = solve(
        &|y: &[f64; 2]| [y[1], -100.0 * y[0]],
        [1.0, 0.0],
        1.0,
        1e-13,
    );
    assert!((spring[0] - 10f64.cos()).abs() < 1e-12, "{spring:?}");
    assert!((spring[1] + 10.0 * 10f64.sin()).abs() < 1e-11, "{spring:?}");
    let growth = solve(&|y: &[f64; 1]| [y[0]], [1.0], 2.0, 1e-14);
    assert!((growth[0] - 2f64.exp()).abs() < 1e-12, "{growth:?}");
    // The pendulum keeps its energy ½θ'² − g cos θ to round-off over 5 s from 90°.
    let f = |y: &[f64; 2]| [y[1], -9.81 * y[0].sin()];
    let y = solve(&f, [std::f64::consts::FRAC_PI_2, 0.0], 5.0, 1e-13);
    let energy = 0.5 * y[1] * y[1] - 9.81 * y[0].cos();
    assert!(energy.abs() < 1e-11, "energy {energy:e}");
}
