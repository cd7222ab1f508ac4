//! `soft-step`'s restitution, one manifold at a time (module doc of `soft_step`, "The step":
//! once, after the sub-steps).
//!
//! # The law
//!
//! A row that met faster than the bounce speed (approach `u⁻ < −bounce_speed`) and pushed
//! during the step asks for a normal rate of at least `−e u⁻` (Newton's target, Box2D v3's),
//! with a non-negative impulse. The rows of one manifold (a run: the rows between the same two
//! bodies) that ask are solved together, as one linear complementarity problem in their new
//! impulses x:
//!
//! ```text
//! w = A x + q ≥ 0,   x ≥ 0,   xᵀw = 0,          q = u + e u⁻ − A λ
//! A_ij = (n_i·n_j)/M_A + (r_A,i×n_i)·I_A⁻¹(r_A,j×n_j) + (n_i·n_j)/M_B + (r_B,i×n_i)·I_B⁻¹(r_B,j×n_j)
//! ```
//!
//! with u the rows' rates after the sub-steps, λ their impulses and w their rates after the
//! bounce minus the target. This is the fixed point of Box2D's one-row law
//! (`j = −(u + e u⁻)/A_ii`, `λ ← max(0, λ + j)`) taken over and over until no row changes. One
//! sequential pass, which Box2D and this response took before, stops short of it: on the four
//! corners of a face landing flat, the first corner is sent off at `−e u⁻` alone, turning the
//! body, and each later corner then finds its own rate changed by the ones before it. Lesson
//! 32's cube (0.2 m, landing flat at 4.2 m/s, e = 0.5) left its first touch spinning at
//! ω ≈ (−3.2, 0, −2.7) rad/s and came down on a corner. Solved together, a face that lands
//! flat leaves flat: every corner at `−e u⁻`, the spin unchanged.
//!
//! A manifold of one row keeps the one-row law, bit for bit.
//!
//! # Redundant rows
//!
//! The four corners of a face are redundant: A has rank 3 (a face's rows can push up and turn
//! about two axes), so x is not unique, though the rates are. The solve takes `A + εD`
//! (`D = diag A`, ε = [`REGULARISE`]), symmetric positive definite, whose one solution tends,
//! as ε → 0, to the solution of least `Σ D_ii x_i²` (Tikhonov's, for a monotone problem): the
//! load spread evenly over symmetric corners. The rates it leaves are off by about `ε |q|`.
//!
//! # The solve
//!
//! Principal pivoting (Murty, "Note on a Bard-type scheme for solving the complementarity
//! problem", 1974): a set S of rows held at `w = 0` (the rest at `x = 0`) gives
//! `x_S = −(A + εD)_SS⁻¹ q_S` by Cholesky; the first row (lowest index) that breaks a sign,
//! `x_i < 0` in S or `w_i < 0` outside it, changes side, until none does. For a positive
//! definite matrix this ends after finitely many changes; it starts from every row in S,
//! which is the answer for a face landing flat.

use super::bodies::Motion;
use super::rows::{Row, Rows};
use super::sweep::{normal_rate, push};

/// ε of the solve `A + εD` (module doc, "Redundant rows").
pub(super) const REGULARISE: f64 = 1e-10;

/// The most side changes a manifold's solve may take before it keeps what it has (clamped
/// to x ≥ 0), per row: never reached in the tests.
const MAX_CHANGES_PER_ROW: usize = 16;

/// Buffers reused from step to step: the manifold's rows that bounce, their coupling and the
/// solve's working arrays.
#[derive(Debug, Clone, Default)]
pub(super) struct Block {
    /// The rows (indices into the step's rows) that bounce in the current manifold.
    index: Vec<usize>,
    /// A + εD, row-major, m × m.
    a: Vec<f64>,
    q: Vec<f64>,
    x: Vec<f64>,
    w: Vec<f64>,
    held: Vec<bool>,
    /// The held rows' places in `index`.
    members: Vec<usize>,
    /// The Cholesky factor of the held rows' block and its right-hand side.
    factor: Vec<f64>,
    rhs: Vec<f64>,
}

/// Restitution, once, from the approach the contact met: every manifold's rows that met
/// faster than `bounce_speed` and pushed, solved together (module doc), manifold by manifold.
#[inline(always)]
pub(super) fn restitution(
    rows: &mut Rows,
    motions: &mut [Motion],
    e: f64,
    bounce_speed: f64,
    block: &mut Block,
) {
    let Rows {
        rows, totals, runs, ..
    } = rows;
    for run in runs.iter() {
        block.index.clear();
        block.index.extend(
            run.rows
                .clone()
                .filter(|&i| totals[i].approach < -bounce_speed && rows[i].max_lambda != 0.0),
        );
        if block.index.is_empty() {
            continue;
        }
        let pair = run.b.is_some();
        let mut a = motions[run.a];
        let mut b = run.b.map_or_else(Motion::default, |i| motions[i]);
        if let [i] = block.index[..] {
            // One row: the one-row law.
            let (row, t) = (&mut rows[i], &mut totals[i]);
            let u = normal_rate(row, &a, &b, pair);
            let j = -row.inv_k * (u + e * t.approach);
            let new = (row.lambda + j).max(0.0);
            let change = new - row.lambda;
            row.lambda = new;
            push(row, change, &mut a, &mut b, pair);
            t.applied += change;
        } else {
            block.couple(rows, &a, &b, pair, |i| e * totals[i].approach);
            block.solve();
            for (k, &i) in block.index.iter().enumerate() {
                let row = &mut rows[i];
                let change = block.x[k] - row.lambda;
                row.lambda = block.x[k];
                push(row, change, &mut a, &mut b, pair);
                totals[i].applied += change;
            }
        }
        motions[run.a] = a;
        if let Some(i) = run.b {
            motions[i] = b;
        }
    }
}

impl Block {
    /// `A + εD` and q of the rows in `index` (module doc), `target(i)` the row's `e u⁻`.
    fn couple(
        &mut self,
        rows: &[Row],
        a: &Motion,
        b: &Motion,
        pair: bool,
        target: impl Fn(usize) -> f64,
    ) {
        let m = self.index.len();
        self.a.clear();
        for &i in &self.index {
            let ri = &rows[i];
            for &j in &self.index {
                let rj = &rows[j];
                let nn = ri.normal.dot(&rj.normal);
                let mut aij = nn * a.inv_mass + ri.rn[0].dot(&rj.w_a);
                if pair {
                    aij += nn * b.inv_mass + ri.rn[1].dot(&rj.w_b);
                }
                self.a.push(aij);
            }
        }
        for k in 0..m {
            self.a[k * m + k] *= 1.0 + REGULARISE;
        }
        self.q.clear();
        for (k, &i) in self.index.iter().enumerate() {
            let row = &rows[i];
            let held: f64 = (0..m)
                .map(|l| self.a[k * m + l] * rows[self.index[l]].lambda)
                .sum();
            self.q
                .push(normal_rate(row, a, b, pair) + target(i) - held);
        }
    }

    /// Solves `w = (A + εD) x + q ≥ 0, x ≥ 0, xᵀw = 0` into `x` by principal pivoting (module
    /// doc, "The solve").
    fn solve(&mut self) {
        let m = self.index.len();
        self.held.clear();
        self.held.resize(m, true);
        let scale_q = self.q.iter().map(|q| q.abs()).fold(0.0, f64::max);
        for _ in 0..MAX_CHANGES_PER_ROW * m {
            self.solve_held();
            let scale_x = self.x.iter().map(|x| x.abs()).fold(0.0, f64::max);
            let broken = (0..m).find(|&k| {
                if self.held[k] {
                    self.x[k] < -1e-12 * scale_x
                } else {
                    self.w[k] < -1e-12 * scale_q
                }
            });
            match broken {
                Some(k) => self.held[k] = !self.held[k],
                None => break,
            }
        }
        for x in &mut self.x {
            *x = x.max(0.0);
        }
    }

    /// x of the held rows from `(A + εD)_SS x_S = −q_S` (Cholesky), 0 for the others, and
    /// `w = (A + εD) x + q`.
    fn solve_held(&mut self) {
        let m = self.index.len();
        let mut held = std::mem::take(&mut self.members);
        held.clear();
        held.extend((0..m).filter(|&k| self.held[k]));
        let s = held.len();
        self.factor.clear();
        self.factor.resize(s * s, 0.0);
        self.rhs.clear();
        self.rhs.extend(held.iter().map(|&k| -self.q[k]));
        // L Lᵀ = A_SS, lower triangle of `factor`.
        for c in 0..s {
            let mut d = self.a[held[c] * m + held[c]];
            for p in 0..c {
                d -= self.factor[c * s + p] * self.factor[c * s + p];
            }
            let d = d.max(f64::MIN_POSITIVE).sqrt();
            self.factor[c * s + c] = d;
            for r in c + 1..s {
                let mut v = self.a[held[r] * m + held[c]];
                for p in 0..c {
                    v -= self.factor[r * s + p] * self.factor[c * s + p];
                }
                self.factor[r * s + c] = v / d;
            }
        }
        for r in 0..s {
            let mut v = self.rhs[r];
            for p in 0..r {
                v -= self.factor[r * s + p] * self.rhs[p];
            }
            self.rhs[r] = v / self.factor[r * s + r];
        }
        for r in (0..s).rev() {
            let mut v = self.rhs[r];
            for p in r + 1..s {
                v -= self.factor[p * s + r] * self.rhs[p];
            }
            self.rhs[r] = v / self.factor[r * s + r];
        }
        self.x.clear();
        self.x.resize(m, 0.0);
        for (c, &k) in held.iter().enumerate() {
            self.x[k] = self.rhs[c];
        }
        self.w.clear();
        for k in 0..m {
            let ax: f64 = (0..m).map(|l| self.a[k * m + l] * self.x[l]).sum();
            self.w.push(ax + self.q[k]);
        }
        self.members = held;
    }
}

#[cfg(test)]
mod tests {
    use super::{Block, REGULARISE};

    /// Solves `w = A' x + q` (A' = A with its diagonal times 1 + ε, as `couple` builds it).
    fn solve(a: &[f64], q: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let m = q.len();
        let mut block = Block {
            index: (0..m).collect(),
            a: a.to_vec(),
            q: q.to_vec(),
            ..Block::default()
        };
        for k in 0..m {
            block.a[k * m + k] *= 1.0 + REGULARISE;
        }
        block.solve();
        (block.x, block.w)
    }

    #[test]
    fn a_row_that_would_pull_is_let_go_and_the_other_takes_the_bounce() {
        // A = [[2, 1], [1, 2]], q = (−1, 1): with both held x = (1, −1), x₂ < 0, so row 2
        // lets go: x = (1/2, 0), w = (0, 3/2) (by hand).
        let (x, w) = solve(&[2.0, 1.0, 1.0, 2.0], &[-1.0, 1.0]);
        assert!((x[0] - 0.5).abs() < 1e-9 && x[1] == 0.0, "{x:?}");
        assert!(w[0].abs() < 1e-9 && (w[1] - 1.5).abs() < 1e-9, "{w:?}");
    }

    #[test]
    fn four_corners_of_a_face_share_the_bounce_evenly() {
        // A cube (M = 1, side 2a = 0.2, I = M(2a)²/6) on the ground, its four bottom corners
        // r = (±a, −a, ±a), n = y: A_ij = 1/M + (r_i×n)·I⁻¹(r_j×n). The rows are redundant
        // (rank 3); each asking for the same rate change c, the least-norm answer is c·M/4
        // per corner (the face pushes its barycenter, turning nothing).
        let (a, inertia) = (0.1, 0.2f64 * 0.2 / 6.0);
        let corners = [(a, a), (a, -a), (-a, a), (-a, -a)];
        // r×y = (−r_z, 0, r_x) for r = (r_x, −a, r_z).
        let mut matrix = Vec::new();
        for &(xi, zi) in &corners {
            for &(xj, zj) in &corners {
                matrix.push(1.0 + (zi * zj + xi * xj) / inertia);
            }
        }
        let c = 2.1;
        let (x, w) = solve(&matrix, &[-c; 4]);
        for (xi, wi) in x.iter().zip(&w) {
            assert!((xi - c / 4.0).abs() < 1e-6 * c, "{x:?}");
            assert!(wi.abs() < 1e-8 * c, "{w:?}");
        }
    }
}
