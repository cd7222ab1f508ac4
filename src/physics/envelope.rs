//! The envelope (skyline) factorisation of a constraint system's effective mass
//! `A = J W Jᵀ`, symmetric positive semi-definite, one row per constraint row: the contacts'
//! direct solves (`collision::impulse`, the position fix `collision::position`) and the joints'
//! multipliers (`joints::solve`).
//!
//! Two rows that share no body are uncoupled (`A_pq = 0`). Row p's *envelope* starts at its
//! first coupled column `first(p)`, the first earlier row acting on one of its bodies; the
//! factor has no entry left of it (fill-in stays inside the envelope), so the factorisation
//! and both substitutions skip those zeros. Only the envelope is stored (skyline storage: row
//! p's entries `first(p)..=p` one after the other), so memory and work grow with
//! `Σ_p (p − first(p))` and `Σ_p (p − first(p))²`, not with m² and m³: rows come grouped by
//! pair of bodies (contacts) or joint by joint along a chain (joints), so a stack of n cubes or
//! a chain of n links is banded and costs n, not n³. Skipping exact zeros leaves every sum as a
//! dense factorisation would compute it, to the last bit.
//!
//! Both factorisations walk the envelope the same way. Row p, column q (first(p) ≤ q < p),
//! with the sums over the columns both rows reach, in increasing k from −0:
//!
//! ```text
//! t_pq = A_pq − Σ_{k = max(first(p), first(q))}^{q−1} F_pk F_qk
//! ```
//!
//! What F is, and what is done with a small pivot, is the *pivot policy*, the one thing the
//! two users choose:
//!
//! ```text
//! regularised  (A + ε𝟙) = L D Lᵀ, ε = 1e-10 · max |Aᵢᵢ|      no square roots
//!              F_pq = w_q = L_pq D_q (kept apart while row p is factored),
//!              L_pq = w_q / D_q,  D_p = A_pp + ε − Σ_q w_q L_pq;   D_p ≤ 0: no answer
//!              x:  L y = b,  then  Lᵀ x = D⁻¹ y
//! dropped      A = L Lᵀ (Cholesky), F = L
//!              L_pq = t_pq / L_qq,  L_pp² = A_pp − Σ_q L_pq²;
//!              L_pp² ≤ 1e-12 · max |Aᵢᵢ|: row p is redundant, 1/L_pp := 0 (its x_p = 0)
//!              x:  L y = b,  then  Lᵀ x = y
//! ```
//!
//! Only the pivots' reciprocals 1/D_p or 1/L_pp are kept: the substitutions multiply, and a
//! division (and a square root) sits on the critical path once per row, not once per entry.
//!
//! Why each user takes its policy:
//!
//! - **Contacts** (`regularised`): two contacts of one face against another are often
//!   dependent (four corners of a box resting on the ground give a rank-3 A), and their
//!   impulses are then not unique. The tiny ε picks, among them, the minimum-norm one, the
//!   symmetric answer a resting box should show; the solve declines (no answer) only when A
//!   is not semi-definite, and the caller falls back to its iterations.
//! - **Joints** (`dropped`): the multipliers are evaluated inside the derivative f(Y) (rk4:
//!   four times a step) and must always give an answer. A redundant row — a ball joint
//!   doubling a hinge's point rows, a closed loop — has a pivot that is round-off of the others:
//!   its multiplier is set to 0 and the independent rows carry the load. Dropping is exact on
//!   the other rows (no ε shifts them), and costs one comparison.
//!
//! Tried and not kept (2026-12-07): eight partial sums in each dot product of 17 terms or
//! more (independent additions, so they run side by side; the same bits on any CPU). It
//! factors a band of width 100 and 600 rows 2.1× faster (0.93 ms against 1.9–2.0 ms, a
//! stand-alone timing), but the sums are no longer a dense factorisation's: wide systems
//! (walls, pyramids) take other paths, lesson 41's ledger closed to 2.0e-8 J against the
//! 1e-8 J its page says, its walk snapshot's P_z at 2.8 s moved 232.495 → 229.411, and the
//! time per unit of solver work on the walls fell 5–18 % in noisy paired runs, none on the
//! pyramid of 20 rows, while the chaotic paths moved the walls' total work by −32 % to +63 %.
//!
//! The back substitutions are ordered differently on purpose: the regularised one sums each
//! column's entries in increasing row order (as a dense left-looking one would), the dropped
//! one subtracts each solved x_p from the rows above it (right-looking, in decreasing p). Both
//! are exact in exact arithmetic; they are kept as they were before the two factorisations
//! shared this file, so the contacts' and the joints' trajectories stay bit-identical.

/// Up to this many rows the regularised back substitution scans the rows below each column;
/// above it, it lists each column's rows once (O(envelope) instead of O(m²)).
const SMALL: usize = 64;

/// What the factorisation does with the pivots (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pivots {
    /// `A + ε𝟙 = L D Lᵀ`, ε = 1e-10 · max |Aᵢᵢ|: the minimum-norm answer of a semi-definite A;
    /// no answer when a pivot is not positive.
    Regularised,
    /// `A = L Lᵀ`: a pivot below 1e-12 · max |Aᵢᵢ| is a redundant row, whose unknown is 0.
    Dropped,
}

/// The system `A x = rhs`, lower triangle of A filled in row by row inside each row's
/// envelope. Buffers reused from solve to solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Envelope {
    m: usize,
    /// The right-hand side, then x (for [`Envelope::solve`]).
    pub rhs: Vec<f64>,
    /// Row p's envelope `first(p)..=p` from `start[p]` on: A, then the factor in place below
    /// the diagonal (the diagonal slot keeps A_pp; `reciprocal` keeps the pivots).
    a: Vec<f64>,
    start: Vec<usize>,
    first: Vec<usize>,
    /// 1/D_p (regularised) or 1/L_pp (dropped; 0 for a redundant row).
    reciprocal: Vec<f64>,
    /// Regularised: w_q = L_pq D_q of the row being factored.
    w: Vec<f64>,
    /// The first row that acts on each body (usize::MAX: none yet).
    body_first: Vec<usize>,
    /// For the regularised back substitution: column q's rows k > q with first(k) ≤ q, in
    /// increasing k, from `column_start[q]` to `column_start[q + 1]`.
    column_start: Vec<usize>,
    column_rows: Vec<usize>,
    fill: Vec<usize>,
    /// Whether `column_start` and `column_rows` list the rows filled since the last reset
    /// (rows are filled after a reset, before the system is solved).
    columns_listed: bool,
}

/// Lists, for each column q of an m-row envelope (`first`: each row's first column), the rows
/// k > q whose envelope reaches q, in increasing k: `column_rows[column_start[q]..
/// column_start[q + 1]]`. Column q's count is the number of rows with first(k) ≤ q < k,
/// summed from a difference array (+1 at first(k), −1 at k: O(m), not O(envelope)).
fn list_columns(
    first: &[usize],
    column_start: &mut Vec<usize>,
    column_rows: &mut Vec<usize>,
    fill: &mut Vec<usize>,
) {
    let m = first.len();
    column_start.clear();
    column_start.resize(m + 1, 0);
    // column_start[q + 1] counts the rows of column q: +1 from q = first(k), −1 from q = k
    // (wrapping: each prefix sum is a count, never below 0).
    for (k, &fk) in first.iter().enumerate() {
        column_start[fk + 1] = column_start[fk + 1].wrapping_add(1);
        column_start[k + 1] = column_start[k + 1].wrapping_sub(1);
    }
    let mut count = 0usize;
    for q in 0..m {
        count = count.wrapping_add(column_start[q + 1]);
        column_start[q + 1] = column_start[q] + count;
    }
    // Every slot below column_start[m] is written once below: grow, never clear.
    let listed = column_start[m];
    if column_rows.len() < listed {
        column_rows.resize(listed, 0);
    }
    fill.clear();
    fill.extend_from_slice(&column_start[..m]);
    for (k, &fk) in first.iter().enumerate() {
        for slot in &mut fill[fk..k] {
            column_rows[*slot] = k;
            *slot += 1;
        }
    }
}

/// `Σ aₖ bₖ` in increasing k from −0 (as `Iterator::sum` does).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sum = -0.0;
    for (x, y) in a.iter().zip(b) {
        sum += x * y;
    }
    sum
}

impl Envelope {
    /// Makes room for an m × m system (its entries are written by [`Envelope::fill_row`]).
    #[inline]
    pub fn reset(&mut self, m: usize) {
        self.m = m;
        self.a.clear();
        self.rhs.clear();
        self.rhs.resize(m, 0.0);
        // Written before they are read (by `fill_row`, by the factorisation): only their
        // length matters.
        for v in [&mut self.reciprocal, &mut self.w] {
            if v.len() < m {
                v.resize(m, 0.0);
            }
        }
        for v in [&mut self.first, &mut self.start] {
            if v.len() < m {
                v.resize(m, 0);
            }
        }
        self.body_first.fill(usize::MAX);
        self.columns_listed = false;
    }

    /// The number of stored entries the rows filled so far take (the envelope's size).
    pub fn stored(&self) -> usize {
        self.a.len()
    }

    /// Fills row p of the lower triangle, rows filled in order 0, 1, …: the row acts on
    /// `bodies` (one or two); its envelope starts at the first earlier row that acts on one of
    /// them, and `entry(q)` is asked for every q from there to p (None: an exact zero).
    #[inline]
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

    /// Row p's first column inside its envelope, and its filled entries, columns
    /// `first(p)..=p` (to add to them, when A is summed body by body rather than row by row).
    pub fn row_mut(&mut self, p: usize) -> (usize, &mut [f64]) {
        let (first, start) = (self.first[p], self.start[p]);
        (first, &mut self.a[start..=start + p - first])
    }

    /// x of `A x = rhs` over `rhs`, or None if `pivots` gives no answer (regularised: a pivot
    /// not positive, A not positive semi-definite).
    pub fn solve(&mut self, pivots: Pivots) -> Option<&[f64]> {
        let mut x = std::mem::take(&mut self.rhs);
        let solved = self.solve_into(pivots, &mut x);
        self.rhs = x;
        solved.then(|| &self.rhs[..self.m])
    }

    /// x of `A x = b`, written over `b` (its first m entries); false (b untouched) if `pivots`
    /// gives no answer. [`Pivots::Dropped`] always answers.
    #[inline(always)]
    pub fn solve_into(&mut self, pivots: Pivots, b: &mut [f64]) -> bool {
        // One copy of the code per policy, each with its `match pivots` resolved.
        match pivots {
            Pivots::Regularised => self.factor_and_substitute(Pivots::Regularised, b),
            Pivots::Dropped => self.factor_and_substitute(Pivots::Dropped, b),
        }
    }

    /// Factors A in place (regularised, as [`Envelope::solve`]) for several right-hand sides
    /// solved by [`Envelope::substitute_regularised`]; false if a pivot is not positive.
    pub fn factor_regularised(&mut self) -> bool {
        self.factor(Pivots::Regularised)
    }

    /// x of `A x = b` over `b` (its first m entries), A factored by
    /// [`Envelope::factor_regularised`].
    pub fn substitute_regularised(&mut self, b: &mut [f64]) {
        let m = self.m;
        self.substitute(Pivots::Regularised, &mut b[..m]);
    }

    #[inline(always)]
    fn factor_and_substitute(&mut self, pivots: Pivots, b: &mut [f64]) -> bool {
        if !self.factor(pivots) {
            return false;
        }
        let m = self.m;
        self.substitute(pivots, &mut b[..m]);
        true
    }

    /// The factor in place (module doc); false if a regularised pivot is not positive.
    #[inline(always)]
    fn factor(&mut self, pivots: Pivots) -> bool {
        let m = self.m;
        let Envelope {
            a,
            start,
            first,
            reciprocal,
            w,
            ..
        } = self;
        let (start, first) = (&start[..m], &first[..m]);
        let (reciprocal, w) = (&mut reciprocal[..m], &mut w[..m]);
        // A is semi-definite: Aᵢᵢ ≥ 0 and |Aᵢᵢ| = Aᵢᵢ. (Were some Aᵢᵢ < 0, its pivot would be
        // negative whatever ε, and the regularised solve would decline all the same.)
        let largest = (0..m)
            .map(|p| a[start[p] + p - first[p]].abs())
            .fold(0.0, f64::max);
        let epsilon = 1e-10 * largest;
        for p in 0..m {
            let fp = first[p];
            let (done, rest) = a.split_at_mut(start[p]);
            let row_p = &mut rest[..=p - fp];
            let diagonal = row_p[p - fp];
            // Regularised: D_p = A_pp + ε − Σ_q w_q L_pq, summed as the columns come.
            let mut pivot = diagonal + epsilon;
            for q in fp..p {
                let fq = first[q];
                let from = fp.max(fq);
                let row_q = &done[start[q] + from - fq..start[q] + q - fq];
                // F_pk for k < q: w_k (regularised) or L_pk (dropped, in place).
                let t = row_p[q - fp]
                    - match pivots {
                        Pivots::Regularised => dot(&w[from..q], row_q),
                        Pivots::Dropped => dot(&row_p[from - fp..q - fp], row_q),
                    };
                row_p[q - fp] = match pivots {
                    Pivots::Regularised => {
                        w[q] = t;
                        let l = t * reciprocal[q];
                        pivot -= t * l;
                        l
                    }
                    Pivots::Dropped => t * reciprocal[q],
                };
            }
            reciprocal[p] = match pivots {
                Pivots::Regularised => {
                    if pivot <= 0.0 {
                        return false;
                    }
                    1.0 / pivot
                }
                Pivots::Dropped => {
                    let off_diagonal = &row_p[..p - fp];
                    let square = diagonal - dot(off_diagonal, off_diagonal);
                    if square > 1e-12 * largest {
                        1.0 / square.sqrt()
                    } else {
                        0.0
                    }
                }
            };
        }
        true
    }

    /// `L y = b`, then `Lᵀ x = D⁻¹ y` (regularised) or `Lᵀ x = y` (dropped), over x = b.
    #[inline(always)]
    fn substitute(&mut self, pivots: Pivots, x: &mut [f64]) {
        let m = self.m;
        let Envelope {
            a,
            start,
            first,
            reciprocal,
            column_start,
            column_rows,
            fill,
            columns_listed,
            ..
        } = self;
        let (start, first, reciprocal) = (&start[..m], &first[..m], &reciprocal[..m]);
        for p in 0..m {
            let fp = first[p];
            let y = x[p] - dot(&a[start[p]..start[p] + p - fp], &x[fp..p]);
            x[p] = match pivots {
                Pivots::Regularised => y,
                Pivots::Dropped => y * reciprocal[p],
            };
        }
        let at = |p: usize, q: usize| start[p] + q - first[p];
        match pivots {
            Pivots::Dropped => {
                // x_p is final once the rows below have been subtracted: take it off the rows
                // above (its row's envelope), from the last row up.
                for p in (0..m).rev() {
                    x[p] *= reciprocal[p];
                    let (fp, xp) = (first[p], x[p]);
                    for (r, l) in x[fp..p].iter_mut().zip(&a[start[p]..at(p, p)]) {
                        *r -= l * xp;
                    }
                }
            }
            Pivots::Regularised if m <= SMALL => {
                // Few rows: scan them (the same sums, in the same order, as the lists below).
                for p in (0..m).rev() {
                    let mut sum = -0.0;
                    for k in p + 1..m {
                        if first[k] <= p {
                            sum += a[at(k, p)] * x[k];
                        }
                    }
                    x[p] = x[p] * reciprocal[p] - sum;
                }
            }
            Pivots::Regularised => {
                // Column q of L below the diagonal: the rows k > q whose envelope reaches q
                // (built once per filled system: a second right-hand side reuses them).
                if !*columns_listed {
                    list_columns(first, column_start, column_rows, fill);
                    *columns_listed = true;
                }
                for p in (0..m).rev() {
                    let sum: f64 = column_rows[column_start[p]..column_start[p + 1]]
                        .iter()
                        .map(|&k| a[at(k, p)] * x[k])
                        .sum();
                    x[p] = x[p] * reciprocal[p] - sum;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The system of `rows` (lower triangles, each from its first column), row p acting on
    /// `bodies[p]`, with right-hand side `rhs`.
    fn system(rows: &[&[f64]], bodies: &[[Option<usize>; 2]], rhs: &[f64]) -> Envelope {
        let mut system = Envelope::default();
        refill(&mut system, rows, bodies, rhs);
        system
    }

    /// [`system`] written into `system`, whatever it held.
    fn refill(system: &mut Envelope, rows: &[&[f64]], bodies: &[[Option<usize>; 2]], rhs: &[f64]) {
        system.reset(rows.len());
        for (p, (row, &acts_on)) in rows.iter().zip(bodies).enumerate() {
            system.fill_row(p, acts_on, |q| Some(row[q + row.len() - 1 - p]));
        }
        system.rhs.copy_from_slice(rhs);
    }

    /// A system's rows (each from its first column), each row's bodies, and b.
    type Springs = (Vec<Vec<f64>>, Vec<[Option<usize>; 2]>, Vec<f64>);

    /// Springs in a row: `m` rows, row p acting on bodies p and p + `stride`, so row p shares
    /// a body with rows p ± stride alone: K has 2 on the diagonal and −1 at distance
    /// `stride` (`stride` independent chains, interleaved). x = 1 takes b = 1 on each chain's
    /// first and last row, 0 elsewhere.
    fn springs(m: usize, stride: usize) -> Springs {
        let rows = (0..m)
            .map(|p| {
                let mut row = vec![0.0; if p < stride { 1 } else { stride + 1 }];
                row[0] = if p < stride { 2.0 } else { -1.0 };
                *row.last_mut().unwrap() = 2.0;
                row
            })
            .collect();
        let bodies = (0..m).map(|p| [Some(p), Some(p + stride)]).collect();
        let rhs = (0..m)
            .map(|p| {
                if p < stride || p + stride >= m {
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        (rows, bodies, rhs)
    }

    /// The regularised answer of [`springs`]: on each chain of n rows, row i of it has
    /// x = 1 − ε (i + 1)(n − i)/2 to first order in ε = 2e-10 (see the test below).
    fn springs_answer(m: usize, stride: usize, p: usize) -> f64 {
        let (n, i) = (m / stride, p / stride);
        1.0 - 2e-10 * ((i + 1) * (n - i)) as f64 / 2.0
    }

    #[test]
    fn the_column_lists_follow_each_filled_system() {
        // Above SMALL the regularised back substitution lists each column's rows once per
        // filled system: two right-hand sides on one factor, then a system of another shape
        // in the same buffers, must each get their own answer.
        let mut k = Envelope::default();
        for (m, stride) in [(100, 1), (80, 2), (90, 3)] {
            let (rows, bodies, rhs) = springs(m, stride);
            let slices: Vec<&[f64]> = rows.iter().map(Vec::as_slice).collect();
            refill(&mut k, &slices, &bodies, &rhs);
            assert!(k.factor_regularised());
            for scale in [1.0, 3.0] {
                let mut b: Vec<f64> = rhs.iter().map(|r| r * scale).collect();
                k.substitute_regularised(&mut b);
                for (p, x) in b.iter().enumerate() {
                    let want = scale * springs_answer(m, stride, p);
                    assert!(
                        (x - want).abs() < 1e-11,
                        "m {m} stride {stride} row {p}: {x}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_column_lists_are_the_rows_below_each_column_inside_their_envelopes() {
        // Brute force against the definition: column q lists the rows k > q with
        // first(k) ≤ q, in increasing k.
        let first = [0, 0, 1, 0, 3, 5, 2, 7, 7, 4];
        let (mut start, mut rows, mut fill) = (Vec::new(), vec![7; 3], Vec::new());
        list_columns(&first, &mut start, &mut rows, &mut fill);
        for q in 0..first.len() {
            let want: Vec<usize> = (q + 1..first.len()).filter(|&k| first[k] <= q).collect();
            assert_eq!(rows[start[q]..start[q + 1]], want[..], "column {q}");
        }
    }

    /// K = [[4, 2, 0], [2, 5, 1], [0, 1, 3]]: rows 0 and 1 share body 0, rows 1 and 2 body 1,
    /// so row 0's envelope starts at column 0, rows 1 and 2 at column 1 (K_20 = 0 is outside).
    /// x = (1, −2, 3): K x = (4 − 4, 2 − 10 + 3, −2 + 9) = (0, −5, 7).
    fn spd() -> Envelope {
        let bodies = [[Some(0), None], [Some(0), Some(1)], [Some(1), None]];
        system(
            &[&[4.0], &[2.0, 5.0], &[1.0, 3.0]],
            &bodies,
            &[0.0, -5.0, 7.0],
        )
    }

    #[test]
    fn the_envelope_starts_at_the_first_row_sharing_a_body() {
        let mut k = spd();
        assert_eq!(k.stored(), 5);
        assert_eq!(k.row_mut(0), (0, &mut [4.0][..]));
        assert_eq!(k.row_mut(1), (0, &mut [2.0, 5.0][..]));
        assert_eq!(k.row_mut(2), (1, &mut [1.0, 3.0][..]));
    }

    #[test]
    fn dropped_inverts_a_symmetric_positive_definite_matrix() {
        let x = spd()
            .solve(Pivots::Dropped)
            .expect("dropped always answers")
            .to_vec();
        for (x, want) in x.iter().zip([1.0, -2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14, "{x:?}");
        }
    }

    #[test]
    fn a_redundant_row_gets_zero_when_dropped() {
        // Two equal rows: K = [[2, 2], [2, 2]], rhs (2, 2). L₀₀ = √2, L₁₀ = 2/√2 = √2,
        // L₁₁² = 2 − 2 = 0: row 1 is dropped (1/L₁₁ := 0). y = (2/√2, 0), x₁ = 0,
        // x₀ = y₀/√2 = 1: λ = (1, 0) solves it.
        let bodies = [[Some(0), None], [Some(0), None]];
        let mut k = system(&[&[2.0], &[2.0, 2.0]], &bodies, &[2.0, 2.0]);
        let x = k.solve(Pivots::Dropped).expect("dropped always answers");
        assert!((x[0] - 1.0).abs() < 1e-14 && x[1] == 0.0, "{x:?}");
    }

    #[test]
    fn the_policies_agree_on_a_well_conditioned_matrix_up_to_epsilon() {
        // Regularised solves (K + ε𝟙) x = b, ε = 1e-10 · max Kᵢᵢ = 5e-10, so to first order
        // x_ε = x − ε K⁻¹ x (the ε² term is ~1e-19). K⁻¹ = adj(K)/det K, det K = 4·14 − 2·6 = 44:
        // K⁻¹ = [[14, −6, 2], [−6, 12, −4], [2, −4, 16]] / 44, and
        // K⁻¹ x = (14 + 12 + 6, −6 − 24 − 12, 2 + 8 + 48)/44 = (8/11, −21/22, 29/22).
        let dropped = spd().solve(Pivots::Dropped).expect("an answer").to_vec();
        let regularised = spd()
            .solve(Pivots::Regularised)
            .expect("an answer")
            .to_vec();
        let epsilon = 5e-10;
        let shift = [8.0 / 11.0, -21.0 / 22.0, 29.0 / 22.0];
        for p in 0..3 {
            let want = [1.0, -2.0, 3.0][p] - epsilon * shift[p];
            assert!((regularised[p] - want).abs() < 1e-14, "{regularised:?}");
            // The two differ by ε K⁻¹ x only: below 1e-9, far above round-off (1e-15).
            let apart = (regularised[p] - dropped[p]).abs();
            assert!(apart < 1e-9 && apart > 1e-11, "{regularised:?} {dropped:?}");
        }
    }

    #[test]
    fn on_a_singular_matrix_regularised_gives_the_minimum_norm_answer_and_dropped_a_zero() {
        // K = [[2, 2], [2, 2]] = 2 (1, 1)(1, 1)ᵀ, b = (2, 2): every x with x₀ + x₁ = 1 solves
        // it. Regularised, ε = 2e-10: b lies along (1, 1), K's eigenvector of eigenvalue 4,
        // so x = b/(4 + ε) = (½, ½)(1 − ε/4 + …), the minimum-norm solution. Its split
        // x₀ − x₁ is known only to the rounding of D₁ = 2 + ε − 4/(2 + ε) ≈ 2ε: ulp(2)/2ε ≈ 1e-6
        // relative; its sum x₀ + x₁ = 4/(4 + ε) = 1 − ε/4 + …, along K's range, to round-off.
        // Dropped: (1, 0), row 1 redundant (previous test).
        let bodies = [[Some(0), None], [Some(0), None]];
        let k = system(&[&[2.0], &[2.0, 2.0]], &bodies, &[2.0, 2.0]);
        let regularised = k
            .clone()
            .solve(Pivots::Regularised)
            .expect("an answer")
            .to_vec();
        let dropped = k
            .clone()
            .solve(Pivots::Dropped)
            .expect("an answer")
            .to_vec();
        let sum = regularised[0] + regularised[1];
        assert!((sum - (1.0 - 5e-11)).abs() < 1e-14, "{regularised:?}");
        for x in &regularised {
            assert!((x - 0.5).abs() < 1e-5, "{regularised:?}");
        }
        assert!(
            (dropped[0] - 1.0).abs() < 1e-14 && dropped[1] == 0.0,
            "{dropped:?}"
        );
    }

    #[test]
    fn regularised_declines_an_indefinite_matrix_and_dropped_drops_its_row() {
        // K = [[1, 2], [2, 1]] (eigenvalues 3 and −1): D₁ = 1 + ε − 4/(1 + ε) ≈ −3 < 0, no
        // answer. Dropped: L₁₁² = 1 − 2² = −3 ≤ tolerance, row 1 gets 0; b = (1, 5):
        // x = (1/1, 0) = (1, 0).
        let bodies = [[Some(0), None], [Some(0), None]];
        let k = system(&[&[1.0], &[2.0, 1.0]], &bodies, &[1.0, 5.0]);
        assert!(k.clone().solve(Pivots::Regularised).is_none());
        let x = k
            .clone()
            .solve(Pivots::Dropped)
            .expect("an answer")
            .to_vec();
        assert_eq!(x, [1.0, 0.0]);
    }

    #[test]
    fn a_long_chain_is_banded_and_both_back_substitutions_are_right() {
        // m = 100 rows (above SMALL: the regularised back substitution lists columns), row p
        // acting on bodies p and p + 1: tridiagonal, 2 on the diagonal and −1 beside it (a
        // string of springs). x = 1 everywhere: b = (1, 0, …, 0, 1). The envelope: row 0 one
        // entry, every other row two: 199 stored.
        // Regularised, ε = 2e-10: x_ε = x − ε K⁻¹ x, K⁻¹ x = (p + 1)(m − p)/2 ≤ 50·51/2 = 1275
        // (the discrete parabola: −z_{p−1} + 2 z_p − z_{p+1} = 1, z = 0 outside), so the shift
        // is at most 2.6e-7, and ε (p + 1)(m − p)/2 to first order.
        let m = 100;
        let rows: Vec<[f64; 2]> = vec![[-1.0, 2.0]; m];
        let slices: Vec<&[f64]> = (0..m)
            .map(|p| if p == 0 { &rows[p][1..] } else { &rows[p][..] })
            .collect();
        let bodies: Vec<[Option<usize>; 2]> = (0..m).map(|p| [Some(p), Some(p + 1)]).collect();
        let mut rhs = vec![0.0; m];
        rhs[0] = 1.0;
        rhs[m - 1] = 1.0;
        let k = system(&slices, &bodies, &rhs);
        assert_eq!(k.stored(), 199);
        let dropped = k
            .clone()
            .solve(Pivots::Dropped)
            .expect("an answer")
            .to_vec();
        let regularised = k
            .clone()
            .solve(Pivots::Regularised)
            .expect("an answer")
            .to_vec();
        for p in 0..m {
            assert!((dropped[p] - 1.0).abs() < 1e-11, "{p}: {}", dropped[p]);
            let shift = 2e-10 * ((p + 1) * (m - p)) as f64 / 2.0;
            assert!(
                (regularised[p] - (1.0 - shift)).abs() < 1e-11,
                "{p}: {}",
                regularised[p]
            );
        }
    }
}
