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
//! Contacts come grouped by pair of bodies, so a stack of n cubes (ground, then each cube on
//! the next) is banded: the cost grows as n, not n³. Skipping exact zeros leaves every sum
//! as it was, to the last bit.

/// The system `(A + ε𝟙) x = rhs`, lower triangle of A filled in row by row. Buffers reused
/// from step to step.
#[derive(Debug, Clone, Default)]
pub struct Dense {
    m: usize,
    /// The right-hand side, then x.
    pub rhs: Vec<f64>,
    /// Row-major m × m, lower triangle: A, then L in place.
    a: Vec<f64>,
    first: Vec<usize>,
    inv_diagonal: Vec<f64>,
    w: Vec<f64>,
    /// The first row that acts on each body (usize::MAX: none yet).
    body_first: Vec<usize>,
}

impl Dense {
    /// Makes room for an m × m system (its entries are written by [`Dense::fill_row`]).
    pub fn reset(&mut self, m: usize) {
        self.m = m;
        if self.a.len() < m * m {
            self.a.resize(m * m, 0.0);
        }
        for v in [&mut self.rhs, &mut self.inv_diagonal, &mut self.w] {
            v.clear();
            v.resize(m, 0.0);
        }
        self.first.clear();
        self.first.resize(m, 0);
        self.body_first.fill(usize::MAX);
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
        let m = self.m;
        for (q, slot) in (first..=p).zip(&mut self.a[p * m + first..p * m + p + 1]) {
            *slot = entry(q).unwrap_or(0.0);
        }
        self.first[p] = first;
    }

    /// x, or None if a pivot is not positive (A not positive definite even with ε).
    pub fn solve(&mut self) -> Option<&[f64]> {
        let m = self.m;
        let Dense {
            a,
            rhs,
            first,
            inv_diagonal,
            w,
            ..
        } = self;
        let largest = (0..m).map(|p| a[p * m + p]).fold(0.0, f64::max);
        let epsilon = 1e-10 * largest;
        // A + ε𝟙 = L D Lᵀ (L unit lower triangular, in place below the diagonal; D kept as
        // 1/Dₚ): no square roots. w_q = L_pq D_q for the row being factored.
        for p in 0..m {
            let fp = first[p];
            let mut pivot = a[p * m + p] + epsilon;
            for q in fp..p {
                let start = fp.max(first[q]);
                let dot: f64 = w[start..q]
                    .iter()
                    .zip(&a[q * m + start..q * m + q])
                    .map(|(x, y)| x * y)
                    .sum();
                w[q] = a[p * m + q] - dot;
                let l = w[q] * inv_diagonal[q];
                pivot -= w[q] * l;
                a[p * m + q] = l;
            }
            if pivot <= 0.0 {
                return None;
            }
            inv_diagonal[p] = 1.0 / pivot;
        }
        // L y = rhs, then Lᵀ x = D⁻¹ y.
        let x = rhs;
        for p in 0..m {
            let fp = first[p];
            let dot: f64 = a[p * m + fp..p * m + p]
                .iter()
                .zip(&x[fp..p])
                .map(|(x, y)| x * y)
                .sum();
            x[p] -= dot;
        }
        for p in (0..m).rev() {
            let dot: f64 = (p + 1..m)
                .filter(|&k| first[k] <= p)
                .map(|k| a[k * m + p] * x[k])
                .sum();
            x[p] = x[p] * inv_diagonal[p] - dot;
        }
        Some(&x[..m])
    }
}
