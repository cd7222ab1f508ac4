//! The multipliers: `(J W Jᵀ) λ = rhs`, a small symmetric solve over every joint row.
//!
//! ```text
//! K_ij = Σ over the bodies β rows i and j share:  lin_i^β·lin_j^β / m_β + ang_i^β·I⁻¹_β ang_j^β
//! K λ = rhs   (Cholesky K = L Lᵀ inside K's block envelope, redundant rows dropped)
//! ```
//!
//! **Blocks.** Consecutive rows acting on the same two bodies (a joint's 1 to 6 rows, or a run
//! of contact rows) form one block of K. Block P's envelope starts at the first row of the
//! first block sharing one of its bodies, column `first(P)`; no factor entry lies left of it
//! (fill-in stays inside the envelope), so only the entries `first(P)..=p` of each row p are
//! stored, one row after the other. A chain's blocks are tridiagonal (joint k shares body k−1
//! with joint k−1 only): block row k holds K_{k,k−1} and K_{k,k}, and the factorisation is
//! the block-tridiagonal Cholesky
//!
//! ```text
//! L_{k,k−1} = K_{k,k−1} L_{k−1,k−1}⁻ᵀ,    L_kk L_kkᵀ = K_kk − L_{k,k−1} L_{k,k−1}ᵀ
//! ```
//!
//! carried out entry by entry (`factor`). K is assembled block pair by block pair, per shared
//! body: for the body β that blocks P and Q share, with the W-weighted rows w_j = I⁻¹_β ang_j
//! computed once per row and side (not once per pair),
//!
//! ```text
//! K_PQ += [lin_i·lin_j / m_β + ang_i·w_j]   i ∈ P, j ∈ Q   (j ≤ i when Q = P)
//! ```
//!
//! and the blocks sharing a body are found by following, from each block, the previous block
//! on each of its bodies (a list per body, threaded through the blocks: no search).
//!
//! **Pivots.** K is symmetric positive definite when the rows are independent. A redundant row
//! (a ball joint doubling a hinge's point rows, a closed loop) has a pivot L_pp² below 1e-12 of
//! K's largest diagonal entry: 1/L_pp := 0, its multiplier is 0 and the others carry the load
//! (as `physics::envelope`'s dropped policy does).
//!
//! The matrix is rebuilt and factored at every evaluation of f(Y) (rk4: four times a step);
//! for a chain of 10 hinges, 50 rows whose envelope is at most 10 wide, that is about
//! 10 · 170 ≈ 1700 multiply–adds for the factor and 550 block entries to assemble, not a dense
//! 50³/6 ≈ 21000. The factor is not reused across rk4's stages: each stage's K is at its own
//! configuration, and an old factor would make λ, hence the method, inexact.

use super::rows::Row;
use nalgebra::{Matrix3, Vector3};

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
    /// Per side, the previous block acting on the same body (NONE: none).
    previous: [usize; 2],
    /// The first column of its envelope.
    column: usize,
}

/// Reused buffers of the solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solver {
    blocks: Vec<Block>,
    /// Per body: the last block acting on it so far, and the first row acting on it.
    last_block: Vec<usize>,
    first_row: Vec<usize>,
    /// Per row: where its entries start in `factor`, and its first column `first(P)`.
    start: Vec<usize>,
    first: Vec<usize>,
    /// Per row: I⁻¹_A ang_a and I⁻¹_B ang_b.
    weighted: Vec<[Vector3<f64>; 2]>,
    /// K's lower triangle inside the envelope, row by row, then its factor L.
    factor: Vec<f64>,
    /// 1/L_pp (0: a dropped row).
    reciprocal: Vec<f64>,
    /// The envelope's size.
    stored: usize,
    /// Whether every block's envelope starts at the previous block or at itself (a chain in
    /// order: K block-tridiagonal), and the most rows a block has.
    banded: bool,
    widest: usize,
    /// The banded solve's buffers, per block.
    parts: Vec<[Parts; 2]>,
    diagonal: Vec<Square>,
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

/// Body β's share of K between rows i of `p` and rows j of `q`: lin_i·lin_j/m + ang_i·I⁻¹ang_j.
#[inline(always)]
fn share(p: &Parts, i: usize, q: &Parts, j: usize) -> f64 {
    dot3(&p.lin[i], &q.scaled[j]) + dot3(&p.ang[i], &q.weighted[j])
}

/// The inverse mass and world inverse inertia of each body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inverse {
    pub mass: f64,
    pub inertia: Matrix3<f64>,
}

/// `Σ aₖ bₖ` in increasing k.
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sum = 0.0;
    for (x, y) in a.iter().zip(b) {
        sum += x * y;
    }
    sum
}

/// A row's linear and angular parts on one side (0: A, 1: B).
#[inline(always)]
fn side(row: &Row, side: usize) -> (&Vector3<f64>, &Vector3<f64>) {
    if side == 0 {
        (&row.lin_a, &row.ang_a)
    } else {
        (&row.lin_b, &row.ang_b)
    }
}

/// Solves `(J W Jᵀ) λ = rhs` for λ, written over `rhs`.
pub fn multipliers(rows: &[Row], inverse: &[Inverse], rhs: &mut [f64], solver: &mut Solver) {
    let x = &mut rhs[..rows.len()];
    solver.group(rows, inverse);
    if solver.banded {
        match solver.widest {
            1 => return solver.banded::<1>(rows, inverse, x),
            2 => return solver.banded::<2>(rows, inverse, x),
            3 => return solver.banded::<3>(rows, inverse, x),
            4 => return solver.banded::<4>(rows, inverse, x),
            5 => return solver.banded::<5>(rows, inverse, x),
            6 => return solver.banded::<6>(rows, inverse, x),
            _ => {}
        }
    }
    solver.weigh(rows, inverse);
    solver.assemble(rows, inverse);
    solver.factor(rows.len());
    solver.substitute(x);
}

impl Solver {
    /// The blocks, each row's envelope and storage, and the weighted rows.
    fn group(&mut self, rows: &[Row], inverse: &[Inverse]) {
        let n = rows.len();
        self.blocks.clear();
        self.last_block.clear();
        self.last_block.resize(inverse.len(), NONE);
        self.first_row.clear();
        self.first_row.resize(inverse.len(), NONE);
        self.start.resize(n, 0);
        self.first.resize(n, 0);
        self.banded = true;
        self.widest = 0;
        let mut stored = 0;
        let mut p = 0;
        while p < n {
            let (a, b) = (rows[p].a, rows[p].b);
            let mut size = 1;
            while p + size < n && rows[p + size].a == a && rows[p + size].b == b {
                size += 1;
            }
            let bodies = [a, b.unwrap_or(NONE)];
            let index = self.blocks.len();
            let mut previous = [NONE; 2];
            let mut column = p;
            for (side, &body) in bodies.iter().enumerate() {
                if body == NONE {
                    continue;
                }
                previous[side] = self.last_block[body];
                self.last_block[body] = index;
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
                previous,
                column,
            });
            for q in p..p + size {
                self.first[q] = column;
                self.start[q] = stored;
                stored += q + 1 - column;
            }
            p += size;
        }
        self.stored = stored;
    }

    /// The weighted rows I⁻¹ ang on each side, and room for the envelope.
    fn weigh(&mut self, rows: &[Row], inverse: &[Inverse]) {
        self.weighted.clear();
        self.weighted.extend(rows.iter().map(|r| {
            let wb =
                r.b.map_or(Vector3::zeros(), |b| inverse[b].inertia * r.ang_b);
            [inverse[r.a].inertia * r.ang_a, wb]
        }));
        self.factor.clear();
        self.factor.resize(self.stored, 0.0);
        self.reciprocal.resize(rows.len(), 0.0);
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
    fn banded<const S: usize>(&mut self, rows: &[Row], inverse: &[Inverse], x: &mut [f64]) {
        let count = self.blocks.len();
        let Solver {
            blocks,
            parts,
            diagonal,
            below,
            pivots,
            solution,
            ..
        } = self;
        parts.resize(count, Default::default());
        diagonal.resize(count, Square::default());
        below.resize(count, Square::default());
        pivots.resize(count, Column::default());
        solution.resize(count, Column::default());
        // Each side's parts: lin, lin/m, ang, I⁻¹ ang.
        for (block, sides) in blocks.iter().zip(parts.iter_mut()) {
            for (side_index, (&body, part)) in block.bodies.iter().zip(sides).enumerate() {
                if body == NONE {
                    continue;
                }
                let inv = &inverse[body];
                for i in 0..S {
                    if i < block.size {
                        let (lin, ang) = side(&rows[block.row + i], side_index);
                        let w = inv.inertia * ang;
                        part.lin[i] = [lin.x, lin.y, lin.z];
                        part.scaled[i] = [lin.x * inv.mass, lin.y * inv.mass, lin.z * inv.mass];
                        part.ang[i] = [ang.x, ang.y, ang.z];
                        part.weighted[i] = [w.x, w.y, w.z];
                    } else {
                        part.lin[i] = [0.0; 3];
                        part.scaled[i] = [0.0; 3];
                        part.ang[i] = [0.0; 3];
                        part.weighted[i] = [0.0; 3];
                    }
                }
            }
        }
        // K_kk and K_{k,k−1}, body by body; K's largest diagonal entry.
        let mut largest = 0.0_f64;
        for k in 0..count {
            let block = &blocks[k];
            let d = &mut diagonal[k];
            for (i, row) in d.iter_mut().enumerate().take(S) {
                for (j, entry) in row.iter_mut().enumerate().take(i + 1) {
                    *entry = if i == j && i >= block.size { 1.0 } else { 0.0 };
                }
            }
            for side_index in 0..2 {
                if block.bodies[side_index] == NONE {
                    continue;
                }
                let p = &parts[k][side_index];
                for i in 0..S {
                    for j in 0..=i {
                        d[i][j] += share(p, i, p, j);
                    }
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
                    for i in 0..S {
                        for j in 0..S {
                            b[i][j] += share(p, i, q, j);
                        }
                    }
                }
            }
        }
        // The factor, block by block.
        let tiny = 1e-12 * largest;
        for k in 0..count {
            if k > 0 {
                let (done, rest) = diagonal.split_at_mut(k);
                let (l, d) = (&done[k - 1], &mut rest[0]);
                let r = &pivots[k - 1];
                let b = &mut below[k];
                for row in b.iter_mut().take(S) {
                    for j in 0..S {
                        let mut t = row[j];
                        for c in 0..j {
                            t -= row[c] * l[j][c];
                        }
                        row[j] = t * r[j];
                    }
                }
                for i in 0..S {
                    for j in 0..=i {
                        let mut t = d[i][j];
                        for c in 0..S {
                            t -= b[i][c] * b[j][c];
                        }
                        d[i][j] = t;
                    }
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
        // L y = b, block by block down; Lᵀ x = y, block by block up.
        for k in 0..count {
            let block = &blocks[k];
            let mut y = Column::default();
            y[..block.size].copy_from_slice(&x[block.row..block.row + block.size]);
            if k > 0 {
                let (b, previous) = (&below[k], &solution[k - 1]);
                for i in 0..S {
                    for c in 0..S {
                        y[i] -= b[i][c] * previous[c];
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
                let (b, next) = (&below[k + 1], &solution[k + 1]);
                for c in 0..S {
                    for i in 0..S {
                        z[i] -= b[c][i] * next[c];
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

    /// K inside the envelope, block pair by block pair and body by body (module doc).
    fn assemble(&mut self, rows: &[Row], inverse: &[Inverse]) {
        let Solver {
            blocks,
            start,
            first,
            weighted,
            factor,
            ..
        } = self;
        for (ip, block) in blocks.iter().enumerate() {
            for (sp, &body) in block.bodies.iter().enumerate() {
                if body == NONE {
                    continue;
                }
                let mass = inverse[body].mass;
                let (mut iq, mut sq) = (ip, sp);
                loop {
                    let other = &blocks[iq];
                    for i in block.row..block.row + block.size {
                        let (lin_i, _) = side(&rows[i], sp);
                        let w_i = &weighted[i][sp];
                        let end = if iq == ip {
                            i + 1
                        } else {
                            other.row + other.size
                        };
                        let at = start[i] + other.row - first[i];
                        let entries = &mut factor[at..at + end - other.row];
                        for (entry, row_j) in entries.iter_mut().zip(&rows[other.row..end]) {
                            let (lin_j, ang_j) = side(row_j, sq);
                            *entry += lin_i.dot(lin_j) * mass + w_i.dot(ang_j);
                        }
                    }
                    iq = other.previous[sq];
                    if iq == NONE {
                        break;
                    }
                    sq = usize::from(blocks[iq].bodies[0] != body);
                }
            }
        }
    }

    /// `K = L Lᵀ` in place, row by row: `L_pq = (K_pq − Σ_k L_pk L_qk) / L_qq` over the
    /// columns both rows reach, `L_pp² = K_pp − Σ_k L_pk²` (dropped below 1e-12 · max K_ii).
    fn factor(&mut self, n: usize) {
        let Solver {
            start,
            first,
            factor,
            reciprocal,
            ..
        } = self;
        let (start, first, reciprocal) = (&start[..n], &first[..n], &mut reciprocal[..n]);
        let largest = (0..n)
            .map(|p| factor[start[p] + p - first[p]])
            .fold(0.0, f64::max);
        let tiny = 1e-12 * largest;
        for p in 0..n {
            let fp = first[p];
            let (done, rest) = factor.split_at_mut(start[p]);
            let row_p = &mut rest[..=p - fp];
            for q in fp..p {
                let fq = first[q];
                let from = fp.max(fq);
                let row_q = &done[start[q] + from - fq..start[q] + q - fq];
                let (left, right) = row_p.split_at_mut(q - fp);
                right[0] = (right[0] - dot(&left[from - fp..], row_q)) * reciprocal[q];
            }
            let (off_diagonal, diagonal) = row_p.split_at(p - fp);
            let square = diagonal[0] - dot(off_diagonal, off_diagonal);
            reciprocal[p] = if square > tiny {
                1.0 / square.sqrt()
            } else {
                0.0
            };
        }
    }

    /// `L y = b`, then `Lᵀ x = y`, over x = b.
    fn substitute(&self, x: &mut [f64]) {
        let n = x.len();
        let (start, first, reciprocal) = (&self.start[..n], &self.first[..n], &self.reciprocal);
        let factor = &self.factor;
        for p in 0..n {
            let fp = first[p];
            let y = x[p] - dot(&factor[start[p]..start[p] + p - fp], &x[fp..p]);
            x[p] = y * reciprocal[p];
        }
        for p in (0..n).rev() {
            x[p] *= reciprocal[p];
            let (fp, xp) = (first[p], x[p]);
            for (r, l) in x[fp..p]
                .iter_mut()
                .zip(&factor[start[p]..start[p] + p - fp])
            {
                *r -= l * xp;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::rows::{rows_of, Pose};
    use super::super::{Joint, JointKind};
    use super::*;
    use crate::physics::state::State;
    use nalgebra::{DMatrix, DVector, UnitQuaternion};

    /// A deterministic number in [−1, 1) (a linear congruential sequence).
    fn next(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn vector(seed: &mut u64) -> Vector3<f64> {
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
            put(r.a, &r.lin_a, &r.ang_a);
            if let Some(b) = r.b {
                put(b, &r.lin_b, &r.ang_b);
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
    /// closing a loop; solves `K λ = rhs` for a random rhs both ways and returns which path the
    /// block solve took (banded or the envelope).
    fn check(kinds: &[JointKind], closed: bool, seed: &mut u64) -> bool {
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
        let mut rows = Vec::new();
        for (index, joint) in joints.iter().enumerate() {
            let b = joint.b.map_or(Pose::WORLD, |b| poses[b]);
            rows_of(joint, index, &poses[joint.a], &b, &mut rows);
        }
        let want_rows: usize = joints.iter().map(|j| j.kind.rows()).sum();
        assert_eq!(rows.len(), want_rows);
        let rhs: Vec<f64> = (0..rows.len()).map(|_| next(seed)).collect();
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
}
