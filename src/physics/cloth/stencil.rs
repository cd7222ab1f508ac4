//! The implicit step's product `A p` on a grid sheet, laid out by spring direction (a
//! matrix-free stencil), to the same bits as `conjugate_gradient::product`'s gather.
//!
//! A grid sheet's springs go from a particle k (their i end) to k + o in one of six directions,
//! each with a fixed index offset o:
//!
//! ```text
//! E: 1   N: nx   NE: nx + 1   NW: nx − 1   EE: 2   NN: 2 nx
//! ```
//!
//! and every particle of a rectangle of the grid has one (E: i < nx − 1; N: j < nz − 1; NE:
//! both; NW: i ≥ 1, j < nz − 1; EE: i < nx − 2; NN: j < nz − 2). So the blocks are stored per
//! direction and per particle, `[along, across, d̂x, d̂y, d̂z][D][k]` (0 outside the rectangle),
//! the terms `y_D[k] = S (p_k − p_{k+o})` are computed over each rectangle's span of rows from
//! p split by component (contiguous streams, no index arrays: the loops vectorise), and each
//! particle gathers its twelve terms by offset, in the mirror-symmetric order of
//! `conjugate_gradient` (its opposite directions read y_D\[k − o\]):
//!
//! ```text
//! (A p)_k = a_k p_k + (((y_E[k] − y_E[k−1]) + (y_N[k] − y_N[k−nx]))
//!                    + ((y_NE[k] − y_NE[k−nx−1]) + (y_NW[k] − y_NW[k−nx+1])))
//!                    + ((y_EE[k] − y_EE[k−2]) + (y_NN[k] − y_NN[k−2nx]))
//! y = d̂ (along (d̂·r)) + across r,   r = p_k − p_{k+o},   d̂·r = (d̂x rx + d̂y ry) + d̂z rz
//! ```
//!
//! Every term is the same floating-point expression as the gathered product's, summed in the
//! same order, and a term outside its rectangle reads an exact 0 (its buffer is never written
//! there; the terms are padded with 2 nx + 1 zeros in front for the k − o of the first rows):
//! the two products agree to the last bit (test below). A sheet whose springs fill a direction
//! only in part (built by hand) has no stencil and keeps the gathered product.
//!
//! The product is also compiled for AVX2 and run so on a CPU that has it (checked at run
//! time): its loops, elementwise, then take four numbers at once instead of SSE2's two, the
//! same operations on each (no FMA), the same bits: ~34k instructions instead of ~66k on the
//! 21 × 21 trampoline (callgrind).

use super::conjugate_gradient::Block;
use nalgebra::Vector3;

/// Directions, in the order of `SpringOrder`'s even slots (slot = 2 D).
const DIRECTIONS: usize = 6;

/// The block fields stored per direction and particle.
const FIELDS: usize = 5;

/// A grid sheet's blocks by direction (module doc).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stencil {
    nx: usize,
    n: usize,
    /// Zeros in front of each direction's terms (2 nx + 1).
    pad: usize,
    /// Per direction: its offset o, and its rectangle [i0, i1) × [j0, j1) (empty when the
    /// sheet has no spring in that direction).
    offset: [usize; DIRECTIONS],
    rectangle: [[usize; 4]; DIRECTIONS],
    /// Per spring: D·n + k, where its block goes.
    place: Vec<u32>,
    /// `[field][D·n + k]`: along, across, d̂x, d̂y, d̂z.
    fields: Vec<f64>,
}

/// The product's buffers: p by component, and the terms by direction and component.
#[derive(Debug, Default)]
pub struct StencilBuffers {
    p: Vec<f64>,
    terms: Vec<f64>,
    out: Vec<f64>,
}

/// A copy starts empty: a product writes every number it reads from them (the terms' zeros
/// when it sizes them), so what they held never reaches a result, and a checkpoint of the
/// world (a copy of its cloths) does not carry ~90 kB of them per 21 × 21 sheet.
impl Clone for StencilBuffers {
    fn clone(&self) -> Self {
        StencilBuffers::default()
    }
}

impl StencilBuffers {
    /// The bytes its buffers hold on the heap.
    pub fn heap_bytes(&self) -> usize {
        (self.p.capacity() + self.terms.capacity() + self.out.capacity())
            * std::mem::size_of::<f64>()
    }
}

impl Stencil {
    /// The stencil of a grid of `count` particles whose springs, listed as (direction D,
    /// i-end particle k) in spring order, fill each direction's rectangle wholly or not at
    /// all; None otherwise.
    pub fn of_grid(count: [usize; 2], springs: &[(usize, usize)]) -> Option<Stencil> {
        let [nx, nz] = count;
        let n = nx * nz;
        let offset = [1, nx, nx + 1, nx.wrapping_sub(1), 2, 2 * nx];
        let full = |d: usize| -> [usize; 4] {
            let (i0, i1) = match d {
                0 | 2 => (0, nx.saturating_sub(1)),
                3 => (1.min(nx), nx),
                4 => (0, nx.saturating_sub(2)),
                _ => (0, nx),
            };
            let j1 = match d {
                1..=3 => nz.saturating_sub(1),
                5 => nz.saturating_sub(2),
                _ => nz,
            };
            [i0, i1, 0, j1]
        };
        let mut seen = vec![false; DIRECTIONS * n];
        let mut place = Vec::with_capacity(springs.len());
        let mut counts = [0usize; DIRECTIONS];
        for &(d, k) in springs {
            let [i0, i1, j0, j1] = full(d);
            let (i, j) = (k % nx, k / nx);
            if d >= DIRECTIONS || k >= n || !(i0..i1).contains(&i) || !(j0..j1).contains(&j) {
                return None;
            }
            let at = d * n + k;
            if seen[at] {
                return None;
            }
            seen[at] = true;
            counts[d] += 1;
            place.push(u32::try_from(at).ok()?);
        }
        let mut rectangle = [[0; 4]; DIRECTIONS];
        for d in 0..DIRECTIONS {
            let r = full(d);
            let size = (r[1] - r[0]) * (r[3] - r[2]);
            match counts[d] {
                0 => {}
                c if c == size => rectangle[d] = r,
                _ => return None,
            }
        }
        Some(Stencil {
            nx,
            n,
            pad: 2 * nx + 1,
            offset,
            rectangle,
            place,
            fields: vec![0.0; FIELDS * DIRECTIONS * n],
        })
    }

    /// Whether group `g` of the gather (0: E, N; 1: NE, NW; 2: EE, NN) has springs.
    fn has_group(&self, g: usize) -> bool {
        let filled = |d: usize| {
            let [i0, i1, j0, j1] = self.rectangle[d];
            i0 < i1 && j0 < j1
        };
        filled(2 * g) || filled(2 * g + 1)
    }

    /// Whether it was built for these many springs and particles.
    pub fn fits(&self, springs: usize, n: usize) -> bool {
        self.place.len() == springs && self.n == n
    }

    /// Stores the blocks (one per spring, in spring order) by direction.
    pub fn load(&mut self, blocks: &[Block]) {
        let size = DIRECTIONS * self.n;
        let (along, rest) = self.fields.split_at_mut(size);
        let (across, rest) = rest.split_at_mut(size);
        let (dx, rest) = rest.split_at_mut(size);
        let (dy, dz) = rest.split_at_mut(size);
        // (Five slices of one length: one bounds check serves the five stores.)
        let dz = &mut dz[..size];
        for (b, &at) in blocks.iter().zip(&self.place) {
            let at = at as usize;
            along[at] = b.along;
            across[at] = b.across;
            dx[at] = b.direction.x;
            dy[at] = b.direction.y;
            dz[at] = b.direction.z;
        }
    }

    /// The bytes it holds on the heap.
    pub fn heap_bytes(&self) -> usize {
        self.place.capacity() * std::mem::size_of::<u32>()
            + self.fields.capacity() * std::mem::size_of::<f64>()
    }

    /// out = A p (module doc), `diagonal` the a_k: compiled for AVX2 as well, and run so when
    /// the CPU has it ([`Stencil::product_avx2`]), the same bits.
    pub fn product(
        &self,
        diagonal: &[f64],
        buffers: &mut StencilBuffers,
        p: &[Vector3<f64>],
        out: &mut [Vector3<f64>],
    ) {
        #[cfg(target_arch = "x86_64")]
        if super::avx2() {
            // SAFETY: `product_avx2` is safe but for its target feature: calling it needs a
            // CPU with AVX2, which `avx2` checked just above.
            unsafe { self.product_avx2(diagonal, buffers, p, out) };
            return;
        }
        self.product_plain(diagonal, buffers, p, out);
    }

    /// [`Stencil::product`] compiled with AVX2: its loops run on four numbers at once instead of
    /// two. The same operations on each number (an elementwise loop has no sum to reorder;
    /// AVX2 without FMA contracts nothing): the same bits (test below).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn product_avx2(
        &self,
        diagonal: &[f64],
        buffers: &mut StencilBuffers,
        p: &[Vector3<f64>],
        out: &mut [Vector3<f64>],
    ) {
        self.product_plain(diagonal, buffers, p, out);
    }

    /// [`Stencil::product`] for any CPU (inlined into [`Stencil::product_avx2`]).
    #[inline(always)]
    fn product_plain(
        &self,
        diagonal: &[f64],
        buffers: &mut StencilBuffers,
        p: &[Vector3<f64>],
        out: &mut [Vector3<f64>],
    ) {
        let (n, nx, pad) = (self.n, self.nx, self.pad);
        debug_assert!(p.len() == n && out.len() == n && diagonal.len() >= n);
        let span = pad + n;
        // The terms' zeros (padding, and outside the rectangles) are written once.
        if buffers.terms.len() != 3 * DIRECTIONS * span {
            buffers.terms.clear();
            buffers.terms.resize(3 * DIRECTIONS * span, 0.0);
        }
        buffers.p.resize(3 * n, 0.0);
        {
            let (px, rest) = buffers.p.split_at_mut(n);
            let (py, pz) = rest.split_at_mut(n);
            for (((v, x), y), z) in p.iter().zip(px).zip(py).zip(pz) {
                (*x, *y, *z) = (v.x, v.y, v.z);
            }
        }
        let (px, rest) = buffers.p.split_at(n);
        let (py, pz) = rest.split_at(n);
        let size = DIRECTIONS * n;
        let field = |f: usize| &self.fields[f * size..(f + 1) * size];
        let (along, across, dx, dy, dz) = (field(0), field(1), field(2), field(3), field(4));
        for d in 0..DIRECTIONS {
            let [i0, i1, j0, j1] = self.rectangle[d];
            if i0 >= i1 || j0 >= j1 {
                continue;
            }
            let o = self.offset[d];
            // The whole span of the rectangle's rows at once (a few particles between two
            // rows are outside it: their terms, from zero blocks, are set back to +0 after).
            let (start, end) = (j0 * nx + i0, (j1 - 1) * nx + i1);
            let len = end - start;
            let base = 3 * d * span + pad;
            let (yx, rest) = buffers.terms[base..base + 2 * span + n].split_at_mut(span);
            let (yy, rest) = rest.split_at_mut(span);
            let yz = &mut rest[..n];
            let (k, b) = (start, d * n + start);
            row_terms(
                [&px[k..k + len], &py[k..k + len], &pz[k..k + len]],
                [
                    &px[k + o..k + o + len],
                    &py[k + o..k + o + len],
                    &pz[k + o..k + o + len],
                ],
                [
                    &along[b..b + len],
                    &across[b..b + len],
                    &dx[b..b + len],
                    &dy[b..b + len],
                    &dz[b..b + len],
                ],
                [
                    &mut yx[k..k + len],
                    &mut yy[k..k + len],
                    &mut yz[k..k + len],
                ],
            );
            for j in j0..j1 - 1 {
                for k in j * nx + i1..(j + 1) * nx + i0 {
                    (yx[k], yy[k], yz[k]) = (0.0, 0.0, 0.0);
                }
            }
        }
        // The gather, component by component (term (D, c) of particle k is at
        // 3 D span + c span + pad + k), into `out` by component, then interleaved.
        buffers.out.resize(3 * n, 0.0);
        let terms = &buffers.terms;
        for (c, (out_c, p_c)) in buffers
            .out
            .chunks_exact_mut(n)
            .zip([px, py, pz])
            .enumerate()
        {
            let at = |d: usize, back: usize| {
                let start = 3 * d * span + c * span + pad - back;
                &terms[start..start + n]
            };
            let o = self.offset;
            let y = [
                [at(0, 0), at(0, o[0])],
                [at(1, 0), at(1, o[1])],
                [at(2, 0), at(2, o[2])],
                [at(3, 0), at(3, o[3])],
                [at(4, 0), at(4, o[4])],
                [at(5, 0), at(5, o[5])],
            ];
            let a = &diagonal[..n];
            match (self.has_group(1), self.has_group(2)) {
                (true, true) => gather_row::<true, true>(out_c, p_c, a, y),
                (true, false) => gather_row::<true, false>(out_c, p_c, a, y),
                (false, true) => gather_row::<false, true>(out_c, p_c, a, y),
                (false, false) => gather_row::<false, false>(out_c, p_c, a, y),
            }
        }
        let (ox, rest) = buffers.out.split_at(n);
        let (oy, oz) = rest.split_at(n);
        for (((out, &x), &y), &z) in out.iter_mut().zip(ox).zip(oy).zip(oz) {
            *out = Vector3::new(x, y, z);
        }
    }
}

/// One component of the gather (module doc): out = p a + Σ the twelve terms in the mirror
/// order, `y[D] = [y_D[k], y_D[k − o_D]]` over all k, slices of one length. A group of
/// directions without springs (`SHEAR`: NE, NW; `BEND`: EE, NN false) is not read: its
/// four terms are exact zeros, so its sum (0 − 0) + (0 − 0) is +0 and the group adds the
/// constant +0 in its place (not nothing: x + 0 turns a −0 into +0), the same bits.
#[inline(always)]
fn gather_row<const SHEAR: bool, const BEND: bool>(
    out: &mut [f64],
    p: &[f64],
    a: &[f64],
    y: [[&[f64]; 2]; DIRECTIONS],
) {
    let len = out.len();
    let (p, a) = (&p[..len], &a[..len]);
    let [[e, w], [n, s], [ne, sw], [nw, se], [ee, ww], [nn, ss]] =
        y.map(|pair| pair.map(|s| &s[..len]));
    for k in 0..len {
        let stretch = (e[k] - w[k]) + (n[k] - s[k]);
        let shear = if SHEAR {
            (ne[k] - sw[k]) + (nw[k] - se[k])
        } else {
            0.0
        };
        let bend = if BEND {
            (ee[k] - ww[k]) + (nn[k] - ss[k])
        } else {
            0.0
        };
        out[k] = p[k] * a[k] + ((stretch + shear) + bend);
    }
}

/// A run of a direction's terms: y = d̂ (along (d̂·r)) + across r, r = p − q (module doc),
/// over slices of one length (no bounds checks inside: the loop vectorises).
#[inline(always)]
fn row_terms(p: [&[f64]; 3], q: [&[f64]; 3], block: [&[f64]; FIELDS], y: [&mut [f64]; 3]) {
    let len = y[0].len();
    let [px, py, pz] = p.map(|s| &s[..len]);
    let [qx, qy, qz] = q.map(|s| &s[..len]);
    let [along, across, dx, dy, dz] = block.map(|s| &s[..len]);
    let [yx, yy, yz] = y;
    let (yy, yz) = (&mut yy[..len], &mut yz[..len]);
    for t in 0..len {
        let (rx, ry, rz) = (px[t] - qx[t], py[t] - qy[t], pz[t] - qz[t]);
        let dot = (dx[t] * rx + dy[t] * ry) + dz[t] * rz;
        let s = along[t] * dot;
        yx[t] = dx[t] * s + rx * across[t];
        yy[t] = dy[t] * s + ry * across[t];
        yz[t] = dz[t] * s + rz * across[t];
    }
}

#[cfg(test)]
mod tests {
    use super::super::conjugate_gradient::{product, ProductBuffers, SpringOrder};
    use super::super::spec::ClothSpec;
    use super::super::Cloth;
    use super::*;

    /// A deterministic sequence in [−1, 1) (a linear congruential generator).
    fn numbers(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// A sheet's springs with random blocks (unit directions, along and across ≥ 0, some
    /// blocks empty as for a spring between two pinned particles), a random p and a_k.
    fn case(
        count: [usize; 2],
        shear: f64,
        bend: f64,
    ) -> (Cloth, Vec<Block>, Vec<f64>, Vec<Vector3<f64>>) {
        let mut spec = ClothSpec::new([1.0, 0.7], count, 1.0, 100.0);
        spec.shear = shear;
        spec.bend = bend;
        let cloth = Cloth::new(&spec).unwrap();
        let mut r = numbers(count[0] as u64 * 31 + count[1] as u64);
        let blocks = (cloth.springs.iter().enumerate())
            .map(|(s, spring)| {
                if s % 7 == 3 {
                    return Block::default();
                }
                let d = Vector3::new(r(), r(), r()).normalize();
                Block {
                    i: spring.i as u32,
                    j: spring.j as u32,
                    along: r().abs() * 3.0,
                    across: r().abs(),
                    direction: d,
                }
            })
            .collect();
        let n = cloth.len();
        let diagonal = (0..n).map(|_| 1.0 + r().abs()).collect();
        let p = (0..n).map(|_| Vector3::new(r(), r(), r())).collect();
        (cloth, blocks, diagonal, p)
    }

    #[test]
    fn the_stencil_product_has_the_bits_of_the_gathered_one() {
        for (count, shear, bend) in [
            ([7, 5], 30.0, 10.0),
            ([21, 21], 1000.0, 0.0),
            ([4, 6], 0.0, 5.0),
            ([9, 1], 0.0, 3.0),
            ([1, 6], 0.0, 0.0),
            ([2, 2], 1.0, 1.0),
        ] {
            let (cloth, blocks, diagonal, p) = case(count, shear, bend);
            let springs = cloth.springs.iter().map(|s| (s.i, s.j, s.kind));
            let mut order = SpringOrder::of_grid(cloth.count, springs).unwrap();
            let stencil = order.stencil.clone();
            let Some(mut stencil) = stencil else {
                panic!("{count:?}: a whole grid has a stencil");
            };
            stencil.load(&blocks);
            order.stencil = Some(stencil);
            let n = cloth.len();
            let mut buffers = ProductBuffers::default();
            let mut by_stencil = vec![Vector3::zeros(); n];
            // Twice: the buffers' second use must not depend on the first; then with a copy of
            // the used buffers (which starts empty).
            for _ in 0..2 {
                product(
                    &blocks,
                    &diagonal,
                    &order,
                    &mut buffers,
                    &p,
                    &mut by_stencil,
                );
            }
            let mut copied = buffers.clone();
            let mut again = vec![Vector3::zeros(); n];
            product(&blocks, &diagonal, &order, &mut copied, &p, &mut again);
            assert!(
                (again.iter().zip(&by_stencil))
                    .all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits)),
                "{count:?}: a copy of the buffers gives the same bits"
            );
            order.stencil = None;
            let mut gathered = vec![Vector3::zeros(); n];
            product(&blocks, &diagonal, &order, &mut buffers, &p, &mut gathered);
            for k in 0..n {
                for c in 0..3 {
                    assert_eq!(
                        by_stencil[k][c].to_bits(),
                        gathered[k][c].to_bits(),
                        "{count:?} particle {k}: {} vs {}",
                        by_stencil[k][c],
                        gathered[k][c]
                    );
                }
            }
            // Independent truth: A p summed straight from its definition (a scatter).
            let mut scattered = vec![Vector3::zeros(); n];
            product(
                &blocks,
                &diagonal,
                &SpringOrder::default(),
                &mut buffers,
                &p,
                &mut scattered,
            );
            for k in 0..n {
                assert!(
                    (by_stencil[k] - scattered[k]).norm() <= 1e-13 * (1.0 + scattered[k].norm()),
                    "{count:?} particle {k}: {:?} vs {:?}",
                    by_stencil[k],
                    scattered[k]
                );
            }
        }
    }

    #[test]
    fn the_product_for_this_cpu_has_the_bits_of_the_plain_one() {
        // `product` runs the AVX2 build where the CPU has AVX2; `product_plain` is the build for
        // any CPU.
        for (count, shear, bend) in [([21, 21], 1000.0, 300.0), ([7, 5], 30.0, 0.0)] {
            let (cloth, blocks, diagonal, p) = case(count, shear, bend);
            let springs = cloth.springs.iter().map(|s| (s.i, s.j, s.kind));
            let order = SpringOrder::of_grid(cloth.count, springs).unwrap();
            let mut stencil = order.stencil.unwrap();
            stencil.load(&blocks);
            let n = cloth.len();
            let (mut fast, mut plain) = (vec![Vector3::zeros(); n], vec![Vector3::zeros(); n]);
            stencil.product(&diagonal, &mut StencilBuffers::default(), &p, &mut fast);
            stencil.product_plain(&diagonal, &mut StencilBuffers::default(), &p, &mut plain);
            assert!(
                (fast.iter().zip(&plain)).all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits)),
                "{count:?}"
            );
        }
    }

    #[test]
    fn a_direction_filled_in_part_has_no_stencil() {
        // Two E springs of a 3 × 2 grid's row 0, none in row 1.
        assert!(Stencil::of_grid([3, 2], &[(0, 0), (0, 1)]).is_none());
        // The whole E rectangle: a stencil.
        assert!(Stencil::of_grid([3, 2], &[(0, 0), (0, 1), (0, 3), (0, 4)]).is_some());
        // A spring outside its rectangle (E from the last column).
        assert!(Stencil::of_grid([3, 2], &[(0, 2)]).is_none());
    }
}
