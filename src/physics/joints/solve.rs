//! The multipliers: `(J W Jᵀ) λ = rhs`, a small symmetric solve over every joint row.
//!
//! ```text
//! K_ij = Σ over the bodies β rows i and j share:  lin_i^β·lin_j^β / m_β + ang_i^β·I⁻¹_β ang_j^β
//! K λ = rhs   (Cholesky K = L Lᵀ inside K's block envelope, redundant rows dropped)
//! ```
//!
//! **Blocks.** Consecutive rows acting on the same two bodies (a joint's 1 to 6 rows, or a run
//! of contact rows) form one block of K. When every block shares bodies only with the block
//! just before it (a chain in order: joint k joins body k to body k − 1), K is
//! block-tridiagonal, and it is solved in blocks padded to S = the widest block's rows
//! (S ≤ 6; a padding row has K_ii = 1, no coupling and rhs 0, so its multiplier is 0 and the
//! others are exactly those of the unpadded system), with loops of fixed length S:
//!
//! ```text
//! K_kk      = Σ_{β ∈ k}  Lin_kβ Lin_kβᵀ / m_β + Ang_kβ (I⁻¹_β Ang_kβᵀ)       (lower half)
//! K_{k,k−1} = Σ_{β ∈ k ∩ k−1}  Lin_kβ Lin_{k−1,β}ᵀ / m_β + Ang_kβ (I⁻¹_β Ang_{k−1,β}ᵀ)
//! B_k = K_{k,k−1} L_{k−1}⁻ᵀ,   L_k L_kᵀ = K_kk − B_k B_kᵀ
//! y_k = L_k⁻¹ (b_k − B_k y_{k−1}),   x_k = L_k⁻ᵀ (y_k − B_{k+1}ᵀ x_{k+1})
//! ```
//!
//! with Lin_kβ, Ang_kβ the block's rows' parts on body β (S × 3) and I⁻¹ Ang computed once per
//! block and side. The rows past the last one with a linear part (a hinge's two angular rows,
//! a fixed joint's three) skip the linear products. For a chain of 10 hinges (50 rows) that is
//! about 10 · (55 + 200) multiply–adds of 3-vectors and scalars with no index arithmetic,
//! where the scalar envelope below spends most of its time on bookkeeping per entry; the
//! factor is kept, so a second right-hand side costs only the substitutions ([`again`]).
//!
//! **Point rows.** When every block starts with three point rows (ball, hinge, fixed: linear
//! part ±e_k, angular part r × (±e_k), whose k-th component is exactly 0) and has no other
//! linear part, the linear products are δ_ij/m (K_kk) and ±δ_ij/m (K_{k,k−1}, − when the
//! shared body is A of one block and B of the other): added directly, no linear parts stored;
//! and I⁻¹ (r × e_k) takes two of I⁻¹'s columns, the dot products with r × e_k two terms —
//! the dropped terms are exact zeros, so K is the same number for number.
//!
//! Anything else (a single block — one joint, with its limit's and motor's rows —, a loop, a
//! body with three joints, the contact passes' joint and contact rows) is solved in the
//! envelope (skyline) storage of `physics::envelope`, row by row, as
//! before: K summed body by body over the pairs of rows that share it.
//!
//! **Pivots.** K is symmetric positive definite when the rows are independent. A redundant row
//! (a ball joint doubling a hinge's point rows, a closed loop) has a pivot L_pp² below 1e-12 of
//! K's largest diagonal entry: 1/L_pp := 0, its multiplier is 0 and the others carry the load
//! (as `physics::envelope`'s dropped policy does).
//!
//! The matrix is rebuilt and factored at every evaluation of f(Y) (rk4: four times a step).
//! The factor is not reused across rk4's stages: each stage's K is at its own
//! configuration, and an old factor would make λ, hence the method, inexact. The step's last
//! factor is lent to the projection after the step (`projection`'s nearby factor: a chord
//! iteration run to the projection's own tolerances, so no method loses its order).
//!
//! **Two builds.** The banded factor (fill the blocks' parts, assemble K's blocks, factor)
//! and its substitutions are compiled twice, plain and with AVX2, and `physics::simd::avx2`
//! picks at run time (as the cloth and soft-step do): no fused multiply–add, so both give
//! the same bits (tested). The system's joint reactions (`System::add_joint_reactions`) and
//! the projection are built the same way. Callgrind, the 10-hinge chain (rk4, dt 1e-3,
//! `examples/chain_steps`): 274.0k instructions per step before the split and the two
//! builds, 213.5k after (212.6k re-measured), 196.7k with the projection on the last stage's
//! factor and B_k stored by columns; MuJoCo 4.0.1's RK4 hinge chain counted the same way:
//! 112.5k (114.2k re-counted). A chain of ball and hinge joints skips the rows: `chain` keeps
//! each joint's rows compact and fills the blocks' parts from them (`chain_multipliers`,
//! the same K bit for bit), its rhs, rates and reactions summed a joint at a time: 196.5k →
//! 142.4k per step, the projection included.

use super::chain::Link;
use super::rows::Row;
use crate::physics::envelope::{Envelope, Pivots};
#[cfg(target_arch = "x86_64")]
use crate::physics::simd::avx2;
use nalgebra::{Matrix3, Vector3};

/// A row touching a body: (row, linear part, I⁻¹ · angular part, angular part).
type Touch = (usize, Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// No body (the world's side of a row) or no block.
const NONE: usize = usize::MAX;

/// A run of consecutive rows on the same bodies: one block row of K.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Block {
    /// Its first row and how many rows it has.
    row: usize,
    size: usize,
    /// Its bodies A and B (NONE: the world).
    bodies: [usize; 2],
    /// Whether its rows with a linear part are exactly three point rows first (ball, hinge,
    /// fixed: lin = ±e_k, ang = r × (±e_k) with a zero k-th component), the others angular
    /// — and every block's are (else false for all).
    points: bool,
}

/// Whether rows `rows` (a block) are three point rows — linear part e_0, e_1, e_2 — then rows
/// with no linear part.
fn point_rows(rows: &[Row]) -> bool {
    rows.len() >= 3
        && rows.iter().enumerate().all(|(i, r)| {
            if i < 3 {
                r.axis.d == Vector3::ith(i, 1.0)
            } else {
                r.axis.d == Vector3::zeros()
            }
        })
}

/// The two indices other than k (k < 3), in order.
const OTHERS: [[usize; 2]; 3] = [[1, 2], [0, 2], [0, 1]];

/// `a · b` of two 3-vectors where a's k-th component is ±0: the two other products, summed
/// in the order `dot3` sums them (so the same number, a zero term dropped).
#[inline(always)]
fn dot_without(a: &[f64; 3], b: &[f64; 3], k: usize) -> f64 {
    let [p, q] = OTHERS[k];
    a[p] * b[p] + a[q] * b[q]
}

/// Reused buffers of the solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solver {
    blocks: Vec<Block>,
    /// Per body: the first row acting on it.
    first_row: Vec<usize>,
    /// The envelope solve's K, then its factor, and per body the rows touching it (row,
    /// linear part, I⁻¹ angular part, angular part).
    system: Envelope,
    touching: Vec<Vec<Touch>>,
    /// Whether every block's envelope starts at the previous block or at itself (a chain in
    /// order: K block-tridiagonal), and the most rows a block has.
    banded: bool,
    widest: usize,
    /// The rows of the last factor.
    solved: usize,
    /// The banded solve's buffers, per block.
    parts: Vec<[Parts; 2]>,
    diagonal: Vec<Square>,
    /// K_{k,k−1}, then B_k, transposed: `below[k][j][i]` is row i, column j (a column of the
    /// block contiguous, so the factor's and the forward substitution's products run down
    /// columns, lane by lane).
    below: Vec<Square>,
    pivots: Vec<Column>,
    solution: Vec<Column>,
}

/// The most rows of a block the banded solve takes (a fixed joint's).
const WIDEST: usize = 6;

/// A block of K or L (the first S × S entries used).
type Square = [[f64; WIDEST]; WIDEST];

/// A block's share of a vector.
type Column = [f64; WIDEST];

/// One side of a block's rows, each part a 3-vector per row: lin, lin / m, ang and I⁻¹ ang
/// (zero past the block's rows).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Parts {
    /// The rows past this one have no linear part (a hinge's or a fixed joint's angular rows);
    /// 0 in a block of point rows, whose linear parts are not stored.
    linear: usize,
    /// 1/m of its body.
    inv_mass: f64,
    lin: [[f64; 3]; WIDEST],
    scaled: [[f64; 3]; WIDEST],
    ang: [[f64; 3]; WIDEST],
    weighted: [[f64; 3]; WIDEST],
}

/// `a · b` of two 3-vectors.
#[inline(always)]
fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The inverse mass and world inverse inertia of each body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inverse {
    pub mass: f64,
    pub inertia: Matrix3<f64>,
}

/// A row's linear and angular parts on one side (0: A, 1: B).
#[inline(always)]
fn side(row: &Row, side: usize) -> (Vector3<f64>, Vector3<f64>) {
    if side == 0 {
        (row.lin_a(), row.ang_a())
    } else {
        (row.lin_b(), row.ang_b())
    }
}

/// Where the banded factor reads the blocks' rows from: rows, or a chain's compact rows
/// (`chain`: one link per block, the same numbers).
#[derive(Clone, Copy)]
enum Source<'a> {
    Rows(&'a [Row]),
    Links(&'a [Link]),
}

/// Solves `(J W Jᵀ) λ = rhs` for λ, written over `rhs`.
pub fn multipliers(rows: &[Row], inverse: &[Inverse], rhs: &mut [f64], solver: &mut Solver) {
    let x = &mut rhs[..rows.len()];
    solver.group(rows, inverse);
    solver.solved = 0;
    if solver.banded && solver.widest <= WIDEST && solver.blocks.len() > 1 {
        banded_factor(solver, Source::Rows(rows), inverse);
    } else {
        envelope(rows, inverse, x, solver);
        return;
    }
    solver.solved = rows.len();
    again(x, solver);
}

/// [`multipliers`] for a chain's compact rows (`chain::Chain`, two or more links in chain
/// order): one block per link, of its rows, every block of point rows; the same factor, kept
/// for [`again`] as the rows' would be.
pub(super) fn chain_multipliers(
    links: &[Link],
    inverse: &[Inverse],
    rhs: &mut [f64],
    solver: &mut Solver,
) {
    solver.blocks.clear();
    solver.banded = true;
    solver.widest = 0;
    let mut row = 0;
    for link in links {
        let size = link.rows();
        solver.widest = solver.widest.max(size);
        solver.blocks.push(Block {
            row,
            size,
            bodies: [link.a, link.b.unwrap_or(NONE)],
            points: true,
        });
        row += size;
    }
    banded_factor(solver, Source::Links(links), inverse);
    solver.solved = row;
    again(&mut rhs[..row], solver);
}

/// The banded factor of the grouped blocks, with AVX2 when the CPU has it.
#[inline(always)]
fn banded_factor(solver: &mut Solver, source: Source, inverse: &[Inverse]) {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the CPU has AVX2.
        unsafe { factor_avx2(solver, source, inverse) };
        return;
    }
    factor_plain(solver, source, inverse);
}

/// The envelope solve (`physics::envelope`, dropped pivots) for what is not a chain in
/// order: K summed body by body over the pairs of rows that share it, into the envelope of
/// each row (its columns from the first row sharing one of its bodies).
fn envelope(rows: &[Row], inverse: &[Inverse], rhs: &mut [f64], solver: &mut Solver) {
    let n = rows.len();
    // Per body, the rows that touch it (row, its linear part, W·its angular part, its
    // angular part): K is summed body by body, over pairs of rows that share it.
    solver.touching.resize_with(inverse.len(), Vec::new);
    for list in &mut solver.touching {
        list.clear();
    }
    for (i, r) in rows.iter().enumerate() {
        let wa = inverse[r.a()].inertia * r.ang_a();
        solver.touching[r.a()].push((i, r.lin_a(), wa, r.ang_a()));
        if let Some(b) = r.b() {
            let wb = inverse[b].inertia * r.ang_b();
            solver.touching[b].push((i, r.lin_b(), wb, r.ang_b()));
        }
    }
    let system = &mut solver.system;
    system.reset(n);
    for (i, r) in rows.iter().enumerate() {
        system.fill_row(i, [Some(r.a()), r.b()], |_| None);
    }
    for (body, list) in solver.touching.iter().enumerate() {
        let inv_mass = inverse.get(body).map_or(0.0, |b| b.mass);
        for (p, &(i, lin_i, w_i, _)) in list.iter().enumerate() {
            let (first, row) = system.row_mut(i);
            for &(j, lin_j, _, ang_j) in &list[..=p] {
                // Rows are pushed in order: first(i) ≤ j ≤ i.
                row[j - first] += lin_i.dot(&lin_j) * inv_mass + w_i.dot(&ang_j);
            }
        }
    }
    // The dropped policy always answers.
    let solved = system.solve_into(Pivots::Dropped, rhs);
    debug_assert!(solved);
}

/// Solves `K λ = rhs` again with the factor of the last [`multipliers`] call (the same number
/// of rows; K as it was then), written over `rhs`, when that call was banded (false, `rhs`
/// untouched: the envelope solve keeps no factor apart).
pub fn again(rhs: &mut [f64], solver: &mut Solver) -> bool {
    let x = &mut rhs[..solver.solved];
    if solver.solved > 0 {
        #[cfg(target_arch = "x86_64")]
        if avx2() {
            // SAFETY: the CPU has AVX2.
            unsafe { substitute_avx2(solver, x) };
        } else {
            substitute_plain(solver, x);
        }
        #[cfg(not(target_arch = "x86_64"))]
        substitute_plain(solver, x);
        true
    } else {
        false
    }
}

impl Solver {
    /// Whether it holds a banded factor of `rows` rows (the last [`multipliers`] call's), which
    /// [`again`] solves with.
    pub fn holds(&self, rows: usize) -> bool {
        rows > 0 && self.solved == rows
    }
}

/// The banded factor at the widest block's width (`Solver::banded`), for any CPU.
#[inline(always)]
fn factor_plain(solver: &mut Solver, source: Source, inverse: &[Inverse]) {
    match solver.widest {
        1 => solver.banded::<1>(source, inverse),
        2 => solver.banded::<2>(source, inverse),
        3 => solver.banded::<3>(source, inverse),
        4 => solver.banded::<4>(source, inverse),
        5 => solver.banded::<5>(source, inverse),
        _ => solver.banded::<6>(source, inverse),
    }
}

/// [`factor_plain`] compiled with AVX2 (no fused multiply–add: the same bits).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn factor_avx2(solver: &mut Solver, source: Source, inverse: &[Inverse]) {
    factor_plain(solver, source, inverse);
}

/// The banded substitutions at the widest block's width, for any CPU.
#[inline(always)]
fn substitute_plain(solver: &mut Solver, x: &mut [f64]) {
    match solver.widest {
        1 => solver.banded_substitute::<1>(x),
        2 => solver.banded_substitute::<2>(x),
        3 => solver.banded_substitute::<3>(x),
        4 => solver.banded_substitute::<4>(x),
        5 => solver.banded_substitute::<5>(x),
        _ => solver.banded_substitute::<6>(x),
    }
}

/// [`substitute_plain`] compiled with AVX2 (the same bits).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn substitute_avx2(solver: &mut Solver, x: &mut [f64]) {
    substitute_plain(solver, x);
}

impl Solver {
    /// The blocks (runs of rows on the same bodies), whether K is block-tridiagonal (each
    /// block's envelope starts at the previous block or at itself: no body of block k is
    /// touched by a block before k − 1), and the widest block.
    fn group(&mut self, rows: &[Row], inverse: &[Inverse]) {
        let n = rows.len();
        self.blocks.clear();
        self.first_row.clear();
        self.first_row.resize(inverse.len(), NONE);
        self.banded = true;
        self.widest = 0;
        let mut p = 0;
        while p < n {
            let (a, b) = (rows[p].a(), rows[p].b());
            let mut size = 1;
            while p + size < n && rows[p + size].a() == a && rows[p + size].b() == b {
                size += 1;
            }
            let bodies = [a, b.unwrap_or(NONE)];
            // The envelope's first column: the first row acting on one of its bodies.
            let mut column = p;
            for &body in bodies.iter().filter(|&&body| body != NONE) {
                if self.first_row[body] == NONE {
                    self.first_row[body] = p;
                }
                column = column.min(self.first_row[body]);
            }
            if let Some(before) = self.blocks.last() {
                self.banded &= column >= before.row;
            }
            self.widest = self.widest.max(size);
            self.blocks.push(Block {
                row: p,
                size,
                bodies,
                points: point_rows(&rows[p..p + size]),
            });
            p += size;
        }
        // The point rows' shortcut needs both blocks of every off-diagonal block on it.
        if !self.blocks.iter().all(|b| b.points) {
            for block in &mut self.blocks {
                block.points = false;
            }
        }
    }

    /// The block-tridiagonal solve (module doc), every block padded to S rows: a padding row
    /// has K_ii = 1, no coupling and rhs 0 (so its multiplier is 0 and the others are exactly
    /// those of the unpadded system).
    ///
    /// ```text
    /// B_k = K_{k,k−1} L_{k−1}⁻ᵀ       (0 when blocks k and k−1 share no body)
    /// L_k L_kᵀ = K_kk − B_k B_kᵀ
    /// y_k = L_k⁻¹ (b_k − B_k y_{k−1}),   x_k = L_k⁻ᵀ (y_k − B_{k+1}ᵀ x_{k+1})
    /// ```
    #[inline(always)]
    fn banded<const S: usize>(&mut self, source: Source, inverse: &[Inverse]) {
        let count = self.blocks.len();
        self.parts.resize(count, Default::default());
        self.diagonal.resize(count, Square::default());
        self.below.resize(count, Square::default());
        self.pivots.resize(count, Column::default());
        self.solution.resize(count, Column::default());
        fill::<S>(&self.blocks, &mut self.parts, source, inverse);
        let largest = assemble::<S>(
            &self.blocks,
            &self.parts,
            &mut self.diagonal,
            &mut self.below,
        );
        factor::<S>(
            &mut self.diagonal,
            &mut self.below,
            &mut self.pivots,
            1e-12 * largest,
        );
    }

    /// `L y = b`, block by block down, then `Lᵀ x = y`, block by block up, over x = b.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn banded_substitute<const S: usize>(&mut self, x: &mut [f64]) {
        let count = self.blocks.len();
        let Solver {
            blocks,
            diagonal,
            below,
            pivots,
            solution,
            ..
        } = self;
        for k in 0..count {
            let block = &blocks[k];
            let mut y = Column::default();
            y[..block.size].copy_from_slice(&x[block.row..block.row + block.size]);
            if k > 0 {
                let (bt, previous) = (&below[k], &solution[k - 1]);
                for c in 0..S {
                    for i in 0..S {
                        y[i] -= bt[c][i] * previous[c];
                    }
                }
            }
            let (l, r) = (&diagonal[k], &pivots[k]);
            for i in 0..S {
                for c in 0..i {
                    y[i] -= l[i][c] * y[c];
                }
                y[i] *= r[i];
            }
            solution[k] = y;
        }
        for k in (0..count).rev() {
            let mut z = solution[k];
            if k + 1 < count {
                let (bt, next) = (&below[k + 1], &solution[k + 1]);
                for i in 0..S {
                    for c in 0..S {
                        z[i] -= bt[i][c] * next[c];
                    }
                }
            }
            let (l, r) = (&diagonal[k], &pivots[k]);
            for i in (0..S).rev() {
                for c in i + 1..S {
                    z[i] -= l[c][i] * z[c];
                }
                z[i] *= r[i];
            }
            solution[k] = z;
            let block = &blocks[k];
            x[block.row..block.row + block.size].copy_from_slice(&z[..block.size]);
        }
    }
}

/// Each side's parts of every block: lin, lin/m, ang, I⁻¹ ang (zero past the block's rows).
#[inline(always)]
fn fill<const S: usize>(
    blocks: &[Block],
    parts: &mut [[Parts; 2]],
    source: Source,
    inverse: &[Inverse],
) {
    for (k, (block, sides)) in blocks.iter().zip(parts.iter_mut()).enumerate() {
        for (side_index, (&body, part)) in block.bodies.iter().zip(sides).enumerate() {
            if body == NONE {
                continue;
            }
            let inv = &inverse[body];
            part.linear = 0;
            part.inv_mass = inv.mass;
            let size = block.size;
            match source {
                Source::Links(links) => {
                    let link = &links[k];
                    if side_index == 0 {
                        fill_points::<S>(size, |i| link.row(i).1, inv, part);
                    } else {
                        fill_points::<S>(size, |i| link.row(i).2, inv, part);
                    }
                }
                Source::Rows(rows) => {
                    let rows = &rows[block.row..block.row + size];
                    match (block.points, side_index) {
                        (true, 0) => fill_points::<S>(size, |i| rows[i].ang_a(), inv, part),
                        (true, _) => fill_points::<S>(size, |i| rows[i].ang_b(), inv, part),
                        (false, _) => fill_rows::<S>(rows, side_index, inv, part),
                    }
                }
            }
        }
    }
}

/// `I⁻¹ ang` of point row k (k < 3), whose angular part `ang` = r × (±e_k) has a zero k-th
/// component: two of I⁻¹'s columns (the zero term of the product dropped, the others summed
/// in its order).
#[inline(always)]
fn point_weight(inertia: &Matrix3<f64>, ang: &Vector3<f64>, k: usize) -> [f64; 3] {
    let [p, q] = OTHERS[k];
    let w = inertia.column(p) * ang[p] + inertia.column(q) * ang[q];
    [w.x, w.y, w.z]
}

/// One side of a block of `size` point rows (three point rows, then angular rows): ang and
/// I⁻¹ ang (`point_weight` for the point rows); their linear parts ±e_i give K's entries
/// ±δ_ij/m directly, no parts stored. `ang(i)` is the side's angular part of row i.
#[inline(always)]
fn fill_points<const S: usize>(
    size: usize,
    ang: impl Fn(usize) -> Vector3<f64>,
    inv: &Inverse,
    part: &mut Parts,
) {
    for k in 0..3 {
        let a = ang(k);
        part.ang[k] = [a.x, a.y, a.z];
        part.weighted[k] = point_weight(&inv.inertia, &a, k);
    }
    for i in 3..size {
        let a = ang(i);
        let w = inv.inertia * a;
        part.ang[i] = [a.x, a.y, a.z];
        part.weighted[i] = [w.x, w.y, w.z];
    }
    for i in size..S {
        part.ang[i] = [0.0; 3];
        part.weighted[i] = [0.0; 3];
    }
}

/// One side of any other block: every part, and how many rows have a linear part.
#[inline(always)]
fn fill_rows<const S: usize>(rows: &[Row], side_index: usize, inv: &Inverse, part: &mut Parts) {
    for i in 0..S {
        if let Some(row) = rows.get(i) {
            let (lin, ang) = side(row, side_index);
            let w = inv.inertia * ang;
            part.lin[i] = [lin.x, lin.y, lin.z];
            part.scaled[i] = [lin.x * inv.mass, lin.y * inv.mass, lin.z * inv.mass];
            part.ang[i] = [ang.x, ang.y, ang.z];
            part.weighted[i] = [w.x, w.y, w.z];
            if lin != Vector3::zeros() {
                part.linear = i + 1;
            }
        } else {
            part.lin[i] = [0.0; 3];
            part.scaled[i] = [0.0; 3];
            part.ang[i] = [0.0; 3];
            part.weighted[i] = [0.0; 3];
        }
    }
}

/// K_kk and K_{k,k−1}, body by body, into `diagonal` and `below`; returns K's largest
/// diagonal entry.
// Index loops of fixed length S, written as the formulas index the blocks.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn assemble<const S: usize>(
    blocks: &[Block],
    parts: &[[Parts; 2]],
    diagonal: &mut [Square],
    below: &mut [Square],
) -> f64 {
    let mut largest = 0.0_f64;
    for k in 0..blocks.len() {
        let block = &blocks[k];
        let d = &mut diagonal[k];
        for (i, row) in d.iter_mut().enumerate().take(S) {
            for (j, entry) in row.iter_mut().enumerate().take(i + 1) {
                *entry = if i == j && i >= block.size { 1.0 } else { 0.0 };
            }
        }
        for side_index in 0..2 {
            if block.bodies[side_index] != NONE {
                add_diagonal::<S>(d, &parts[k][side_index], block.points);
            }
        }
        for i in 0..block.size {
            largest = largest.max(d[i][i]);
        }
        if k == 0 {
            continue;
        }
        let b = &mut below[k];
        *b = Square::default();
        let before = &blocks[k - 1];
        for (sp, &body) in block.bodies.iter().enumerate() {
            for (sq, &other) in before.bodies.iter().enumerate() {
                if body == NONE || body != other {
                    continue;
                }
                let (p, q) = (&parts[k][sp], &parts[k - 1][sq]);
                // (±e_i)·(±e_j)/m of point rows: +δ_ij/m when the body is on the same side
                // of both blocks, −δ_ij/m otherwise.
                let shared = if sp == sq { p.inv_mass } else { -p.inv_mass };
                add_below::<S>(b, p, q, block.points && before.points, shared);
            }
        }
    }
    largest
}

/// One side's share of K_kk (lower half): ang_i · I⁻¹ ang_j, and the linear parts' products
/// (`points`: δ_ij/m on the three point rows).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn add_diagonal<const S: usize>(d: &mut Square, p: &Parts, points: bool) {
    if points {
        for i in 0..S {
            for j in 0..=i {
                d[i][j] += if i < 3 {
                    dot_without(&p.ang[i], &p.weighted[j], i)
                } else {
                    dot3(&p.ang[i], &p.weighted[j])
                };
            }
        }
        // (±e_i)·(±e_j)/m = δ_ij/m.
        for (i, row) in d.iter_mut().enumerate().take(3) {
            row[i] += p.inv_mass;
        }
        return;
    }
    for i in 0..S {
        for j in 0..=i {
            d[i][j] += dot3(&p.ang[i], &p.weighted[j]);
        }
    }
    for i in 0..p.linear {
        for j in 0..=i {
            d[i][j] += dot3(&p.lin[i], &p.scaled[j]);
        }
    }
}

/// One shared body's share of K_{k,k−1} (transposed: `b[j][i]`): block k's side `p` against
/// block k − 1's side `q` (`points`: both blocks of point rows, whose linear products are
/// `shared` δ_ij).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn add_below<const S: usize>(b: &mut Square, p: &Parts, q: &Parts, points: bool, shared: f64) {
    if points {
        for i in 0..S {
            for j in 0..S {
                b[j][i] += if i < 3 {
                    dot_without(&p.ang[i], &q.weighted[j], i)
                } else {
                    dot3(&p.ang[i], &q.weighted[j])
                };
            }
        }
        for (i, row) in b.iter_mut().enumerate().take(3) {
            row[i] += shared;
        }
        return;
    }
    for i in 0..S {
        for j in 0..S {
            b[j][i] += dot3(&p.ang[i], &q.weighted[j]);
        }
    }
    for i in 0..p.linear {
        for j in 0..q.linear {
            b[j][i] += dot3(&p.lin[i], &q.scaled[j]);
        }
    }
}

/// The factor, block by block, over K's blocks in place: B_k = K_{k,k−1} L_{k−1}⁻ᵀ into
/// `below` (transposed), L_k (and 1/L_k's pivots, 0 for a pivot² at or below `tiny`) into `diagonal`.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn factor<const S: usize>(
    diagonal: &mut [Square],
    below: &mut [Square],
    pivots: &mut [Column],
    tiny: f64,
) {
    for k in 0..diagonal.len() {
        if k > 0 {
            let (done, rest) = diagonal.split_at_mut(k);
            let (l, d) = (&done[k - 1], &mut rest[0]);
            let r = &pivots[k - 1];
            // Column by column (B transposed: `bt[j]` is B's column j), each product run
            // over a column's S entries at once.
            let bt = &mut below[k];
            for j in 0..S {
                let mut t = bt[j];
                for c in 0..j {
                    let (column, ljc) = (&bt[c], l[j][c]);
                    for i in 0..S {
                        t[i] -= column[i] * ljc;
                    }
                }
                for i in 0..S {
                    bt[j][i] = t[i] * r[j];
                }
            }
            // D −= B Bᵀ row by row, over a whole row of D at once (its upper part, never
            // read, included).
            for i in 0..S {
                let mut t = d[i];
                for column in bt.iter().take(S) {
                    let bic = column[i];
                    for j in 0..S {
                        t[j] -= bic * column[j];
                    }
                }
                d[i][..S].copy_from_slice(&t[..S]);
            }
        }
        let d = &mut diagonal[k];
        let r = &mut pivots[k];
        for i in 0..S {
            for j in 0..i {
                let mut t = d[i][j];
                for c in 0..j {
                    t -= d[i][c] * d[j][c];
                }
                d[i][j] = t * r[j];
            }
            let mut square = d[i][i];
            for c in 0..i {
                square -= d[i][c] * d[i][c];
            }
            r[i] = if square > tiny {
                1.0 / square.sqrt()
            } else {
                0.0
            };
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::rows::{rows_of, Pose};
    use super::super::{Joint, JointKind};
    use super::*;
    use crate::physics::state::State;
    use nalgebra::{DMatrix, DVector, UnitQuaternion};

    /// A deterministic number in [−1, 1) (a linear congruential sequence).
    pub(in crate::physics::joints) fn next(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    pub(in crate::physics::joints) fn vector(seed: &mut u64) -> Vector3<f64> {
        Vector3::new(next(seed), next(seed), next(seed))
    }

    /// K = J W Jᵀ dense, straight from its definition: J's rows as 6n-vectors, W block
    /// diagonal.
    fn dense(rows: &[Row], inverse: &[Inverse]) -> DMatrix<f64> {
        let n = inverse.len();
        let mut j = DMatrix::<f64>::zeros(rows.len(), 6 * n);
        for (i, r) in rows.iter().enumerate() {
            let mut put = |body: usize, lin: &Vector3<f64>, ang: &Vector3<f64>| {
                for k in 0..3 {
                    j[(i, 6 * body + k)] += lin[k];
                    j[(i, 6 * body + 3 + k)] += ang[k];
                }
            };
            put(r.a(), &r.lin_a(), &r.ang_a());
            if let Some(b) = r.b() {
                put(b, &r.lin_b(), &r.ang_b());
            }
        }
        let mut w = DMatrix::<f64>::zeros(6 * n, 6 * n);
        for (body, inv) in inverse.iter().enumerate() {
            for k in 0..3 {
                w[(6 * body + k, 6 * body + k)] = inv.mass;
            }
            w.view_mut((6 * body + 3, 6 * body + 3), (3, 3))
                .copy_from(&inv.inertia);
        }
        &j * w * j.transpose()
    }

    /// A chain of `kinds.len()` bodies in random poses and motion, joint i joining body i to
    /// body i − 1 (joint 0 to the world), and (`closed`) a ball joint between bodies 2 and 5
    /// closing a loop: its rows, inverse masses and a random rhs.
    fn system(
        kinds: &[JointKind],
        closed: bool,
        seed: &mut u64,
    ) -> (Vec<Row>, Vec<Inverse>, Vec<f64>) {
        let (joints, poses, inverse) = setup(kinds, closed, seed);
        let rows = rows_at(&joints, &poses);
        let want_rows: usize = joints.iter().map(|j| j.kind.rows()).sum();
        assert_eq!(rows.len(), want_rows);
        let rhs: Vec<f64> = (0..rows.len()).map(|_| next(seed)).collect();
        (rows, inverse, rhs)
    }

    /// The joints' rows at `poses`.
    fn rows_at(joints: &[Joint], poses: &[Pose]) -> Vec<Row> {
        let mut rows = Vec::new();
        for (index, joint) in joints.iter().enumerate() {
            let b = joint.b.map_or(Pose::WORLD, |b| poses[b]);
            rows_of(joint, index, &poses[joint.a], &b, &mut rows);
        }
        rows
    }

    /// [`system`]'s joints, poses and inverse masses.
    fn setup(
        kinds: &[JointKind],
        closed: bool,
        seed: &mut u64,
    ) -> (Vec<Joint>, Vec<Pose>, Vec<Inverse>) {
        let seed = &mut *seed;
        let states: Vec<State> = (0..kinds.len())
            .map(|i| State {
                position: Vector3::new(i as f64 * 0.5, 0.0, 0.0) + 0.1 * vector(seed),
                orientation: crate::physics::state::Orientation::Quaternion(
                    UnitQuaternion::from_scaled_axis(vector(seed)),
                ),
                ..State::at_rest()
            })
            .collect();
        let mut joints: Vec<Joint> = kinds
            .iter()
            .enumerate()
            .map(|(i, &kind)| {
                let at = Vector3::new(i as f64 * 0.5, 0.05, 0.0);
                let axis = vector(seed);
                if kind == JointKind::Distance {
                    let other = at + Vector3::new(-0.2, 0.1, 0.0);
                    Joint::distance("d".into(), i, i.checked_sub(1), [at, other], None, &states)
                } else {
                    Joint::at_point("j".into(), kind, i, i.checked_sub(1), at, axis, &states)
                }
            })
            .collect();
        if closed {
            let at = Vector3::new(1.5, 0.3, 0.1);
            joints.push(Joint::at_point(
                "loop".into(),
                JointKind::Ball,
                5,
                Some(2),
                at,
                Vector3::z(),
                &states,
            ));
        }
        // Poses moved off the joints' start, with velocities, and world inverse inertias.
        let poses: Vec<Pose> = states
            .iter()
            .map(|s| Pose {
                x: s.position + 0.01 * vector(seed),
                r: (UnitQuaternion::from_scaled_axis(0.05 * vector(seed))
                    * s.orientation.quaternion())
                .to_rotation_matrix()
                .into_inner(),
                v: vector(seed),
                w: vector(seed),
            })
            .collect();
        let inverse: Vec<Inverse> = poses
            .iter()
            .map(|p| {
                let d = Vector3::new(3.0, 1.5, 2.0) + 0.5 * vector(seed);
                Inverse {
                    mass: 1.0 + next(seed) * 0.5,
                    inertia: p.r * Matrix3::from_diagonal(&d) * p.r.transpose(),
                }
            })
            .collect();
        (joints, poses, inverse)
    }

    /// A chain of ball and hinge joints through its compact rows (`chain`): the factor and
    /// the multipliers are the row path's bit for bit on the same rhs; C is the rows' C, and
    /// the rates J u, the rhs −(J a + J̇u) and the reactions Jᵀ λ, summed a joint at a time,
    /// are the rows' to round-off. A loop or a fixed joint takes the row path.
    #[test]
    fn a_chains_compact_rows_give_the_row_paths_numbers() {
        use super::super::chain::Chain;
        use crate::physics::effects::Loads;
        use JointKind::{Ball, Fixed, Hinge};
        let seed = &mut 5;
        let (joints, poses, inverse) =
            setup(&[Hinge, Ball, Hinge, Hinge, Ball, Hinge], false, seed);
        let rows = rows_at(&joints, &poses);
        let mut chain = Chain::default();
        assert!(chain.build(&joints, &poses));
        assert_eq!(chain.rows(), rows.len());
        let close = |got: &[f64], want: &[f64]| {
            let scale = want.iter().fold(1.0_f64, |m, w| m.max(w.abs()));
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() <= 1e-14 * scale, "{g} against {w}");
            }
        };
        let mut got = Vec::new();
        chain.errors(&mut got);
        let errors: Vec<f64> = rows.iter().map(|r| -r.error).collect();
        assert_eq!(got, errors);
        chain.rates(&poses, &mut got);
        let pose = |b: Option<usize>| b.map_or(Pose::WORLD, |b| poses[b]);
        let rates: Vec<f64> = (rows.iter())
            .map(|r| -super::super::rows::rate(r, &poses[r.a()], &pose(r.b())))
            .collect();
        close(&got, &rates);
        let free: Vec<_> = poses.iter().map(|_| (vector(seed), vector(seed))).collect();
        chain.rhs(&free, &mut got);
        let zero = (Vector3::zeros(), Vector3::zeros());
        let rhs: Vec<f64> = (rows.iter())
            .map(|r| {
                let ((la, aa), (lb, ab)) = (free[r.a()], r.b().map_or(zero, |b| free[b]));
                let j_a = r.lin_a().dot(&la) + r.ang_a().dot(&aa);
                -(j_a + r.lin_b().dot(&lb) + r.ang_b().dot(&ab) + r.bias)
            })
            .collect();
        close(&got, &rhs);
        let (mut by_rows, mut by_chain) = (rhs.clone(), rhs.clone());
        multipliers(&rows, &inverse, &mut by_rows, &mut Solver::default());
        chain.solve(&inverse, &mut by_chain, &mut Solver::default());
        let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&by_rows), bits(&by_chain));
        let mut loads = vec![Loads::default(); poses.len()];
        let mut reactions = vec![Loads::default(); joints.len()];
        chain.apply(&by_chain, &mut loads, &mut reactions);
        let mut want = vec![Loads::default(); poses.len()];
        let mut want_reactions = vec![Loads::default(); joints.len()];
        for (r, &l) in rows.iter().zip(&by_rows) {
            want[r.a()].force += r.lin_a() * l;
            want[r.a()].torque += r.ang_a() * l;
            want_reactions[r.owner].force += r.lin_a() * l;
            want_reactions[r.owner].torque += r.ang_a() * l;
            if let Some(b) = r.b() {
                want[b].force += r.lin_b() * l;
                want[b].torque += r.ang_b() * l;
            }
        }
        let flat = |l: &[Loads]| -> Vec<f64> {
            l.iter()
                .flat_map(|l| {
                    l.force
                        .iter()
                        .chain(l.torque.iter())
                        .copied()
                        .collect::<Vec<_>>()
                })
                .collect()
        };
        close(&flat(&loads), &flat(&want));
        close(&flat(&reactions), &flat(&want_reactions));
        let (looped, poses, _) = setup(&[Hinge, Ball, Hinge, Ball, Hinge, Ball], true, seed);
        assert!(!chain.build(&looped, &poses));
        let (fixed, poses, _) = setup(&[Hinge, Fixed, Hinge], false, seed);
        assert!(!chain.build(&fixed, &poses));
    }

    /// [`system`]'s `K λ = rhs` solved both ways (the block solve and a dense LU); returns
    /// which path the block solve took (banded or the envelope).
    fn check(kinds: &[JointKind], closed: bool, seed: &mut u64) -> bool {
        let (rows, inverse, rhs) = system(kinds, closed, seed);
        let mut lambda = rhs.clone();
        let mut solver = Solver::default();
        multipliers(&rows, &inverse, &mut lambda, &mut solver);
        let k = dense(&rows, &inverse);
        let want = k
            .clone()
            .lu()
            .solve(&DVector::from_vec(rhs.clone()))
            .expect("regular");
        let scale = want.amax();
        for (got, want) in lambda.iter().zip(want.iter()) {
            assert!((got - want).abs() <= 1e-12 * scale, "{got} against {want}");
        }
        let residual = &k * DVector::from_vec(lambda) - DVector::from_vec(rhs);
        assert!(residual.amax() < 1e-12, "{}", residual.amax());
        solver.banded
    }

    /// The block solve equals a dense LU solve of the same J W Jᵀ to 1e-12 (relative), on
    /// chains joined by every kind (ball, hinge, fixed, slider, distance): banded with blocks
    /// of 6 rows; hinges and balls, the balls' blocks padded to 5 rows; a hinge chain; and
    /// every kind with a loop closed (the envelope path).
    #[test]
    fn the_block_solve_equals_a_dense_solve() {
        use JointKind::{Ball, Distance, Fixed, Hinge, Slider};
        let mut seed = 7;
        let every = [Hinge, Ball, Fixed, Slider, Distance, Hinge, Slider, Fixed];
        assert!(check(&every, false, &mut seed));
        assert!(check(
            &[Ball, Hinge, Ball, Ball, Hinge, Hinge],
            false,
            &mut seed
        ));
        assert!(check(&[Hinge; 10], false, &mut seed));
        assert!(!check(&every, true, &mut seed));
    }

    /// The AVX2 build of the banded factor and substitutions gives the plain build's bits, on
    /// a chain of every kind and on a hinge chain (a second right-hand side through `again`).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_avx2_build_gives_the_plain_builds_bits() {
        use JointKind::{Ball, Distance, Fixed, Hinge, Slider};
        let bits = |kinds: &[JointKind], plain: bool| {
            crate::physics::simd::set_plain(plain);
            let (rows, inverse, rhs) = system(kinds, false, &mut 11);
            let mut lambda = rhs.clone();
            let mut solver = Solver::default();
            multipliers(&rows, &inverse, &mut lambda, &mut solver);
            let mut second: Vec<f64> = rhs.iter().map(|x| 0.5 - x).collect();
            assert!(again(&mut second, &mut solver));
            crate::physics::simd::set_plain(false);
            let all: Vec<u64> = lambda.iter().chain(&second).map(|x| x.to_bits()).collect();
            all
        };
        for kinds in [
            &[Hinge, Ball, Fixed, Slider, Distance, Hinge, Slider, Fixed][..],
            &[Hinge; 10][..],
        ] {
            assert_eq!(bits(kinds, true), bits(kinds, false));
        }
    }
}
