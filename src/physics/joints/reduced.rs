//! A hinge chain's multipliers through its joint coordinates: `K λ = r` (K = J M⁻¹ Jᵀ) solved
//! in the null space of J, whose dimension is one per hinge, instead of factoring K's 5n rows.
//!
//! ```text
//! Δu = M⁻¹ Jᵀ λ  with  J Δu = r          (λ = K⁻¹ r: the same problem)
//! Δu = u_p + N z:   J u_p = r  (a particular solution),   J N = 0  (N: one column per hinge)
//! Nᵀ M Δu = Nᵀ Jᵀ λ = 0   ⇒   H z = −Nᵀ M u_p,   H = Nᵀ M N   (n × n, Cholesky)
//! Jᵀ λ = M Δu   ⇒   λ joint by joint from the leaves (each joint's share of M Δu on its child)
//! ```
//!
//! **The recursion.** Joint k joins its child c (the body it brings into the chain) to its
//! parent p (a body of an earlier joint, or the world for the first). With r_c, r_p the levers
//! on the child's and the parent's side (σ = +1 when the child is the joint's A, −1 when B),
//! J u = r reads `(v_c + ω_c × r_c) − (v_p + ω_p × r_p) = σ r_point`, `g_i·(ω_c − ω_p) = σ r_i`:
//!
//! ```text
//! ω_c = ω_p + σ (r_1 h_1 + r_2 h_2) + n z_k          n = g_1 × g_2,   h_i·g_j = δ_ij (h_i ∈ span g)
//! v_c = σ r_point + v_p + ω_p × r_p − ω_c × r_c
//! ```
//!
//! so N's column k moves the child's subtree as one body turning about n at the child's anchor:
//! S_k = (r_c × n, n) on the child, carried to each descendant by the shift d = r_p − r_c of
//! every joint between (v ← v + ω × d: a rigid motion whose points are at the sums of the d's,
//! the bodies' centres when the anchors meet). Nᵀ f of forces f per body sums them from the
//! leaves, `f_p += f_c`, `τ_p += τ_c + d × f_c`, and `(Nᵀ f)_k = n·(τ_c − r_c × f_c)`.
//!
//! **H by composite bodies**, every body's point y (y_c = y_p + d, the root's at O) and every
//! quantity about O: a body's inertia `(m, h = m y, I + m (|y|² 1 − y yᵀ))`, a subtree's the
//! sum of its bodies' (children first), a column `S_k = (r_c × n − n × y_c, n)`;
//! `H_jk = S_j·(I^C_k S_k)` for j = k and each ancestor j, with
//! `I^C (v, ω) = (M v + ω × h, h × v + I ω)`. H = L Lᵀ is factored column by column. Every step
//! is J's own numbers at the current configuration, on the constraint manifold or off it, so
//! λ is K⁻¹ r to round-off (tested against a dense solve).
//!
//! **The forces of f(Y)** (`Reduced::accelerate`, `Chain::react`) need no λ: with
//! F̃ = (F, τ − ω × L) = M a_free, `J a_p = −J̇u`, `H z = Nᵀ (F̃ − M a_p)`, `a = a_p + N z`,
//! each body's total load is `(m a, I α + ω × L)` and `M a − F̃ = Jᵀ λ` gives each joint's
//! reaction from the leaves: a_free, J a_free and the rows' Jᵀ λ are never formed.
//!
//! **When.** Hinges only (a ball joint's three free turns would make H 3n wide, and its banded
//! blocks are already 3 rows: `solve`), the first joint on the world and each later one
//! bringing one new body (a tree rooted in the world), every body moving, at most [`MOST`]
//! hinges (H is dense). Otherwise `solve`'s banded factor. Callgrind, the 10-hinge chain (rk4,
//! `examples/chain_steps`, (1200 − 200 steps) / 1000): 142.3k instructions per step with the
//! banded factor, see the commit that brought this for after.
//!
//! **Tried and dropped** (same count, hinge chain per step, all three bit-identical): each
//! hinge's compact rows made as `read` reads them, with the composite inertias placed there
//! and no links stored, 125.19k -> 130.99k; Lᵀ kept by rows for the back substitution (each
//! L_ic copied in `cholesky`), 125.19k -> 126.86k; the back substitution's column read row by
//! row instead of `step_by`, 124.61k -> 125.16k. The counts follow how the one inlined f(Y)
//! function is laid out more than the work removed. Also tried (2026-12-07, bit-identical,
//! not kept): both substitutions' sums as plain loops over rows (no `step_by`), 120.27k ->
//! 120.28k; the solve's buffers sized once per tree instead of a `resize` at each solve,
//! 114.53k -> 115.02k.
//!
//! **Kept** (same count, each bit-identical): the projection's rows without J̇u
//! (`Chain::build_for_projection`), the composite inertias' diagonal-only additions and the
//! shares without multiplications by σ, the projection's kinetic energy from its build's v
//! and ω, the derive phase's R and I⁻¹_world from the projection's last build, the tree's
//! shape found once (`Reduced::tree_of`): 120.27k -> 114.53k per step, against MuJoCo
//! 4.0.1's RK4 hinge chain (`benches/mujoco/chain10.py` under callgrind, `mj_step`
//! collected): 115.06k, 0.995×. Build-to-build noise on this count is about ±1 %.

use super::chain::Link;
use super::solve::Inverse;
use crate::physics::effects::Loads;
use nalgebra::{Matrix3, Vector3};

/// No body: a body outside the chain (`Reduced::joint_of`).
const NONE: usize = usize::MAX;

/// The most hinges the reduced solve takes (H is dense: its factor is n³/6 multiply–adds).
const MOST: usize = 48;

/// One hinge, as the recursion reads it. Its child's motion, force and mass are at the
/// hinge's index in `Reduced`'s per-hinge lists; `up` is the parent's (n for the world: a
/// slot at rest that nothing reads back).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Hinge {
    /// The body it brings in, and its parent's hinge (n: the world).
    child: usize,
    up: usize,
    /// +1 when the child is the joint's A, −1 when it is B.
    sign: f64,
    /// The levers on the child's and on the parent's side.
    rc: Vector3<f64>,
    rp: Vector3<f64>,
    /// d = r_p − r_c.
    shift: Vector3<f64>,
    /// n = g_1 × g_2, and r_c × n: N's column on the child.
    axis: Vector3<f64>,
    motion: Vector3<f64>,
    /// h_1, h_2: in span(g_1, g_2), h_i·g_j = δ_ij.
    dual: [Vector3<f64>; 2],
}

/// A subtree's mass, first moment and inertia about its root's point.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Composite {
    mass: f64,
    moment: Vector3<f64>,
    inertia: Matrix3<f64>,
}

/// A motion (v, ω) or a force (f, τ) of one body.
type Pair = (Vector3<f64>, Vector3<f64>);

/// A column S_k about O (v, ω) and its child's point y.
type Column = (Vector3<f64>, Vector3<f64>, Vector3<f64>);

const REST: Pair = (Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 0.0));

/// The factor of the last [`Reduced::factor`] (its hinges, their children's M and H's
/// Cholesky factor) and the solve's buffers, all per hinge (its child).
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Reduced {
    hinges: Vec<Hinge>,
    /// Each child's m and I_world.
    mass: Vec<(f64, Matrix3<f64>)>,
    /// H's Cholesky factor L, n × n by rows (lower half), and 1/L_kk.
    lower: Vec<f64>,
    pivots: Vec<f64>,
    /// The rows of the held factor (0: none).
    held: usize,
    /// Per body: the hinge that brought it in (NONE: none), while [`Reduced::find_tree`]
    /// runs.
    joint_of: Vec<usize>,
    /// The links' bodies (A, B) and the body count the tree below was found for, the tree
    /// (per hinge: its child, its parent's hinge, whether the child is the joint's A), and
    /// whether they were a tree at all: a step's several solves do not walk it again.
    shape: Vec<(usize, Option<usize>)>,
    shape_bodies: usize,
    tree: Vec<(usize, usize, bool)>,
    is_tree: bool,
    composite: Vec<Composite>,
    /// Per hinge: its column S_k about O, and its child's point y (`joint_space_inertia`).
    columns: Vec<Column>,
    /// The solve's motions and forces (n + 1: the world's slot last), particular parts, z.
    motion: Vec<Pair>,
    force: Vec<Pair>,
    particular: Vec<Pair>,
    /// Each child's applied load (F, τ − ω × L) (`Reduced::accelerate`).
    applied: Vec<Pair>,
    z: Vec<f64>,
}

/// The inverse of a symmetric 3 × 3 matrix (its upper half read) by cofactors; None unless
/// it is positive definite enough to invert (det > 0).
#[inline(always)]
// `!(x > 0.0)` on purpose here and below: a NaN must fail the test too.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn symmetric_inverse(m: &Matrix3<f64>) -> Option<Matrix3<f64>> {
    let (a, b, c) = (m[(0, 0)], m[(0, 1)], m[(0, 2)]);
    let (d, e, f) = (m[(1, 1)], m[(1, 2)], m[(2, 2)]);
    let c00 = d * f - e * e;
    let c01 = c * e - b * f;
    let c02 = b * e - c * d;
    let det = a * c00 + b * c01 + c * c02;
    if !(det > 0.0) || !det.is_finite() {
        return None;
    }
    let r = 1.0 / det;
    let (c11, c12, c22) = (a * f - c * c, b * c - a * e, a * d - b * b);
    Some(Matrix3::new(
        c00 * r,
        c01 * r,
        c02 * r,
        c01 * r,
        c11 * r,
        c12 * r,
        c02 * r,
        c12 * r,
        c22 * r,
    ))
}

impl Reduced {
    /// Whether it holds a factor of `rows` rows.
    #[inline(always)]
    pub fn holds(&self, rows: usize) -> bool {
        rows > 0 && self.held == rows
    }

    /// How many bodies the held factor's world has.
    #[inline(always)]
    pub fn bodies(&self) -> usize {
        self.shape_bodies
    }

    /// Forgets the held factor.
    #[inline(always)]
    pub fn drop_factor(&mut self) {
        self.held = 0;
    }

    /// Factors H for the chain's compact rows `links` (module doc); false (nothing held) when
    /// they are not a hinge tree rooted in the world of moving bodies.
    #[inline(always)]
    pub fn factor(&mut self, links: &[Link], inverse: &[Inverse]) -> bool {
        self.held = 0;
        if links.len() > MOST || !self.read(links, inverse) {
            return false;
        }
        self.joint_space_inertia();
        if !self.cholesky() {
            return false;
        }
        self.held = 5 * links.len();
        true
    }

    /// The hinges from the links, and each child's m and I_world; false when they are not a
    /// hinge tree rooted in the world of moving bodies.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // a NaN must fail the tests
    fn read(&mut self, links: &[Link], inverse: &[Inverse]) -> bool {
        if !self.tree_of(links, inverse.len()) {
            return false;
        }
        self.hinges.clear();
        self.mass.clear();
        for (link, &(child, up, child_is_a)) in links.iter().zip(&self.tree) {
            if link.angular != 2 {
                return false;
            }
            let (sign, rc, rp) = if child_is_a {
                (1.0, link.ra, link.rb)
            } else {
                (-1.0, link.rb, link.ra)
            };
            let inv = &inverse[child];
            if !(inv.mass > 0.0) {
                return false;
            }
            let Some(inertia) = symmetric_inverse(&inv.inertia) else {
                return false;
            };
            self.mass.push((1.0 / inv.mass, inertia));
            let [g1, g2] = link.g;
            let (aa, ab, bb) = (g1.dot(&g1), g1.dot(&g2), g2.dot(&g2));
            let det = aa * bb - ab * ab;
            if !(det > 0.0) {
                return false;
            }
            let r = 1.0 / det;
            let axis = g1.cross(&g2);
            self.hinges.push(Hinge {
                child,
                up,
                sign,
                rc,
                rp,
                shift: rp - rc,
                axis,
                motion: rc.cross(&axis),
                dual: [(g1 * bb - g2 * ab) * r, (g2 * aa - g1 * ab) * r],
            });
        }
        true
    }

    /// Whether the links (on `bodies` bodies) are a tree rooted in the world, each joint
    /// bringing in one new body ([`Reduced::find_tree`]), asked again only when their bodies
    /// or the body count changed since the last answer.
    #[inline(always)]
    fn tree_of(&mut self, links: &[Link], bodies: usize) -> bool {
        let same = self.shape_bodies == bodies
            && self.shape.len() == links.len()
            && (self.shape.iter().zip(links)).all(|(&(a, b), l)| a == l.a && b == l.b);
        if !same {
            self.shape.clear();
            self.shape.extend(links.iter().map(|l| (l.a, l.b)));
            self.shape_bodies = bodies;
            self.is_tree = self.find_tree(links, bodies);
        }
        self.is_tree
    }

    /// The tree of the links (per hinge its child, its parent's hinge, n for the world, and
    /// whether the child is its A) into `tree`: the first joint on the world, each later one
    /// joining a new body to one an earlier joint brought in. False otherwise.
    fn find_tree(&mut self, links: &[Link], bodies: usize) -> bool {
        let n = links.len();
        self.joint_of.clear();
        self.joint_of.resize(bodies, NONE);
        self.tree.clear();
        for (k, link) in links.iter().enumerate() {
            let a = link.a;
            let (child, up, child_is_a) = match link.b {
                None if k == 0 => (a, n, true),
                None => return false,
                Some(b) => match (self.joint_of[a], self.joint_of[b]) {
                    (NONE, up) if up != NONE => (a, up, true),
                    (up, NONE) if up != NONE => (b, up, false),
                    _ => return false,
                },
            };
            self.joint_of[child] = k;
            self.tree.push((child, up, child_is_a));
        }
        true
    }

    /// H = Nᵀ M N by composite bodies (module doc), its lower half into `lower`: every
    /// column S_k and every inertia taken about one point O (the root's), where the
    /// pairing H_jk = S_j·(I^C_k S_k) needs no carrying.
    // Loops over the hinges that index several per-hinge lists, as the formulas do.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn joint_space_inertia(&mut self) {
        let n = self.hinges.len();
        let Reduced {
            hinges,
            mass,
            lower,
            composite,
            columns,
            ..
        } = self;
        lower.clear();
        lower.resize(n * n, 0.0);
        composite.clear();
        columns.clear();
        // Each body's point y (y_child = y_parent + d, the root's at O), its column about O
        // (v − ω × y, ω) and its inertia about O (m, m y, I + m (|y|² 1 − y yᵀ)).
        for (hinge, &(m, inertia)) in hinges.iter().zip(mass.iter()) {
            let y = match hinge.up {
                up if up < columns.len() => columns[up].2 + hinge.shift,
                _ => Vector3::zeros(),
            };
            let axis = hinge.axis;
            columns.push((hinge.motion - axis.cross(&y), axis, y));
            let my = y * m;
            // I + m (|y|² 1 − y yᵀ), as (I + |y|² 1) − (m y) yᵀ: the diagonal's additions only
            // (the off-diagonal's I_ij + 0 are I_ij).
            let mut about_o = inertia;
            let square = my.dot(&y);
            for i in 0..3 {
                about_o[(i, i)] += square;
            }
            about_o -= my * y.transpose();
            composite.push(Composite {
                mass: m,
                moment: my,
                inertia: about_o,
            });
        }
        for k in (0..n).rev() {
            let c = composite[k];
            let (v, w, _) = &columns[k];
            let p = v * c.mass + w.cross(&c.moment);
            let l = c.moment.cross(v) + c.inertia * w;
            // H_kj at L's place (row k, column j ≤ k: `lower[k n + j]`).
            lower[k * n + k] = v.dot(&p) + w.dot(&l);
            let mut j = hinges[k].up;
            while j < n {
                let (vj, wj, _) = &columns[j];
                lower[k * n + j] = vj.dot(&p) + wj.dot(&l);
                j = hinges[j].up;
            }
            if let Some(parent) = composite.get_mut(hinges[k].up) {
                parent.mass += c.mass;
                parent.moment += c.moment;
                parent.inertia += c.inertia;
            }
        }
    }

    /// H = L Lᵀ in place (lower half, by rows: L_ij at `lower[i n + j]`), column by column,
    /// each entry its own sum in the order of the columns left of it,
    /// `L_ic = (H_ic − Σ_{j<c} L_ij L_cj) / L_cc` (a dot product along two rows: the same
    /// operations, in the same order, as subtracting each column's update from the columns
    /// right of it); 1/L_jj into `pivots`. False when H is not positive definite to 1e-12 of
    /// its largest diagonal entry.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // a NaN must fail the tests
    fn cholesky(&mut self) -> bool {
        let n = self.hinges.len();
        let h = &mut self.lower;
        let mut largest = 0.0_f64;
        for k in 0..n {
            largest = largest.max(h[k * n + k]);
        }
        let pivots = &mut self.pivots;
        pivots.clear();
        pivots.resize(n, 0.0);
        for (c, pivot_c) in pivots.iter_mut().enumerate() {
            let (done, rest) = h.split_at_mut((c + 1) * n);
            let (left, diagonal) = done[c * n..].split_at_mut(c);
            let d = left.iter().fold(diagonal[0], |s, l| s - l * l);
            if !(d > 1e-12 * largest) {
                return false;
            }
            let root = d.sqrt();
            let pivot = 1.0 / root;
            diagonal[0] = root;
            *pivot_c = pivot;
            let left = &*left;
            for row in rest.chunks_exact_mut(n) {
                let (row_left, x) = row.split_at_mut(c);
                let s = (row_left.iter().zip(left)).fold(x[0], |s, (y, l)| s - y * l);
                x[0] = s * pivot;
            }
        }
        true
    }

    /// K λ = `rhs` with the held factor (the configuration of the last [`Reduced::factor`]),
    /// λ written over `rhs`'s first rows.
    #[inline(always)]
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let n = self.hinges.len();
        self.motions(rhs);
        let Reduced {
            hinges,
            mass,
            motion,
            force,
            ..
        } = self;
        // Jᵀ λ = M Δu: each joint's share on its child, leaves to root.
        momenta(mass, motion, force);
        for (k, r) in rhs[..5 * n].chunks_exact_mut(5).enumerate().rev() {
            let hinge = &hinges[k];
            let (lin, ang) = force[k];
            let f = lin * hinge.sign;
            let t = ang * hinge.sign - hinge.rc.cross(&f);
            r.copy_from_slice(&[f.x, f.y, f.z, hinge.dual[0].dot(&t), hinge.dual[1].dot(&t)]);
            let parent = &mut force[hinge.up];
            parent.0 += f * hinge.sign;
            parent.1 += (hinge.rp.cross(&f) + t) * hinge.sign;
        }
    }

    /// Δu = M⁻¹ Jᵀ λ for K λ = `rhs` with the held factor, λ never formed: each hinge's
    /// child's (Δv, Δω) written into `out` at its body's index (other bodies untouched). A
    /// position pass moves each body by it (`x += Δv`, turned by Δω).
    #[inline(always)]
    pub fn displace(&mut self, rhs: &[f64], out: &mut [Pair]) {
        self.motions(rhs);
        for (hinge, m) in self.hinges.iter().zip(&self.motion) {
            out[hinge.child] = *m;
        }
    }

    /// Jᵀ λ for K λ = `rhs` with the held factor, λ never formed: each hinge's child's
    /// M Δu = (m Δv, I Δω) written into `moved` at its body's index (other bodies untouched),
    /// and each joint's share on its body A added to `reactions` (as `Chain::apply` of λ).
    // Loops over the hinges that index several per-hinge lists, as the formulas do.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    pub fn impulses(&mut self, rhs: &[f64], moved: &mut [Loads], reactions: &mut [Loads]) {
        let n = self.hinges.len();
        self.motions(rhs);
        let Reduced {
            hinges,
            mass,
            motion,
            force,
            ..
        } = self;
        for k in 0..n {
            let ((m, inertia), (v, w)) = (&mass[k], &motion[k]);
            let p = (v * *m, inertia * w);
            moved[hinges[k].child] = Loads {
                force: p.0,
                torque: p.1,
            };
            force[k] = p;
        }
        force[n] = REST;
        shares(hinges, force, reactions);
    }

    /// Δu = u_p + N z for J Δu = `rhs` with the held factor (`motion`'s first n: each
    /// hinge's child's), the first part of [`Reduced::solve`].
    // Loops over the hinges that index several per-hinge lists, as the formulas do.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn motions(&mut self, rhs: &[f64]) {
        let n = self.hinges.len();
        let Reduced {
            hinges,
            mass,
            lower,
            pivots,
            motion,
            force,
            particular,
            z,
            ..
        } = self;
        let rhs = &rhs[..5 * n];
        motion.resize(n + 1, REST);
        motion[n] = REST;
        force.resize(n + 1, REST);
        particular.resize(n, REST);
        z.resize(n, 0.0);
        // u_p: J u_p = r, root to leaves.
        for (k, (hinge, r)) in hinges.iter().zip(rhs.chunks_exact(5)).enumerate() {
            let point = Vector3::new(r[0], r[1], r[2]) * hinge.sign;
            let turn = (hinge.dual[0] * r[3] + hinge.dual[1] * r[4]) * hinge.sign;
            particular[k] = (point, turn);
            let (vp, wp) = motion[hinge.up];
            let w = wp + turn;
            motion[k] = (point + vp + wp.cross(&hinge.rp) - w.cross(&hinge.rc), w);
        }
        // −Nᵀ M u_p, leaves to root.
        momenta(mass, motion, force);
        for k in (0..n).rev() {
            let hinge = &hinges[k];
            let (f, t) = force[k];
            z[k] = -hinge.axis.dot(&(t - hinge.rc.cross(&f)));
            let parent = &mut force[hinge.up];
            parent.0 += f;
            parent.1 += t + hinge.shift.cross(&f);
        }
        substitute(lower, pivots, z);
        // Δu = u_p + N z, root to leaves.
        along_hinges(hinges, particular, z, motion);
    }
}

impl Reduced {
    /// The accelerations the joints allow, with the factor just made from `links`, and the
    /// loads that give them: each child's `loads` (F, τ in; m a, I α + ω × L out) and each
    /// joint's reaction on its body A added to `reactions` (J_Aᵀ λ, as `Chain::apply`).
    /// `gyroscopic(b)` is ω × L of body b. The same problem as `Chain::rhs`, `solve` and
    /// `apply` (K λ = −(J a_free + J̇u), F += Jᵀ λ), through the joint coordinates:
    ///
    /// ```text
    /// J a_p = −J̇u,   H z = Nᵀ (F̃ − M a_p),   a = a_p + N z,   Jᵀ λ = M a − F̃
    /// ```
    ///
    /// with F̃ = (F, τ − ω × L) = M a_free: a_free and J a_free are never formed.
    // Loops over the hinges that index several per-hinge lists, as the formulas do.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    pub fn accelerate(
        &mut self,
        links: &[Link],
        gyroscopic: impl Fn(usize) -> Vector3<f64>,
        loads: &mut [Loads],
        reactions: &mut [Loads],
    ) {
        let n = self.hinges.len();
        let Reduced {
            hinges,
            mass,
            lower,
            pivots,
            motion,
            force,
            particular,
            applied,
            z,
            ..
        } = self;
        motion.resize(n + 1, REST);
        motion[n] = REST;
        force.resize(n + 1, REST);
        force[n] = REST;
        particular.resize(n, REST);
        applied.resize(n, REST);
        z.resize(n, 0.0);
        // a_p: J a_p = −J̇u, root to leaves.
        for (k, (hinge, link)) in hinges.iter().zip(links).enumerate() {
            let point = link.centripetal * -hinge.sign;
            let turn = (hinge.dual[0] * link.bias[0] + hinge.dual[1] * link.bias[1]) * -hinge.sign;
            particular[k] = (point, turn);
            force[k] = REST;
            let (vp, wp) = motion[hinge.up];
            let w = wp + turn;
            motion[k] = (point + vp + wp.cross(&hinge.rp) - w.cross(&hinge.rc), w);
        }
        // Nᵀ (F̃ − M a_p), leaves to root.
        for k in (0..n).rev() {
            let hinge = &hinges[k];
            let load = &loads[hinge.child];
            let f_applied = (load.force, load.torque - gyroscopic(hinge.child));
            applied[k] = f_applied;
            let (m, inertia) = &mass[k];
            let (v, w) = &motion[k];
            let (f, t) = force[k];
            let f = f + f_applied.0 - v * *m;
            let t = t + f_applied.1 - inertia * w;
            force[k] = REST;
            z[k] = hinge.axis.dot(&(t - hinge.rc.cross(&f)));
            let parent = &mut force[hinge.up];
            parent.0 += f;
            parent.1 += t + hinge.shift.cross(&f);
        }
        substitute(lower, pivots, z);
        // a = a_p + N z, root to leaves.
        along_hinges(hinges, particular, z, motion);
        // Jᵀ λ = M a − F̃: each joint's share on its child, leaves to root.
        force[n] = REST;
        for k in (0..n).rev() {
            let hinge = &hinges[k];
            let (m, inertia) = &mass[k];
            let (v, w) = &motion[k];
            let (lin, ang) = (v * *m, inertia * w);
            let (f_lin, f_ang) = &applied[k];
            let total = &mut loads[hinge.child];
            total.force = lin;
            total.torque = ang + (total.torque - f_ang);
            let (c_lin, c_ang) = force[k];
            let load = (lin - f_lin + c_lin, ang - f_ang + c_ang);
            share(hinge, load, force, &mut reactions[k]);
        }
    }
}

/// Each joint's load on its child and its share on its body A (added to `reactions`), leaves
/// to root, from `force`: each child's own total constraint load (Jᵀλ on it; the world's
/// slot n at rest). Joint k's load on its child is the child's own plus what the joints
/// below put on it, (w, τ_w); with f = σ w, t = σ τ_w − r_c × f its load on A is (w, τ_w)
/// when the child is A, else q = (f, r_p × f + t), and the parent takes σ q.
#[inline(always)]
fn shares(hinges: &[Hinge], force: &mut [Pair], reactions: &mut [Loads]) {
    for (k, hinge) in hinges.iter().enumerate().rev() {
        share(hinge, force[k], force, &mut reactions[k]);
    }
}

/// One joint's step of [`shares`]: its load on its child (w, τ_w) into `reaction` (on A)
/// and σ q onto its parent's slot of `force`.
#[inline(always)]
fn share(hinge: &Hinge, (w_lin, w_ang): Pair, force: &mut [Pair], reaction: &mut Loads) {
    // σ = ±1: σ x is x or −x, and a + σ x is a + x or a − x, exactly.
    let parent = &mut force[hinge.up];
    if hinge.sign > 0.0 {
        let t = w_ang - hinge.rc.cross(&w_lin);
        parent.0 += w_lin;
        parent.1 += hinge.rp.cross(&w_lin) + t;
        reaction.force += w_lin;
        reaction.torque += w_ang;
    } else {
        let f = -w_lin;
        let t = -w_ang - hinge.rc.cross(&f);
        let q = (f, hinge.rp.cross(&f) + t);
        parent.0 -= q.0;
        parent.1 -= q.1;
        reaction.force += q.0;
        reaction.torque += q.1;
    }
}

/// `force` = M `motion` of every child, (m v, I ω); the world's slot at rest.
#[inline(always)]
fn momenta(mass: &[(f64, Matrix3<f64>)], motion: &[Pair], force: &mut [Pair]) {
    for ((f, (m, inertia)), (v, w)) in force.iter_mut().zip(mass).zip(motion) {
        *f = (v * *m, inertia * w);
    }
    force[mass.len()] = REST;
}

/// z ← H⁻¹ z with H = L Lᵀ (L by rows): L y = z row by row, then Lᵀ x = y from the last row
/// up, each entry's sum in the order of the columns (rows) before (after) it.
#[inline(always)]
fn substitute(lower: &[f64], pivots: &[f64], z: &mut [f64]) {
    let n = z.len();
    for (i, (row, pivot)) in lower.chunks_exact(n).zip(pivots).enumerate() {
        let (before, rest) = z.split_at_mut(i);
        let s = (row[..i].iter().zip(&*before)).fold(rest[0], |s, (l, y)| s - l * y);
        rest[0] = s * pivot;
    }
    for i in (0..n).rev() {
        let (head, after) = z.split_at_mut(i + 1);
        // L_ki for k > i: column i below the diagonal.
        let below = lower.get((i + 1) * n + i..).unwrap_or_default();
        let below = below.iter().step_by(n);
        let s = (after.iter().zip(below)).fold(head[i], |s, (x, l)| s - l * x);
        head[i] = s * pivots[i];
    }
}

/// The bodies' motions from a particular motion and the hinges' coordinates z, root to
/// leaves: body k moves as its parent (v_p + ω_p × r_p at the joint), plus its own particular
/// part and its turn about the hinge axis z_k a,
///
/// ```text
/// ω_k = ω_p + turn_k + z_k a_k,    v_k = point_k + v_p + ω_p × r_p − ω_k × r_c
/// ```
///
/// (u = u_p + N z for velocities, a = a_p + N z for accelerations: the same map).
#[inline(always)]
fn along_hinges(hinges: &[Hinge], particular: &[Pair], z: &[f64], motion: &mut [Pair]) {
    for (k, hinge) in hinges.iter().enumerate() {
        let (point, turn) = particular[k];
        let (vp, wp) = motion[hinge.up];
        let w = wp + turn + hinge.axis * z[k];
        motion[k] = (point + vp + wp.cross(&hinge.rp) - w.cross(&hinge.rc), w);
    }
}

#[cfg(test)]
mod tests {
    use super::super::chain::{Chain, Wanted};
    use super::super::rows::{rows_of, Pose, Row};
    use super::super::solve::tests::{next, vector};
    use super::super::solve::{multipliers, Solver};
    use super::super::{Joint, JointKind};
    use super::*;
    use crate::physics::state::{Orientation, State};
    use nalgebra::{DMatrix, DVector, UnitQuaternion};

    /// A chain of `n` hinges in random poses moved off the joints (|C| ~ 1e-2), joint 0 on
    /// the world, joint k joining body k to body k − 1 (A the new body, or B when `swapped`
    /// says so), with random axes, velocities and inverse masses.
    fn chain(n: usize, swapped: &[bool], seed: &mut u64) -> (Vec<Joint>, Vec<Pose>, Vec<Inverse>) {
        let states: Vec<State> = (0..n)
            .map(|i| State {
                position: Vector3::new(i as f64 * 0.5, 0.0, 0.0) + 0.1 * vector(seed),
                orientation: Orientation::Quaternion(UnitQuaternion::from_scaled_axis(vector(
                    seed,
                ))),
                ..State::at_rest()
            })
            .collect();
        let joints = (0..n)
            .map(|i| {
                let at = Vector3::new(i as f64 * 0.5 - 0.25, 0.05, 0.0);
                let (a, b) = match i.checked_sub(1) {
                    Some(p) if swapped[i % swapped.len()] => (p, Some(i)),
                    p => (i, p),
                };
                Joint::at_point(
                    "h".into(),
                    JointKind::Hinge,
                    a,
                    b,
                    at,
                    vector(seed),
                    &states,
                )
            })
            .collect();
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
        let inverse = poses
            .iter()
            .map(|p| {
                let d = Vector3::new(3.0, 1.5, 2.0) + 0.5 * vector(seed);
                Inverse {
                    mass: 1.0 + 0.5 * next(seed),
                    inertia: p.r * Matrix3::from_diagonal(&d) * p.r.transpose(),
                }
            })
            .collect();
        (joints, poses, inverse)
    }

    /// Every force and torque of `got` within 1e-12 of `want`'s largest (or of 1).
    fn assert_close(got: &[Loads], want: &[Loads]) {
        let flat = |l: &[Loads]| -> Vec<f64> {
            l.iter()
                .flat_map(|l| [l.force.as_slice(), l.torque.as_slice()].concat())
                .collect()
        };
        let (got, want) = (flat(got), flat(want));
        assert_eq!(got.len(), want.len());
        let scale = want.iter().fold(1.0_f64, |m, w| m.max(w.abs()));
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-12 * scale, "{g} against {w}");
        }
    }

    /// K = J W Jᵀ dense, from the rows.
    fn dense(rows: &[Row], inverse: &[Inverse]) -> DMatrix<f64> {
        let n = inverse.len();
        let mut j = DMatrix::<f64>::zeros(rows.len(), 6 * n);
        for (i, r) in rows.iter().enumerate() {
            let sides = [(r.a(), r.lin_a(), r.ang_a())]
                .into_iter()
                .chain(r.b().map(|b| (b, r.lin_b(), r.ang_b())));
            for (body, lin, ang) in sides {
                for k in 0..3 {
                    j[(i, 6 * body + k)] += lin[k];
                    j[(i, 6 * body + 3 + k)] += ang[k];
                }
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

    /// The reduced solve gives a dense LU solve's λ to 1e-12 (relative) and the banded
    /// factor's to 1e-12, off the constraint manifold, on chains whose joints take the new
    /// body as A or as B; solving again with the held factor gives the same bits; a chain
    /// with a fixed body (inverse mass 0) or a ball joint is declined.
    #[test]
    fn the_reduced_solve_equals_a_dense_solve() {
        let seed = &mut 3;
        for (n, swapped) in [
            (2, &[false][..]),
            (10, &[false][..]),
            (7, &[false, true, true][..]),
        ] {
            let (joints, poses, inverse) = chain(n, swapped, seed);
            let mut rows = Vec::new();
            for (index, joint) in joints.iter().enumerate() {
                let b = joint.b.map_or(Pose::WORLD, |b| poses[b]);
                rows_of(joint, index, &poses[joint.a], &b, &mut rows);
            }
            let rhs: Vec<f64> = (0..rows.len()).map(|_| next(seed)).collect();
            let want = dense(&rows, &inverse)
                .lu()
                .solve(&DVector::from_vec(rhs.clone()))
                .expect("regular");
            let mut chain = Chain::default();
            assert!(chain.build(&joints, &poses));
            let mut got = rhs.clone();
            chain.solve(&inverse, &mut got, &mut Solver::default());
            assert!(chain.reduced.holds(rows.len()));
            let mut banded = rhs.clone();
            multipliers(&rows, &inverse, &mut banded, &mut Solver::default());
            let scale = want.amax();
            for ((got, want), banded) in got.iter().zip(want.iter()).zip(&banded) {
                assert!((got - want).abs() <= 1e-12 * scale, "{got} against {want}");
                assert!(
                    (got - banded).abs() <= 1e-12 * scale,
                    "{got} against {banded}"
                );
            }
            let mut again = rhs.clone();
            chain.reduced.solve(&mut again);
            let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&again), bits(&got));
            let mut fixed = inverse.clone();
            fixed[n / 2].mass = 0.0;
            assert!(!chain.reduced.factor(&chain.links, &fixed));
        }
        let (mut joints, poses, inverse) = chain(4, &[false], seed);
        joints[2].kind = JointKind::Ball;
        let mut chain = Chain::default();
        assert!(chain.build(&joints, &poses));
        assert!(!chain.reduced.factor(&chain.links, &inverse));
    }

    /// `Chain::react` (through the joint coordinates, a_free never formed) gives the loads
    /// and reactions of `Chain::rhs`, the multipliers and `Chain::apply` to 1e-12 (relative),
    /// off the constraint manifold, with bodies at speed.
    #[test]
    fn reacting_equals_the_multipliers_path() {
        let seed = &mut 9;
        let (joints, poses, inverse) = chain(7, &[false, true], seed);
        let mut rows = Vec::new();
        for (index, joint) in joints.iter().enumerate() {
            let b = joint.b.map_or(Pose::WORLD, |b| poses[b]);
            rows_of(joint, index, &poses[joint.a], &b, &mut rows);
        }
        let applied: Vec<Loads> = (0..poses.len())
            .map(|_| Loads {
                force: 5.0 * vector(seed),
                torque: vector(seed),
            })
            .collect();
        let gyro: Vec<Vector3<f64>> = (0..poses.len()).map(|_| vector(seed)).collect();
        let mut chain = Chain::default();
        assert!(chain.build(&joints, &poses));
        let free: Vec<_> = (applied.iter().zip(&inverse).zip(&gyro))
            .map(|((l, inv), g)| (l.force * inv.mass, inv.inertia * (l.torque - g)))
            .collect();
        let mut lambda = Vec::new();
        chain.rhs(&free, &mut lambda);
        multipliers(&rows, &inverse, &mut lambda, &mut Solver::default());
        let (mut want, mut want_reactions) = (applied.clone(), vec![Loads::default(); 7]);
        chain.apply(&lambda, &mut want, &mut want_reactions);
        let (mut got, mut got_reactions) = (applied.clone(), vec![Loads::default(); 7]);
        let solver = &mut Solver::default();
        assert!(chain.react(&inverse, solver, |i| gyro[i], &mut got, &mut got_reactions));
        assert_close(&got, &want);
        assert_close(&got_reactions, &want_reactions);
    }

    /// The projection's answers without λ, with the held factor: `Wanted::Impulses` gives
    /// `Chain::apply` of the solve's λ (Jᵀ λ on each body, each joint's share on A), and
    /// `Wanted::Moves` gives W Jᵀ λ, to 1e-12 (relative), off the constraint manifold.
    #[test]
    fn moves_and_impulses_are_the_multipliers_applied() {
        let seed = &mut 5;
        let (joints, poses, inverse) = chain(7, &[false, true, true], seed);
        let mut chain = Chain::default();
        assert!(chain.build(&joints, &poses));
        let rhs: Vec<f64> = (0..chain.rows()).map(|_| next(seed)).collect();
        let mut lambda = rhs.clone();
        chain.solve(&inverse, &mut lambda, &mut Solver::default());
        let rest = vec![Loads::default(); 7];
        let (mut want, mut want_reactions) = (rest.clone(), rest.clone());
        chain.apply(&lambda, &mut want, &mut want_reactions);
        let (mut got, mut got_reactions) = (Vec::new(), rest.clone());
        (chain.reduced).answer(&rhs, Wanted::Impulses(&mut got, &mut got_reactions));
        let mut moves = Vec::new();
        chain.reduced.answer(&rhs, Wanted::Moves(&mut moves));
        let moved: Vec<Loads> = (want.iter().zip(&inverse))
            .map(|(l, inv)| Loads {
                force: l.force * inv.mass,
                torque: inv.inertia * l.torque,
            })
            .collect();
        let as_loads: Vec<Loads> = (moves.iter())
            .map(|&(force, torque)| Loads { force, torque })
            .collect();
        assert_close(&got, &want);
        assert_close(&got_reactions, &want_reactions);
        assert_close(&as_loads, &moved);
    }

    /// The 10-hinge chain of `chain_steps` (hinges about z, moving in the xy plane, where a
    /// hinge's two angular rows carry nothing) follows the ball chain (the banded factor) to
    /// 1e-12 m over 0.3 s under every integrator: the reduced forces of f(Y) and the
    /// projection's reduced solves are the multipliers' to round-off, so every method keeps
    /// its order.
    #[test]
    fn the_hinge_chain_follows_the_ball_chain_under_every_integrator() {
        use crate::joint_scenes::chain;
        use crate::physics::joints::Correction;
        use crate::physics::Integrator;
        for integrator in Integrator::ALL {
            let mut worlds = [JointKind::Ball, JointKind::Hinge]
                .map(|kind| chain(10, kind, Correction::Projection));
            for world in &mut worlds {
                world.set_integrator(integrator);
                for _ in 0..300 {
                    world.step();
                }
            }
            let [ball, hinge] = &worlds;
            for (a, b) in ball.states().iter().zip(hinge.states()) {
                let dx = (a.position - b.position).amax();
                let dl = (a.angular_momentum - b.angular_momentum).amax();
                assert!(
                    dx < 1e-12 && dl < 1e-12,
                    "{}: {dx:e} m, {dl:e}",
                    integrator.name()
                );
                assert!(a.position.z.abs() < 1e-12 && b.position.z.abs() < 1e-12);
            }
        }
    }
}
