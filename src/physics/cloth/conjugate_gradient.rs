//! Preconditioned conjugate gradients on the implicit step's matrix, with Baraff & Witkin's
//! filter for pinned particles.
//!
//! # The matrix: one compact block per spring, assembled once per step
//!
//! ```text
//! A = diag(a_i I) + Σ_springs (i, j)  [  S_s  −S_s ]   rows/columns i, j
//!                                     [ −S_s   S_s ]
//! a_i = m_i + h k_drag,i,     S_s = h c d̂d̂ᵀ + h² k J           (see `spring`, `implicit_euler`)
//!     = (h c + h² k (1 − t)) d̂d̂ᵀ + h² k t I,   t = max(0, 1 − ℓ₀/ℓ)
//! (A p)_i = a_i p_i + Σ_{s ∋ i} ±S_s (p_i − p_j)
//! ```
//!
//! Every spring's block is built once per step, in the same pass over the springs as the
//! forces and the right-hand side (`implicit_euler`), and stored compactly next to its two
//! particle indices: `[i, j: u32; along, across: f64; d̂]`, 48 bytes, so that a product is one
//! stream over the blocks (S r = along (d̂·r) d̂ + across r: 14 flops) and one over the
//! particles gathering their springs' terms (below): ~118k instructions per product on the
//! 21 × 21 trampoline's 2 438 springs (the scatter it replaced: ~105k). On a grid sheet the
//! same blocks are also stored by direction and the product runs as a stencil over them
//! (`stencil`: the same bits, ~66k instructions; ~34k built for AVX2, which it runs when the
//! CPU has it). A spring whose two ends are pinned has an empty block: it acts on no free
//! particle. Why not a CSR matrix of 3×3 blocks by rows: each
//! particle's row holds its ~9 blocks (itself and 8 neighbours), i.e. every spring block stored
//! twice as a full 3×3 plus index arrays, ~2× the flops per product (a full 3×3 product per
//! neighbour against one compact product per spring). A is symmetric positive definite
//! (M > 0 and every S_s positive semi-definite), which is what conjugate gradients need. A
//! direct sparse factorisation would have to be redone every step (the blocks change), and on
//! a 2-D grid its fill-in (bandwidth 3·nx) costs more than the few iterations CG needs.
//!
//! # Sums in a mirror-symmetric order
//!
//! A product is computed in two passes: every spring's `y_s = S_s (p_i − p_j)` (one stream over
//! the blocks), then every particle's `(A p)_k = a_k p_k + Σ_{s ∋ k} ±y_s`, gathered from its
//! own springs in a fixed order of *directions* on the grid ([`SpringOrder`]):
//!
//! ```text
//! ((E + W) + (N + S)) + ((NE + SW) + (NW + SE)) + ((EE + WW) + (NN + SS))
//! ```
//!
//! Floating-point addition is commutative but not associative, so a sum's rounding depends on
//! its order; summed in the springs' storage order (a scatter), a particle and its mirror image
//! under x → −x add the same terms in different orders and end up to an ulp apart. In the
//! order above, a mirror (x → −x, z → −z, or x ↔ z) only swaps the two terms of a pair or
//! the two pairs of a group, and negation is exact: on a mirror-symmetric sheet the product
//! of a mirror-symmetric vector is mirror-symmetric *to the last bit*, and so is every CG
//! iterate. Why it matters: a mirror-symmetric scene (lesson 16's frictionless centred drop)
//! then keeps its symmetry exactly instead of from an ulp-sized seed that the contact set's
//! decisions and the CG's polynomial amplify (`tests/physics/cloth_world.rs`). The gathered
//! product costs ~12 % more instructions than the scatter did (callgrind); a tied solve
//! makes up for it by computing A Δv only at the tied particles for their impulses
//! ([`SpringOrder::row`]). A sheet whose springs are not the grid's (built by hand, or a
//! spring with i > j) falls back to the scatter.
//!
//! # Preconditioner: Jacobi by 3×3 particle blocks
//!
//! `P_i = a_i I + Σ_{s ∋ i} S_s` (the diagonal block of A, symmetric: 6 numbers), summed in the
//! spring pass and inverted once per step (adjugate over determinant). It is the Jacobi
//! preconditioner taken per particle rather than per scalar, so that a particle whose springs
//! are much stiffer along one direction than across is scaled in each direction.
//!
//! # The filter (Baraff & Witkin 1998, §5.3)
//!
//! A pinned particle's Δv is prescribed (0): the filter zeroes its rows in every residual and
//! search direction (its P⁻¹ is 0, and its rows of every product are zeroed), so CG works on
//! the free particles only and never moves a pinned one.
//!
//! ```text
//! Δv ← filter(warm start);  r = filter(b − A Δv);  z = P⁻¹ r;  p = z;  δ = rᵀz
//! δ₀ = filter(b)ᵀ P⁻¹ filter(b)
//! while δ > ε² δ₀:   q = filter(A p);  α = δ / pᵀq;  Δv += α p;  r −= α q
//!                    z = P⁻¹ r;  δ' = rᵀz;  p = z + (δ'/δ) p;  δ = δ'
//! ```
//!
//! The stopping test is relative to the right-hand side, in the norm of P⁻¹ (ε is
//! [`SolverSettings::tolerance`](super::sheet::SolverSettings); why its default is enough:
//! `implicit_euler`).

use super::stencil::{Stencil, StencilBuffers};
use nalgebra::Vector3;

/// One spring's block `S = along·d̂d̂ᵀ + across·I` (module doc) and its particles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Block {
    pub i: u32,
    pub j: u32,
    pub along: f64,
    pub across: f64,
    pub direction: Vector3<f64>,
}

impl Block {
    /// S r.
    #[inline(always)]
    pub(super) fn apply(&self, r: &Vector3<f64>) -> Vector3<f64> {
        self.direction * (self.along * self.direction.dot(r)) + r * self.across
    }
}

/// A symmetric 3×3 matrix by its 6 entries `[xx, yy, zz, xy, xz, yz]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Symmetric3(pub [f64; 6]);

impl Symmetric3 {
    /// a I.
    #[inline]
    pub fn diagonal(a: f64) -> Symmetric3 {
        Symmetric3([a, a, a, 0.0, 0.0, 0.0])
    }

    /// S of a block as a matrix.
    #[inline(always)]
    pub fn of(b: &Block) -> Symmetric3 {
        let d = &b.direction;
        let ad = d * b.along;
        Symmetric3([
            ad.x * d.x + b.across,
            ad.y * d.y + b.across,
            ad.z * d.z + b.across,
            ad.x * d.y,
            ad.x * d.z,
            ad.y * d.z,
        ])
    }

    /// self += other.
    #[inline(always)]
    pub fn add(&mut self, other: &Symmetric3) {
        for (a, b) in self.0.iter_mut().zip(&other.0) {
            *a += b;
        }
    }

    /// The inverse (adjugate over determinant); 0 when singular or not finite.
    #[inline]
    pub fn inverse(&self) -> Symmetric3 {
        let [a, e, i, b, c, f] = self.0;
        // [[a b c] [b e f] [c f i]]
        let (ca, cb, cc) = (e * i - f * f, c * f - b * i, b * f - c * e);
        let det = a * ca + b * cb + c * cc;
        if det.is_finite() && det != 0.0 {
            let s = 1.0 / det;
            Symmetric3([
                ca * s,
                (a * i - c * c) * s,
                (a * e - b * b) * s,
                cb * s,
                cc * s,
                (b * c - a * f) * s,
            ])
        } else {
            Symmetric3::default()
        }
    }

    /// M v.
    #[inline(always)]
    pub fn apply(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let m = &self.0;
        Vector3::new(
            m[0] * v.x + m[3] * v.y + m[4] * v.z,
            m[3] * v.x + m[1] * v.y + m[5] * v.z,
            m[4] * v.x + m[5] * v.y + m[2] * v.z,
        )
    }
}

/// Per particle, its springs in the mirror-symmetric order of the module doc: 12 slots
/// `[E, W, N, S, NE, SW, NW, SE, EE, WW, NN, SS]`, each a spring's index s, or the number of
/// springs (a zero term) when empty: an index into the terms `[y_0, y_1, …, 0]`. Every grid
/// spring has i < j, so a particle is the i end of its springs in the even slots (E, N, NE,
/// NW, EE, NN: its term +y_s) and the j end in the odd ones (its term −y_s).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpringOrder {
    pub slots: Vec<[u32; SLOTS]>,
    /// The number of springs it was built for.
    pub springs: usize,
    /// The blocks by direction, when every direction's springs fill its rectangle
    /// (`stencil`): the product's fast path, to the same bits.
    pub stencil: Option<Stencil>,
    /// Whether any particle has a spring in the bend slots (EE … SS). Without one, the last
    /// group of every sum is (0 − 0) + (0 − 0) = +0 exactly: the sums add the constant +0 in
    /// its place instead of reading four empty slots (not nothing: x + 0 turns a −0 into +0),
    /// the same bits.
    pub bend: bool,
}

/// Directions a particle of the grid has springs in.
pub const SLOTS: usize = 12;

impl SpringOrder {
    /// The order for a grid of `count = [nx, nz]` particles (index j·nx + i) with springs
    /// `(i, j, kind)`; None when a spring is not one of the grid's or two share a slot.
    pub fn of_grid(
        count: [usize; 2],
        springs: impl ExactSizeIterator<Item = (usize, usize, super::spring::SpringKind)>,
    ) -> Option<SpringOrder> {
        use super::spring::SpringKind;
        let nx = count[0];
        let n = count[0] * count[1];
        let total = springs.len();
        let empty = u32::try_from(total).ok()?;
        let mut slots = vec![[empty; SLOTS]; n];
        for (s, (a, b, kind)) in springs.enumerate() {
            if a >= b {
                return None;
            }
            let same_row = |k: usize| a % nx + k < nx;
            // The slot of `a` (its neighbour b is E, N, NE, NW, EE or NN of it); b's is the next.
            let slot = match (kind, b - a) {
                (SpringKind::Stretch, 1) if same_row(1) => 0,
                (SpringKind::Stretch, d) if d == nx => 2,
                (SpringKind::Shear, d) if d == nx + 1 && same_row(1) => 4,
                (SpringKind::Shear, d) if d + 1 == nx && a % nx >= 1 => 6,
                (SpringKind::Bend, 2) if same_row(2) => 8,
                (SpringKind::Bend, d) if d == 2 * nx => 10,
                _ => return None,
            };
            if b >= n {
                return None;
            }
            // The spring's i end (a, even slot) takes +y_s, its j end (b, odd slot) −y_s.
            for (particle, slot) in [(a, slot), (b, slot + 1)] {
                if slots[particle][slot] != empty {
                    return None;
                }
                slots[particle][slot] = s as u32;
            }
        }
        // Each spring by (direction, its i end): its even slot 2 D at particle k.
        let mut ends = vec![(0, 0); total];
        for (k, particle) in slots.iter().enumerate() {
            for d in 0..SLOTS / 2 {
                if let Some(end) = ends.get_mut(particle[2 * d] as usize) {
                    *end = (d, k);
                }
            }
        }
        let stencil = Stencil::of_grid(count, &ends);
        let bend = (slots.iter()).any(|s| s[8..].iter().any(|&spring| spring != empty));
        Some(SpringOrder {
            slots,
            springs: total,
            stencil,
            bend,
        })
    }

    /// Σ ±terms\[slot\] of particle `k` in the order of the module doc (+ in the even
    /// slots, − in the odd ones: c_even + c_odd is computed as y_even − y_odd, the same bits);
    /// `terms` holds `[y_0, y_1, …, 0]`.
    #[inline(always)]
    pub fn gather(&self, k: usize, terms: &[Vector3<f64>]) -> Vector3<f64> {
        let s = &self.slots[k];
        let y = |m: usize| terms[s[m] as usize];
        let bend = if self.bend {
            (y(8) - y(9)) + (y(10) - y(11))
        } else {
            Vector3::zeros()
        };
        ((y(0) - y(1)) + (y(2) - y(3))) + ((y(4) - y(5)) + (y(6) - y(7))) + bend
    }

    /// (A p)_k alone, `a p_k + Σ ±S_s (p_i − p_j)` over particle k's springs, to the same bits
    /// as [`product`]'s row k (the same terms, summed in the same order).
    #[inline]
    pub fn row(&self, blocks: &[Block], a: f64, p: &[Vector3<f64>], k: usize) -> Vector3<f64> {
        let s = &self.slots[k];
        let y = |m: usize| match blocks.get(s[m] as usize) {
            Some(b) => b.apply(&(p[b.i as usize] - p[b.j as usize])),
            None => Vector3::zeros(),
        };
        let bend = if self.bend {
            (y(8) - y(9)) + (y(10) - y(11))
        } else {
            Vector3::zeros()
        };
        p[k] * a + (((y(0) - y(1)) + (y(2) - y(3))) + ((y(4) - y(5)) + (y(6) - y(7))) + bend)
    }

    /// Σ blocks\[slot\] of particle `k` (all with +), in the same order.
    #[inline(always)]
    pub fn gather_blocks(&self, k: usize, blocks: &[Symmetric3]) -> Symmetric3 {
        let s = &self.slots[k];
        let c = |m: usize| blocks[s[m] as usize];
        let sum = |a: Symmetric3, b: Symmetric3| {
            let mut a = a;
            a.add(&b);
            a
        };
        let bend = if self.bend {
            sum(sum(c(8), c(9)), sum(c(10), c(11)))
        } else {
            Symmetric3::default()
        };
        sum(
            sum(
                sum(sum(c(0), c(1)), sum(c(2), c(3))),
                sum(sum(c(4), c(5)), sum(c(6), c(7))),
            ),
            bend,
        )
    }
}

/// The solve's buffers, reused from step to step; `solution` is the last Δv (the warm start).
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    /// S_s with its particles, one per spring (0 when both ends are pinned).
    pub blocks: Vec<Block>,
    /// a_i, one per particle.
    pub diagonal: Vec<f64>,
    /// P_i (summed by the caller), inverted by [`Workspace::solve`] (0 for pinned particles).
    pub preconditioner: Vec<Symmetric3>,
    /// The pinned particles' indices.
    pub pinned: Vec<u32>,
    pub rhs: Vec<Vector3<f64>>,
    pub solution: Vec<Vector3<f64>>,
    pub(super) residual: Vec<Vector3<f64>>,
    pub(super) preconditioned: Vec<Vector3<f64>>,
    pub(super) direction: Vec<Vector3<f64>>,
    pub(super) product: Vec<Vector3<f64>>,
    /// The tied solve's buffers (`ties`).
    pub(super) ties: super::ties::TieBuffers,
    /// The order the springs' terms are summed in per particle (module doc); empty: scatter.
    pub order: SpringOrder,
    /// The product's buffers ([`ProductBuffers`]); in the spring pass, per spring its
    /// right-hand-side term and a zero at the end.
    pub(super) terms: ProductBuffers,
    /// Per spring, S_s as a matrix (for the preconditioner's sums), and a zero at the end.
    pub(super) matrices: Vec<Symmetric3>,
}

/// A product's buffers: per spring y_s = S_s (p_i − p_j) and a zero at the end
/// ([`SpringOrder`]), or the stencil's.
#[derive(Debug, Clone, Default)]
pub struct ProductBuffers {
    pub terms: Vec<Vector3<f64>>,
    pub stencil: StencilBuffers,
}

impl ProductBuffers {
    /// The bytes its buffers hold on the heap.
    pub fn heap_bytes(&self) -> usize {
        bytes_of(&self.terms, self.terms.capacity()) + self.stencil.heap_bytes()
    }
}

/// out = A p (no filter): a_k p_k plus the springs' terms, gathered in `order` when it was
/// built for these blocks (module doc) — by the stencil when the order has one and it holds
/// these blocks (`stencil`, the same bits) — scattered otherwise.
pub(super) fn product(
    blocks: &[Block],
    diagonal: &[f64],
    order: &SpringOrder,
    buffers: &mut ProductBuffers,
    p: &[Vector3<f64>],
    out: &mut [Vector3<f64>],
) {
    let n = out.len();
    let (diagonal, p) = (&diagonal[..n], &p[..n]);
    if let Some(stencil) = order.stencil.as_ref().filter(|s| s.fits(blocks.len(), n)) {
        stencil.product(diagonal, &mut buffers.stencil, p, out);
        return;
    }
    let terms = &mut buffers.terms;
    if order.springs == blocks.len() && order.slots.len() == n {
        terms.resize(blocks.len() + 1, Vector3::zeros());
        for (y, b) in terms.iter_mut().zip(blocks) {
            *y = b.apply(&(p[b.i as usize] - p[b.j as usize]));
        }
        terms[blocks.len()] = Vector3::zeros();
        for (k, ((o, p), &a)) in out.iter_mut().zip(p).zip(diagonal).enumerate() {
            *o = p * a + order.gather(k, terms);
        }
    } else {
        for ((o, &a), p) in out.iter_mut().zip(diagonal).zip(p) {
            *o = p * a;
        }
        for b in blocks {
            let (i, j) = (b.i as usize, b.j as usize);
            let y = b.apply(&(p[i] - p[j]));
            out[i] += y;
            out[j] -= y;
        }
    }
}

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    pub iterations: usize,
    /// √(δ/δ₀) at the end.
    pub relative_residual: f64,
}

/// A `Vec`'s heap bytes: its capacity × its element size.
pub(crate) fn bytes_of<T>(v: &[T], capacity: usize) -> usize {
    debug_assert!(capacity >= v.len());
    capacity * std::mem::size_of::<T>()
}

impl Workspace {
    /// The bytes its buffers hold on the heap.
    pub fn heap_bytes(&self) -> usize {
        bytes_of(&self.blocks, self.blocks.capacity())
            + bytes_of(&self.diagonal, self.diagonal.capacity())
            + bytes_of(&self.preconditioner, self.preconditioner.capacity())
            + bytes_of(&self.pinned, self.pinned.capacity())
            + [
                &self.rhs,
                &self.solution,
                &self.residual,
                &self.preconditioned,
                &self.direction,
                &self.product,
            ]
            .iter()
            .map(|v| bytes_of(v, v.capacity()))
            .sum::<usize>()
            + self.ties.heap_bytes()
            + bytes_of(&self.order.slots, self.order.slots.capacity())
            + self.terms.heap_bytes()
            + self.order.stencil.as_ref().map_or(0, Stencil::heap_bytes)
            + bytes_of(&self.matrices, self.matrices.capacity())
    }

    /// Sizes every per-particle buffer for `n` particles and lists the pinned ones; the warm
    /// start is reset to 0 when the size changed.
    pub fn resize(&mut self, pinned: &[bool]) {
        let n = pinned.len();
        if self.solution.len() != n {
            self.solution = vec![Vector3::zeros(); n];
        }
        for buffer in [
            &mut self.rhs,
            &mut self.residual,
            &mut self.preconditioned,
            &mut self.direction,
            &mut self.product,
        ] {
            buffer.resize(n, Vector3::zeros());
        }
        self.preconditioner.resize(n, Symmetric3::default());
        self.diagonal.resize(n, 0.0);
        self.pinned.clear();
        self.pinned.extend(
            pinned
                .iter()
                .enumerate()
                .filter(|(_, &p)| p)
                .map(|(i, _)| i as u32),
        );
    }

    /// out = filter(A p).
    #[inline]
    fn multiply(
        blocks: &[Block],
        diagonal: &[f64],
        order: &SpringOrder,
        terms: &mut ProductBuffers,
        pinned: &[u32],
        p: &[Vector3<f64>],
        out: &mut [Vector3<f64>],
    ) {
        product(blocks, diagonal, order, terms, p, out);
        for &i in pinned {
            out[i as usize] = Vector3::zeros();
        }
    }

    /// Solves A Δv = rhs for the particles not pinned, A built from `blocks` and `diagonal`,
    /// P from `preconditioner` (inverted here); the result is in `solution`.
    pub fn solve(&mut self, tolerance: f64, max_iterations: usize) -> Outcome {
        #[cfg(target_arch = "x86_64")]
        if super::avx2() {
            // SAFETY: `solve_avx2` is safe but for its target feature: calling it needs a CPU
            // with AVX2, which `avx2` checked just above.
            return unsafe { self.solve_avx2(tolerance, max_iterations) };
        }
        self.solve_plain(tolerance, max_iterations)
    }

    /// [`Workspace::solve`] compiled with AVX2 (its loops inlined; the product is the
    /// stencil's own AVX2 build).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_avx2(&mut self, tolerance: f64, max_iterations: usize) -> Outcome {
        self.solve_plain(tolerance, max_iterations)
    }

    /// [`Workspace::solve`] for any CPU.
    #[inline(always)]
    fn solve_plain(&mut self, tolerance: f64, max_iterations: usize) -> Outcome {
        // P_i⁻¹ (pinned rows: 0, and the right-hand side and warm start filtered).
        for p in &mut self.preconditioner {
            *p = p.inverse();
        }
        for &i in &self.pinned {
            let i = i as usize;
            self.preconditioner[i] = Symmetric3::default();
            self.rhs[i] = Vector3::zeros();
            self.solution[i] = Vector3::zeros();
        }
        let mut delta0 = 0.0;
        for (b, p) in self.rhs.iter().zip(&self.preconditioner) {
            delta0 += b.dot(&p.apply(b));
        }
        if !delta0.is_finite() || delta0 <= 0.0 {
            self.solution.iter_mut().for_each(|x| *x = Vector3::zeros());
            return Outcome {
                iterations: 0,
                relative_residual: 0.0,
            };
        }
        // r = filter(b − A Δv) from the warm start.
        Self::multiply(
            &self.blocks,
            &self.diagonal,
            &self.order,
            &mut self.terms,
            &self.pinned,
            &self.solution,
            &mut self.product,
        );
        let mut delta = 0.0;
        for (((r, z), (b, q)), inverse) in (self.residual.iter_mut())
            .zip(self.preconditioned.iter_mut())
            .zip(self.rhs.iter().zip(&self.product))
            .zip(&self.preconditioner)
        {
            *r = b - q;
            *z = inverse.apply(r);
            delta += r.dot(z);
        }
        if delta > delta0 {
            // A warm start worse than zero: start from zero.
            self.solution.iter_mut().for_each(|x| *x = Vector3::zeros());
            self.residual.clone_from(&self.rhs);
            for ((z, r), inverse) in (self.preconditioned.iter_mut())
                .zip(&self.residual)
                .zip(&self.preconditioner)
            {
                *z = inverse.apply(r);
            }
            delta = delta0;
        }
        self.direction.clone_from(&self.preconditioned);
        let target = tolerance * tolerance * delta0;
        let mut iterations = 0;
        while delta > target && iterations < max_iterations {
            Self::multiply(
                &self.blocks,
                &self.diagonal,
                &self.order,
                &mut self.terms,
                &self.pinned,
                &self.direction,
                &mut self.product,
            );
            let curvature: f64 = self
                .direction
                .iter()
                .zip(&self.product)
                .map(|(p, q)| p.dot(q))
                .sum();
            if curvature.is_nan() || curvature <= 0.0 {
                break;
            }
            let alpha = delta / curvature;
            let mut next = 0.0;
            for ((((x, r), z), (p, q)), inverse) in (self.solution.iter_mut())
                .zip(self.residual.iter_mut())
                .zip(self.preconditioned.iter_mut())
                .zip(self.direction.iter().zip(&self.product))
                .zip(&self.preconditioner)
            {
                *x += p * alpha;
                *r -= q * alpha;
                *z = inverse.apply(r);
                next += r.dot(z);
            }
            let beta = next / delta;
            for (p, z) in self.direction.iter_mut().zip(&self.preconditioned) {
                *p = z + *p * beta;
            }
            delta = next;
            iterations += 1;
        }
        Outcome {
            iterations,
            relative_residual: (delta / delta0).max(0.0).sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    #[test]
    fn the_symmetric_inverse_is_the_inverse() {
        let mut m = Symmetric3::diagonal(2.0);
        m.add(&Symmetric3::of(&Block {
            i: 0,
            j: 1,
            along: 3.0,
            across: 0.5,
            direction: Vector3::new(1.0, 2.0, -2.0) / 3.0,
        }));
        let [a, e, i, b, c, f] = m.0;
        let full = Matrix3::new(a, b, c, b, e, f, c, f, i);
        let inv = m.inverse();
        for v in [Vector3::x(), Vector3::y(), Vector3::z()] {
            // M (M⁻¹ v) = v.
            assert!((full * inv.apply(&v) - v).norm() < 1e-14);
        }
        assert_eq!(Symmetric3::default().inverse(), Symmetric3::default());
    }
}
