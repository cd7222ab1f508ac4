//! A small symmetric positive semi-definite system `(A + ε𝟙) x = rhs`, solved by LDLᵀ in the
//! envelope of its rows: the direct solves of the `impulse` response (contact-space inverse
//! mass) and of the position fix (translations).
//!
//! No square roots; ε = 1e-10 · max Aᵢᵢ picks the minimum-norm x when A is only
//! semi-definite.
//!
//! Two rows that share no body are uncoupled (`A_pq = 0`). Row p's *envelope* starts at its
//! first coupled column `first(p)`; the factor L has no entry left of it (fill-in stays inside
//! the envelope), so the factorisation and both substitutions skip those zeros:
//!
//! ```text
//! w_q   = A_pq − Σ_{k = max(first(p), first(q))}^{q−1} w_k L_qk      first(p) ≤ q < p
//! L_pq  = w_q / D_q,     D_p = A_pp + ε − Σ_q w_q L_pq
//! ```
//!
//! Only the envelope is stored (skyline storage: row p's entries `first(p)..=p` one after the
//! other), so memory and work grow with `Σ_p (p − first(p))` and `Σ_p (p − first(p))²`, not
//! with m². Contacts come grouped by pair of bodies, so a stack of n cubes (ground, then each
//! cube on the next) is banded: the cost grows as n, not n³. Skipping exact zeros leaves every
//! sum as it was, to the last bit (the back substitution sums each column's entries in
//! increasing row order, as a dense one would).

/// Up to this many rows the back substitution scans the rows below each column; above it,
/// it lists each column's rows once (O(envelope) instead of O(m²)).
const SMALL: usize = 64;

/// The system `(A + ε𝟙) x = rhs`, lower triangle of A filled in row by row. Buffers reused
/// from step to step.
#[derive(Debug, Clone, Default)]
pub struct Dense {
    m: usize,
    /// The right-hand side, then x.
    pub rhs: Vec<f64>,
    /// Row p's envelope `first(p)..=p` from `start[p]` on: A, then L in place (D on the
    /// diagonal slot is not used: `inv_diagonal` keeps 1/Dₚ).
    a: Vec<f64>,
    start: Vec<usize>,
    first: Vec<usize>,
    inv_diagonal: Vec<f64>,
    w: Vec<f64>,
    /// The first row that acts on each body (usize::MAX: none yet).
    body_first: Vec<usize>,
    /// For the back substitution: column q's rows k > q with first(k) ≤ q, in increasing k,
    /// from `column_start[q]` to `column_start[q + 1]`.
    column_start: Vec<usize>,
    column_rows: Vec<usize>,
    fill: Vec<usize>,
}

impl Dense {
    /// Makes room for an m × m system (its entries are written by [`Dense::fill_row`]).
    pub fn reset(&mut self, m: usize) {
        self.m = m;
        self.a.clear();
        for v in [&mut self.rhs, &mut self.inv_diagonal, &mut self.w] {
            v.clear();
            v.resize(m, 0.0);
        }
        self.first.clear();
        self.first.resize(m, 0);
        self.start.clear();
        self.start.resize(m, 0);
        self.body_first.fill(usize::MAX);
    }

    /// The number of stored entries the rows filled so far take (the envelope's size).
    pub fn stored(&self) -> usize {
        self.a.len()
    }

    /// Fills row p of the lower triangle, rows filled in order 0, 1, …: the row acts on
    /// `bodies` (one or two); its envelope starts at the first earlier row that acts on one of
    /// them, and `entry(q)` is asked for every q from there to p (None: an exact zero).
    pub fn fill_row(
        &mut self,
        p: usize,
        bodies: [Option<usize>; 2],
        mut entry: impl FnMut(usize) -> Option<f64>,
    ) {
        let mut first = p;
        for b in bodies.into_iter().flatten() {
            if b >= self.body_first.len() {
                self.body_first.resize(b + 1, usize::MAX);
            }
            first = first.min(self.body_first[b]);
            self.body_first[b] = self.body_first[b].min(p);
        }
        self.start[p] = self.a.len();
        self.a.reserve(p + 1 - first);
        for q in first..p + 1 {
            let value = entry(q).unwrap_or(0.0);
            self.a.push(value);
        }
        self.first[p] = first;
    }

    /// x, or None if a pivot is not positive (A not positive definite even with ε).
    pub fn solve(&mut self) -> Option<&[f64]> {
        let m = self.m;
        let Dense {
            a,
            rhs,
            start,
            first,
            inv_diagonal,
            w,
            column_start,
            column_rows,
            fill,
            ..
        } = self;
        // The m rows' slices (bounds known once).
        let (start, first) = (&start[..m], &first[..m]);
        let (inv_diagonal, w) = (&mut inv_diagonal[..m], &mut w[..m]);
        // Entry (p, q) of the envelope, first(p) ≤ q ≤ p. Every dot product below is summed
        // in increasing index from −0 (as `Iterator::sum` does).
        let at = |p: usize, q: usize| start[p] + q - first[p];
        let mut largest = 0.0;
        for p in 0..m {
            largest = f64::max(largest, a[at(p, p)]);
        }
        let epsilon = 1e-10 * largest;
        // A + ε𝟙 = L D Lᵀ (L unit lower triangular, in place below the diagonal; D kept as
        // 1/Dₚ): no square roots. w_q = L_pq D_q for the row being factored.
        for p in 0..m {
            let fp = first[p];
            let row_p = at(p, fp);
            let mut pivot = a[row_p + p - fp] + epsilon;
            for q in fp..p {
                let begin = fp.max(first[q]);
                let row_q = at(q, begin);
                let mut dot = -0.0;
                for (wk, y) in w[begin..q].iter().zip(&a[row_q..row_q + q - begin]) {
                    dot += wk * y;
                }
                let wq = a[row_p + q - fp] - dot;
                w[q] = wq;
                let l = wq * inv_diagonal[q];
                pivot -= wq * l;
                a[row_p + q - fp] = l;
            }
            if pivot <= 0.0 {
                return None;
            }
            inv_diagonal[p] = 1.0 / pivot;
        }
        // L y = rhs, then Lᵀ x = D⁻¹ y.
        let x = &mut rhs[..m];
        for p in 0..m {
            let fp = first[p];
            let row_p = at(p, fp);
            let mut dot = -0.0;
            for (y, xk) in a[row_p..row_p + p - fp].iter().zip(&x[fp..p]) {
                dot += y * xk;
            }
            x[p] -= dot;
        }
        if m <= SMALL {
            // Few rows: scan them (the same sums, in the same order).
            for p in (0..m).rev() {
                let mut dot = -0.0;
                for k in p + 1..m {
                    if first[k] <= p {
                        dot += a[at(k, p)] * x[k];
                    }
                }
                x[p] = x[p] * inv_diagonal[p] - dot;
            }
            return Some(&x[..m]);
        }
        // Column q of L below the diagonal: the rows k > q whose envelope reaches q.
        column_start.clear();
        column_start.resize(m + 1, 0);
        for (k, &fk) in first.iter().enumerate() {
            for count in &mut column_start[fk + 1..k + 1] {
                *count += 1;
            }
        }
        for q in 0..m {
            column_start[q + 1] += column_start[q];
        }
        column_rows.clear();
        column_rows.resize(column_start[m], 0);
        fill.clear();
        fill.extend_from_slice(&column_start[..m]);
        for (k, &fk) in first.iter().enumerate() {
            for slot in &mut fill[fk..k] {
                column_rows[*slot] = k;
                *slot += 1;
            }
        }
        for p in (0..m).rev() {
            let dot: f64 = column_rows[column_start[p]..column_start[p + 1]]
                .iter()
                .map(|&k| a[at(k, p)] * x[k])
                .sum();
            x[p] = x[p] * inv_diagonal[p] - dot;
        }
        Some(&x[..m])
    }
}
