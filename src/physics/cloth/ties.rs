//! Ties: particles held to a body's surface (contact) or to a body's point (attach) *inside*
//! the implicit step's linear solve — Baraff & Witkin's constraint filtering (1998, §5),
//! extended so that the velocity a tied particle is held to may belong to a rigid body that is
//! itself an unknown of the solve.
//!
//! # The filter (Baraff & Witkin §5.1–5.3)
//!
//! A particle constrained along k directions has `S_i = I − Σ p pᵀ` over those directions
//! (k = 0: S = I; one contact normal n: S = I − n nᵀ; all three: S = 0) and a prescribed part
//! z_i of its velocity change in them. The modified conjugate gradient solves
//! `filter(A Δv) = filter(b)` for Δv with `(I − S_i) Δv_i = z_i`, filtering (multiplying by
//! S_i) every residual and search direction, so the constrained components stay exactly
//! z_i whatever the number of iterations. The constraint's impulse is what the filtered
//! system left out: the residual at that particle, `λ_i = (I − S_i)(A Δv − b)_i` (the force
//! the constraint applied over the step, times h). A contact whose λ·n would pull the particle
//! onto the surface is released and the step solved again (§6.2's rule for cloth–solid
//! contact: a constraint is let go when its force turns attractive).
//!
//! # The body's side: the body is an unknown too
//!
//! Here the prescribed velocity of a tied particle is a target t_i (where the caller wants
//! the particle to end: on the body's surface, `cloth_coupling::tied_step`) plus the motion
//! Y = (Y_V, Y_ω) the very impulses the particles take add to the body's point,
//! `(I − S_i) v_i = (I − S_i)(t_i + Y_V + Y_ω × r_i)`; Y joins the unknowns, with the body's
//! mass matrix in the solve M_b = diag(M I, I_world) (the caller may scale it: a body whose
//! position takes only a fraction of its correction enters with M/factor). A tied
//! particle's velocity change is affine in the reduced unknowns (y_i the free part,
//! S_i y_i = y_i):
//!
//! ```text
//! Δv_i = S_i y_i + G_i Y + z_i,    G_i Y = (I − S_i)(Y_V + Y_ω × r_i)
//!                                  z_i   = (I − S_i)(t_i − v₀_i)
//! ```
//!
//! i.e. Δv = T x + z with x = (y, Y). The step minimises ½ Δvᵀ A Δv − Δvᵀ b + ½ Yᵀ M_b Y −
//! Yᵀ b_Y over that affine set, which is the symmetric positive-definite system
//!
//! ```text
//! Tᵀ Ā T x = Tᵀ (b̄ − Ā z),      Ā = diag(A, M_b),   b̄ = (b + e, −Σ_i [e_i; r_i × e_i])
//! (Tᵀ q)_i = S_i q_i,           (Tᵀ q)_Y = M_b Y + Σ_i [(I − S_i) q_i;  r_i × (I − S_i) q_i]
//! ```
//!
//! (e_i an impulse from outside the constraint — sliding friction — on the particle, its
//! opposite on the body). Its solution is backward Euler's step of sheet and body
//! together with the contact as an equality constraint: the body's weight is carried by the
//! springs behind the particles within the step, not a step later. Conjugate gradients run on x with
//! the block-Jacobi preconditioner `S_i P_i⁻¹ S_i` for the particles and
//! `(M_b + Σ_i G_iᵀ P_i G_i)⁻¹` (6 × 6) for each body. Because the constrained components are
//! built from Y, a particle and the body's surface move together exactly, at any tolerance.
//!
//! # Joints on the bodies: a filter on Y
//!
//! A body the ties pull may itself be held by joints (a pole on a hinge at a wall). Solved
//! apart — the joints in their own step, the cloth after — the hinge would learn of the
//! cloth's pull a step late: the pull turns the pole within the cloth's step, the next step's
//! projection turns it back, and that projection's energy climbs while nothing moves. So the
//! joints' velocity rows are held here, on the same footing as a tie: the bodies' corrections
//! must not move them apart,
//!
//! ```text
//! J Y = 0,    Y = (Y₁, …, Y_k) the stacked corrections of the bodies the joint rows touch
//!             (a fixed body or the world has no Y: its columns are dropped)
//! ```
//!
//! (the rows `J` of `joints::rows_of` at the bodies' poses after their own step; the joints'
//! own step already left them at J u = 0). With N an orthonormal basis of null(J) (6k × d),
//! the bodies' unknowns are Y = N w: the bodies' preconditioner becomes
//!
//! ```text
//! Q = N (Nᵀ D N)⁻¹ Nᵀ,    D = blockdiag(M_b + Σ_i G_iᵀ P_i G_i)   (the bodies' 6 × 6 blocks)
//! ```
//!
//! exactly Baraff & Witkin's filter applied to the bodies: Y starts at 0 and every search
//! direction is Q times a residual, so Y stays in null(J) at every iteration and the solve
//! minimises the step's energy over the motions the joints allow. The joints' impulse on the
//! bodies is then what the filter left out of the bodies' rows, as for a tie:
//!
//! ```text
//! W_b = M_b Y_b + Σ_{ties on b} [λ_i + e_i; r_i × (λ_i + e_i)]     (= Jᵀ μ at the solution)
//! ```
//!
//! An ideal joint does no work: W·Y = μᵀ J Y = 0. (The caller reads μ per joint from W.)
//! The momentum closure below is skipped when a tied body is held by a joint: the joint's
//! impulse comes from outside the sheet and its bodies.
//!
//! # Warm starts
//!
//! A solve starts cold: the particles' y from the last Δv (as in the untied solve), a body's
//! Y from 0. Why not Y from the last Y: a solve stopped at tolerance ε leaves in
//! x an error up to ε of the right-hand side (mostly the body's: ~90 % of δ₀ while it rests
//! on the sheet), and what a warm start hands on is never corrected while it stays below ε.
//! For a body that error is a correction ΔV, Δω applied again step after step: a steady
//! push or torque of up to ε times the weight's. Measured with Y carried over: the
//! frictionless centred drop of lesson 16 went from 1.8e-14 m off centre to 1.0e-7 m
//! within its landing (0.3 → 0.5 s) and 6–12 mm, 0.4–0.7° at 4 s; lesson 31's box at dt =
//! 10 ms rested 1.5e-5 m from the statics. Started from 0, the Krylov space of a
//! mirror-symmetric scene is mirror-symmetric, and each step's error is fresh, not summed.
//! Its price: a resting cube's solve takes ~8 iterations instead of 1 (none while it moves:
//! the last Y is no better a guess then).
//!
//! **The round's warm start, when the step barely changed.** A step solves its tied system
//! in rounds (the first contact set; the set after a contact was released or began to slide;
//! …: a cube resting with friction on a trampoline sticks all its contacts in the first
//! round and lets them slide in the second, every step). When a moving body is tied by
//! contacts (no attachment among the ties), each round first tries what the *same* round
//! ended with the step before, (y, Y) = (Δv, Y)
//! then, and keeps it only when its residual is already small,
//!
//! ```text
//! √(δ_w/δ₀) ≤ WARM_GATE = 0.01     (δ_w the warm start's δ, δ₀ the right-hand side's)
//! ```
//!
//! i.e. the system barely changed since the last step: a body at rest. Then the solve runs
//! until its residual is both below ε of the right-hand side and CONTRACTION = 0.1 of the
//! warm start's, `δ ≤ min(ε² δ₀, 0.01 δ_w)`. The second bound is what removes the objection
//! above: each step shrinks the error it was handed by at least 10 (in the preconditioned
//! residual's norm), so what a step carries over is a geometric series, at most
//! 1/(1 − 0.1) ≈ 1.11 times one step's own error, never a sum over the steps. Otherwise
//! (a moving body: landing, bouncing) the trial is dropped and the solve starts cold exactly
//! as above, to the last bit; the trial costs one product, so after a dropped one the round
//! skips its trial for [`TRIAL_PAUSE`] = 7 steps (a body coming to rest waits at most that
//! long for its warm starts). Measured: lesson 16's landing
//! (steps 272–555) has the same bits as with cold starts only; at rest its solve takes 1–3
//! iterations instead of ~8, and the cube's height at 4 s moves by 1e-6 m; the frictionless
//! centred drop keeps its mirror symmetry exactly (`tests/physics/cloth_world.rs`). A body held
//! by joints starts its Y from 0 (its last Y kept last step's rows, not these). Not with
//! attachments: a frame attached to the sheet and resting on the floor is moved again by the
//! floor after every step, and warm-started its rim's load leant 0.1 N sideways (lesson 35,
//! `tests/physics/cloth_attach.rs`: 3 g = 29.43 N straight up within 0.02 N).
//!
//! **Momentum.** The impulses are internal: at the exact solution the particles' momentum
//! changes by `Σ b_i − M ΔV` and the body's by `M ΔV`. The solve stops at a tolerance, so when
//! nothing is pinned and every tie is to a body, the free particles (untied) get the uniform
//! shift that makes `Σ a_i Δv_i = Σ b_i − Σ_bodies M ΔV` exactly (a translation: it changes no
//! spring and no tie): body + sheet keep their momentum to round-off.
//!
//! **Friction** (Coulomb, μ): a sticking contact ties all three components (S = 0: the
//! particle moves with the body's point); if its impulse leaves the cone, |λ_t| > μ λ_n, the
//! caller makes it a normal tie with the bounded impulse `e = μ λ_n λ_t/|λ_t|` and solves again.
//! **Attach** is a permanent full tie whose u_i brings the particle back to its point.

#![allow(clippy::needless_range_loop)] // parallel per-particle arrays, indexed together

use super::conjugate_gradient::{Symmetric3, Workspace};
use crate::physics::constraints::{attachment::point_jacobian, SolverBody};
use nalgebra::{Matrix3, Matrix3x6, Matrix6, Vector3, Vector6};

/// Which components of a particle's velocity a tie prescribes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TieKind {
    /// Along the normal only (S = I − n nᵀ): a frictionless or sliding contact.
    Normal,
    /// All three (S = 0): a sticking contact, or an attached particle.
    Full,
}

/// A rigid body as the tied solve sees it: its solver body (the constraint layer's
/// [`SolverBody`]: V and ω after the body's own step, 1/M and I⁻¹), and, since its velocity
/// change is an unknown of the same linear solve as the particles', the solve's mass matrix
/// M_b = diag(M I, I_world) (not the inverses a contact solver applies impulses with) and the
/// solution, its correction.
#[derive(Debug, Clone, Copy)]
pub struct TiedBody {
    /// The body's solver body: V, ω, L after its own step, before the ties; 1/M, I⁻¹.
    pub body: SolverBody,
    /// M in the solve, kg; 0 for a body that cannot move (then it has no unknowns).
    pub mass: f64,
    /// World inertia tensor about the barycenter in the solve, kg·m².
    pub inertia: Matrix3<f64>,
    /// Out: the change the ties made, ΔV (m/s) and Δω (rad/s).
    pub correction: [Vector3<f64>; 2],
}

/// Joint rows on the solve's bodies: the bodies' corrections must keep `J Y = 0` (module doc,
/// "Joints on the bodies"). Empty: no body is held.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BodyJoints {
    /// The bodies the rows touch (indices into the solve's bodies, each one that moves), in
    /// the order their corrections are stacked.
    pub bodies: Vec<usize>,
    /// An orthonormal basis N of null(J), 6k × d (d = 0: the rows hold the bodies still).
    basis: nalgebra::DMatrix<f64>,
}

impl BodyJoints {
    /// The filter of rows `rows` (r × 6k, each row J over the stacked corrections of
    /// `bodies`): N from the eigenvectors of Jᵀ J whose eigenvalue is below 1e-12 of the
    /// largest (a redundant row removes nothing).
    pub fn new(bodies: Vec<usize>, rows: &nalgebra::DMatrix<f64>) -> BodyJoints {
        let size = 6 * bodies.len();
        debug_assert_eq!(rows.ncols(), size);
        let normal = rows.transpose() * rows;
        let eigen = nalgebra::SymmetricEigen::new(normal);
        let largest = eigen
            .eigenvalues
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let free: Vec<usize> = (0..size)
            .filter(|&k| eigen.eigenvalues[k] <= 1e-12 * largest)
            .collect();
        let mut basis = nalgebra::DMatrix::zeros(size, free.len());
        for (c, &k) in free.iter().enumerate() {
            basis.set_column(c, &eigen.eigenvectors.column(k));
        }
        BodyJoints { bodies, basis }
    }

    /// Whether no body is held.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// `Q = N (Nᵀ D N)⁻¹ Nᵀ` over the held bodies' stacked 6-vectors, D = blockdiag(`block(b)`)
    /// for b in [`BodyJoints::bodies`]: the inverse of D on the motions the joints allow (Y = Q w
    /// minimises ½ Yᵀ D Y − Yᵀ w subject to J Y = 0), 0 when they allow none.
    pub fn filtered_inverse(
        &self,
        block: impl Fn(usize) -> Matrix6<f64>,
    ) -> nalgebra::DMatrix<f64> {
        let size = 6 * self.bodies.len();
        let mut d = nalgebra::DMatrix::<f64>::zeros(size, size);
        for (g, &b) in self.bodies.iter().enumerate() {
            d.view_mut((6 * g, 6 * g), (6, 6)).copy_from(&block(b));
        }
        let n = &self.basis;
        let reduced = n.transpose() * &d * n;
        match reduced.cholesky() {
            Some(c) if n.ncols() > 0 => n * c.inverse() * n.transpose(),
            _ => nalgebra::DMatrix::zeros(size, size),
        }
    }
}

/// One particle tied to a body (or to a fixed surface when `body` is None).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tie {
    pub particle: usize,
    /// Index into the solve's bodies; None: a fixed surface (an obstacle).
    pub body: Option<usize>,
    /// The tie's point relative to the body's barycenter, m.
    pub arm: Vector3<f64>,
    /// Unit normal out of the body (towards the particle).
    pub normal: Vector3<f64>,
    pub kind: TieKind,
    /// The particle's velocity the tie prescribes besides the body's correction, m/s: its
    /// tied components are `(I − S)(target + ΔV + Δω × r)` (Normal: only its n part counts).
    pub target: Vector3<f64>,
    /// An impulse on the particle from outside the constraint (sliding friction), N·s; the
    /// body takes its opposite.
    pub extra: Vector3<f64>,
    /// Never released (attach).
    pub permanent: bool,
    /// Out: the impulse the constraint gave the particle, λ (N·s), besides `extra`.
    pub impulse: Vector3<f64>,
}

impl Tie {
    /// (I − S) u: the tied components of u.
    #[inline(always)]
    fn tied(&self, u: &Vector3<f64>) -> Vector3<f64> {
        match self.kind {
            TieKind::Normal => self.normal * self.normal.dot(u),
            TieKind::Full => *u,
        }
    }

    /// S u: the free components of u.
    #[inline(always)]
    fn free(&self, u: &Vector3<f64>) -> Vector3<f64> {
        u - self.tied(u)
    }

    /// I − S, the projector on its tied directions, Σ d dᵀ over its rows' directions d: n nᵀ
    /// (Normal: one row along n), I (Full: three rows along e_x, e_y, e_z, as an attachment's,
    /// `constraints::Attachment::rows`).
    #[inline(always)]
    fn projector(&self) -> Matrix3<f64> {
        match self.kind {
            TieKind::Normal => self.normal * self.normal.transpose(),
            TieKind::Full => Matrix3::identity(),
        }
    }

    /// G_i = (I − S_i) `[I, −[r]×]` (module doc): the tied components of the body's point
    /// velocity, G Y = (I − S)(Y_V + Y_ω × r), from the layer's point Jacobian
    /// ([`point_jacobian`]: the body end of its rows is −G, row by row). The products of the
    /// solve's loops apply it as `tied(point(Y, r))` and its transpose as `wrench(tied(u), r)`.
    #[inline(always)]
    fn jacobian(&self) -> Matrix3x6<f64> {
        self.projector() * point_jacobian(&self.arm)
    }
}

/// The tied solve's extra buffers (kept in the workspace, reused from step to step).
#[derive(Debug, Clone, Default)]
pub struct TieBuffers {
    /// Per particle: its tie's index, or u32::MAX.
    tie_of: Vec<u32>,
    inverse: Vec<Symmetric3>,
    /// The particles whose P⁻¹ this step's last round filtered, with their P⁻¹ before.
    filtered: Vec<(usize, Symmetric3)>,
    offset: Vec<Vector3<f64>>,
    /// The rows of p a product expanded in place, as they were (`multiply_reduced`).
    saved: Vec<(usize, Vector3<f64>)>,
    full: Vec<Vector3<f64>>,
    /// Per body: the 6 × 6 preconditioner's inverse, the unknown Y and its CG vectors.
    body_inverse: Vec<Matrix6<f64>>,
    body: Vec<BodyVectors>,
    /// The buffers of a product (`conjugate_gradient::product`).
    terms: super::conjugate_gradient::ProductBuffers,
    /// Per tie, its body and the wrench it adds there, before they are summed
    /// ([`add_wrenches`]); and the values of one sum.
    wrenches: Vec<(usize, Vector6<f64>)>,
    values: Vec<f64>,
    /// The tied rows of a product (`multiply_reduced`).
    tied_rows: Vec<(usize, Vector3<f64>)>,
    /// Per solve of a step (its round: the first, the one after the contact set changed, …),
    /// what that solve ended with the step before: the next step's solve of the same round
    /// starts from it (module doc, "Warm starts").
    starts: Vec<Start>,
    /// The rounds solved since [`TieBuffers::new_step`].
    round: usize,
    /// A solve's cold start, kept while its warm start is tried.
    kept: Vec<Vector3<f64>>,
    /// The particles' reduced right-hand side Tᵀ(b̄ − Ā z) (`start_residual` reads it: a
    /// start tried and dropped leaves it as it was).
    reduced: Vec<Vector3<f64>>,
    /// The rows of A z to compute, and which are listed (`solve_tied`).
    rows: Vec<usize>,
    marked: Vec<bool>,
    /// Per particle, whether it is pinned.
    is_pinned: Vec<bool>,
    /// Joints on the bodies: Q = N (Nᵀ D N)⁻¹ Nᵀ over the held bodies' stacked corrections,
    /// and per body whether it is held (module doc).
    held_inverse: nalgebra::DMatrix<f64>,
    held: Vec<bool>,
    /// The bodies' vectors of a solve, kept for their allocations (`solve_tied` takes them).
    body_scratch: BodyScratch,
}

/// Per body, what one solve builds beside [`BodyVectors`] (every entry written before read).
#[derive(Debug, Clone, Default)]
struct BodyScratch {
    /// M_b + Σ G_iᵀ P_i G_i, and the terms G_iᵀ P_i G_i of the ties on a moving body.
    blocks: Vec<Matrix6<f64>>,
    terms: Vec<(usize, Matrix6<f64>)>,
    /// The right-hand side; the unknown Y, its product and its search direction.
    rhs: Vec<Vector6<f64>>,
    x: Vec<Vector6<f64>>,
    q: Vec<Vector6<f64>>,
    direction: Vec<Vector6<f64>>,
}

/// What one round's solve ended with: Δv per particle, Y per body.
#[derive(Debug, Clone, Default)]
struct Start {
    particles: Vec<Vector3<f64>>,
    bodies: Vec<Vector6<f64>>,
    /// Steps this round skips its trial for (after a trial was dropped: [`TRIAL_PAUSE`]).
    pause: u32,
}

/// The steps a round waits before trying its warm start again after one was dropped (a body
/// in motion): a dropped trial costs a product for nothing (module doc, "Warm starts").
pub const TRIAL_PAUSE: u32 = 7;

#[derive(Debug, Clone, Copy, Default)]
struct BodyVectors {
    x: Vector6<f64>,
    r: Vector6<f64>,
    z: Vector6<f64>,
    rhs: Vector6<f64>,
}

impl TieBuffers {
    /// A new step: its next solve is its first round.
    pub fn new_step(&mut self) {
        self.round = 0;
    }

    pub fn heap_bytes(&self) -> usize {
        use super::conjugate_gradient::bytes_of;
        bytes_of(&self.tie_of, self.tie_of.capacity())
            + bytes_of(&self.inverse, self.inverse.capacity())
            + bytes_of(&self.filtered, self.filtered.capacity())
            + bytes_of(&self.offset, self.offset.capacity())
            + bytes_of(&self.saved, self.saved.capacity())
            + bytes_of(&self.full, self.full.capacity())
            + bytes_of(&self.body_inverse, self.body_inverse.capacity())
            + bytes_of(&self.body, self.body.capacity())
            + self.terms.heap_bytes()
            + bytes_of(&self.wrenches, self.wrenches.capacity())
            + bytes_of(&self.values, self.values.capacity())
            + bytes_of(&self.tied_rows, self.tied_rows.capacity())
            + bytes_of(&self.rows, self.rows.capacity())
            + bytes_of(&self.marked, self.marked.capacity())
            + bytes_of(&self.is_pinned, self.is_pinned.capacity())
            + self.held_inverse.len() * std::mem::size_of::<f64>()
            + bytes_of(&self.held, self.held.capacity())
            + bytes_of(&self.starts, self.starts.capacity())
            + bytes_of(&self.kept, self.kept.capacity())
            + bytes_of(&self.reduced, self.reduced.capacity())
            + bytes_of(
                &self.body_scratch.blocks,
                self.body_scratch.blocks.capacity(),
            )
            + bytes_of(&self.body_scratch.terms, self.body_scratch.terms.capacity())
            + bytes_of(&self.body_scratch.rhs, self.body_scratch.rhs.capacity())
            + bytes_of(&self.body_scratch.x, self.body_scratch.x.capacity())
            + bytes_of(&self.body_scratch.q, self.body_scratch.q.capacity())
            + bytes_of(
                &self.body_scratch.direction,
                self.body_scratch.direction.capacity(),
            )
            + (self.starts.iter())
                .map(|s| {
                    bytes_of(&s.particles, s.particles.capacity())
                        + bytes_of(&s.bodies, s.bodies.capacity())
                })
                .sum::<usize>()
    }
}

/// A round's warm start is kept when its residual is already below this fraction of the
/// right-hand side's, √(δ_w/δ₀) ≤ WARM_GATE (module doc, "Warm starts").
pub const WARM_GATE: f64 = 0.01;

/// How much a warm-started solve shrinks its starting residual at least, √(δ/δ_w) ≤
/// CONTRACTION, besides reaching ε of the right-hand side (module doc, "Warm starts").
pub const CONTRACTION: f64 = 0.1;

/// [ΔV; Δω] ↦ ΔV + Δω × r: G y with G = `[I, −[r]×]` ([`point_jacobian`]), summed as the
/// vectors, not as G's row products.
#[inline(always)]
fn point(y: &Vector6<f64>, r: &Vector3<f64>) -> Vector3<f64> {
    let (v, w) = (y.fixed_rows::<3>(0), y.fixed_rows::<3>(3));
    Vector3::new(v[0], v[1], v[2]) + Vector3::new(w[0], w[1], w[2]).cross(r)
}

/// u ↦ [u; r × u]: Gᵀ u (the transpose of `point`).
#[inline(always)]
fn wrench(u: &Vector3<f64>, r: &Vector3<f64>) -> Vector6<f64> {
    let t = r.cross(u);
    Vector6::new(u.x, u.y, u.z, t.x, t.y, t.z)
}

/// Σ values, the same to the last bit for any order of the values and exactly −Σ for the
/// negated values: the positive and the negative values each summed by increasing magnitude.
/// A body's sums over its ties use it, so that ties in mirror-image places (a cube centred on
/// a sheet) add up to a wrench with exact zeros where the mirror says so (`conjugate_gradient`,
/// "Sums in a mirror-symmetric order"); summed in the ties' order, a + b − a − b need not be 0.
fn order_free_sum(values: &mut [f64]) -> f64 {
    values.sort_unstable_by(|a, b| a.abs().total_cmp(&b.abs()));
    let (mut positive, mut negative) = (0.0, 0.0);
    for &v in values.iter() {
        if v > 0.0 {
            positive += v;
        } else {
            negative += v;
        }
    }
    positive + negative
}

/// out\[b\] += Σ the wrenches listed for body b, each component by [`order_free_sum`]
/// (`wrenches` is sorted by body, stably, to find each body's together).
fn add_wrenches(
    out: &mut [Vector6<f64>],
    wrenches: &mut [(usize, Vector6<f64>)],
    values: &mut Vec<f64>,
) {
    wrenches.sort_by_key(|w| w.0);
    for listed in wrenches.chunk_by(|a, b| a.0 == b.0) {
        let o = &mut out[listed[0].0];
        for c in 0..6 {
            values.clear();
            values.extend(listed.iter().map(|w| w.1[c]));
            o[c] += order_free_sum(values);
        }
    }
}

/// Each body's z = its preconditioner times its r (`from_rhs`: times its right-hand side):
/// the 6 × 6 inverse of its block, or for the bodies held by joints Q over their stacked
/// vectors (module doc, "Joints on the bodies").
fn precondition_bodies(t: &mut TieBuffers, joints: &BodyJoints, from_rhs: bool) {
    let pick = |bv: &BodyVectors| if from_rhs { bv.rhs } else { bv.r };
    for (b, bv) in t.body.iter_mut().enumerate() {
        if !t.held[b] {
            bv.z = t.body_inverse[b] * pick(bv);
        }
    }
    if joints.is_empty() {
        return;
    }
    let mut r = nalgebra::DVector::<f64>::zeros(6 * joints.bodies.len());
    for (g, &b) in joints.bodies.iter().enumerate() {
        r.rows_mut(6 * g, 6).copy_from(&pick(&t.body[b]));
    }
    let z = &t.held_inverse * r;
    for (g, &b) in joints.bodies.iter().enumerate() {
        t.body[b].z = z.fixed_rows::<6>(6 * g).into_owned();
    }
}

/// M_b Y.
#[inline(always)]
fn body_mass(b: &TiedBody, y: &Vector6<f64>) -> Vector6<f64> {
    let w = b.inertia * Vector3::new(y[3], y[4], y[5]);
    Vector6::new(b.mass * y[0], b.mass * y[1], b.mass * y[2], w.x, w.y, w.z)
}

/// What a tied solve is over: the ties, the bodies, the joints on them, the pinned particles.
struct Over<'a> {
    ties: &'a [Tie],
    bodies: &'a [TiedBody],
    joints: &'a BodyJoints,
    pinned: &'a [u32],
}

impl Over<'_> {
    /// Whether a tie has body terms: its body can move.
    #[inline(always)]
    fn moves(&self, tie: &Tie) -> bool {
        tie.body.is_some_and(|b| self.bodies[b].mass > 0.0)
    }
}

/// The workspace's buffers a tied solve takes while it runs (given back by `end_round`).
struct Taken {
    t: TieBuffers,
    is_pinned: Vec<bool>,
    body: BodyScratch,
}

/// A round of the tied solve: its number in the step, whether its warm start is tried, and
/// δ₀ of its right-hand side.
struct Round {
    round: usize,
    candidate: bool,
    delta0: f64,
}

/// A start filtered: a pinned row to 0, a tied row to its free part S y (only the rows a tie
/// or a pin names: every other row is left as it is).
#[inline(always)]
fn filter_start(solution: &mut [Vector3<f64>], tie_of: &[u32], over: &Over, is_pinned: &[bool]) {
    for (k, tie) in over.ties.iter().enumerate() {
        let i = tie.particle;
        if tie_of[i] == k as u32 && !is_pinned[i] {
            solution[i] = tie.free(&solution[i]);
        }
    }
    for &i in over.pinned {
        solution[i as usize] = Vector3::zeros();
    }
}

impl Workspace {
    /// Solves the tied system of the module doc. Before: `blocks`, `diagonal`, `rhs` and the
    /// (uninverted) `preconditioner` as the spring pass left them, `pinned` listed; `v0` the
    /// velocities at the start of the step. After: `solution` holds Δv of every particle
    /// (0 where pinned), each tie its impulse, each body its correction.
    pub fn solve_tied(
        &mut self,
        ties: &mut [Tie],
        bodies: &mut [TiedBody],
        joints: &BodyJoints,
        v0: &[Vector3<f64>],
        tolerance: f64,
        max_iterations: usize,
    ) -> super::conjugate_gradient::Outcome {
        #[cfg(target_arch = "x86_64")]
        if super::avx2() {
            // SAFETY: `solve_tied_avx2` is safe but for its target feature: calling it needs a
            // CPU with AVX2, which `avx2` checked just above.
            return unsafe {
                self.solve_tied_avx2(ties, bodies, joints, v0, tolerance, max_iterations)
            };
        }
        self.solve_tied_plain(ties, bodies, joints, v0, tolerance, max_iterations)
    }

    /// [`Workspace::solve_tied`] compiled with AVX2 (its loops and products inlined).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_tied_avx2(
        &mut self,
        ties: &mut [Tie],
        bodies: &mut [TiedBody],
        joints: &BodyJoints,
        v0: &[Vector3<f64>],
        tolerance: f64,
        max_iterations: usize,
    ) -> super::conjugate_gradient::Outcome {
        self.solve_tied_plain(ties, bodies, joints, v0, tolerance, max_iterations)
    }

    /// [`Workspace::solve_tied`] for any CPU, in named steps (each inlined: the AVX2 build
    /// compiles them all with its target feature).
    #[inline(always)]
    fn solve_tied_plain(
        &mut self,
        ties: &mut [Tie],
        bodies: &mut [TiedBody],
        joints: &BodyJoints,
        v0: &[Vector3<f64>],
        tolerance: f64,
        max_iterations: usize,
    ) -> super::conjugate_gradient::Outcome {
        let pinned = std::mem::take(&mut self.pinned);
        let mut s = self.take_tied(ties, bodies.len(), &pinned, v0);
        let over = Over {
            ties,
            bodies,
            joints,
            pinned: &pinned,
        };
        self.assemble_bodies(&mut s, &over);
        self.reduce_rhs(&mut s, &over);
        let round = self.begin_round(&mut s, &over);
        let outcome = if round.delta0.is_finite() && round.delta0 > 0.0 {
            self.iterate_tied(&mut s, &over, &round, (tolerance, max_iterations))
        } else {
            super::conjugate_gradient::Outcome {
                iterations: 0,
                relative_residual: 0.0,
            }
        };
        self.expand_solution(&s, &over);
        self.tie_impulses(&mut s, ties);
        self.end_round(s, bodies, round.round, pinned);
        outcome
    }

    /// The solve's buffers taken out of the workspace, with each particle's tie (`tie_of`),
    /// which are pinned, the prescribed part z (`offset`) and the particles' preconditioner
    /// S P⁻¹ S before the ties filter it.
    #[inline(always)]
    fn take_tied(
        &mut self,
        ties: &[Tie],
        body_count: usize,
        pinned: &[u32],
        v0: &[Vector3<f64>],
    ) -> Taken {
        let n = self.rhs.len();
        let mut t = std::mem::take(&mut self.ties);
        t.tie_of.clear();
        t.tie_of.resize(n, u32::MAX);
        for (k, tie) in ties.iter().enumerate() {
            t.tie_of[tie.particle] = k as u32;
        }
        let mut is_pinned = std::mem::take(&mut t.is_pinned);
        is_pinned.clear();
        is_pinned.resize(n, false);
        for &i in pinned {
            is_pinned[i as usize] = true;
        }
        // z: the prescribed part (module doc).
        t.offset.clear();
        t.offset.resize(n, Vector3::zeros());
        for tie in ties.iter() {
            let i = tie.particle;
            t.offset[i] = tie.tied(&(tie.target - v0[i]));
        }
        // Preconditioners: S P⁻¹ S for the particles, the bodies' 6 × 6. P⁻¹ is inverted on
        // a step's first round only (P does not change between its rounds): a later round
        // puts back the P⁻¹ of the particles the last round's ties filtered.
        if t.round == 0 || t.inverse.len() != n {
            // (A loop, not `extend`: inlined here, it is compiled for AVX2 with the rest.)
            t.inverse.resize(n, Symmetric3::default());
            for (inverse, p) in t.inverse.iter_mut().zip(&self.preconditioner) {
                *inverse = p.inverse();
            }
            for &i in pinned {
                t.inverse[i as usize] = Symmetric3::default();
            }
        } else {
            for &(i, inverse) in t.filtered.iter().rev() {
                t.inverse[i] = inverse;
            }
        }
        t.filtered.clear();
        t.body.clear();
        t.body.resize(body_count, BodyVectors::default());
        let body = std::mem::take(&mut t.body_scratch);
        Taken { t, is_pinned, body }
    }

    /// The ties filter the particles' preconditioners; each moving body's block
    /// M_b + Σ G_iᵀ P_i G_i and its inverse; the joints' Q over the held bodies.
    #[inline(always)]
    fn assemble_bodies(&self, s: &mut Taken, over: &Over) {
        let Taken { t, body, .. } = s;
        body.blocks.clear();
        body.blocks.extend(over.bodies.iter().map(|b| {
            let mut m = Matrix6::zeros();
            for k in 0..3 {
                m[(k, k)] = b.mass;
            }
            m.fixed_view_mut::<3, 3>(3, 3).copy_from(&b.inertia);
            m
        }));
        body.terms.clear();
        for tie in over.ties.iter() {
            let i = tie.particle;
            let p = &self.preconditioner[i];
            let [a, e, f, b, c, d] = p.0;
            let full = Matrix3::new(a, b, c, b, e, d, c, d, f);
            let free = Matrix3::identity() - tie.projector();
            t.filtered.push((i, t.inverse[i]));
            let inv = t.inverse[i].0;
            let inv_full = Matrix3::new(
                inv[0], inv[3], inv[4], inv[3], inv[1], inv[5], inv[4], inv[5], inv[2],
            );
            let filtered = free * inv_full * free;
            t.inverse[i] = Symmetric3([
                filtered[(0, 0)],
                filtered[(1, 1)],
                filtered[(2, 2)],
                filtered[(0, 1)],
                filtered[(0, 2)],
                filtered[(1, 2)],
            ]);
            if over.moves(tie) {
                let g = tie.jacobian();
                body.terms
                    .push((tie.body.unwrap(), g.transpose() * full * g));
            }
        }
        // Summed in no particular order (`order_free_sum`): each body's terms together (a
        // stable sort: in the ties' order), then every entry's sum over them.
        body.terms.sort_by_key(|x| x.0);
        for terms in body.terms.chunk_by(|a, c| a.0 == c.0) {
            let m = &mut body.blocks[terms[0].0];
            for e in 0..36 {
                t.values.clear();
                t.values.extend(terms.iter().map(|x| x.1[e]));
                m[e] += order_free_sum(&mut t.values);
            }
        }
        t.body_inverse.clear();
        t.body_inverse
            .extend(body.blocks.iter().zip(over.bodies.iter()).map(|(m, b)| {
                if b.mass > 0.0 {
                    m.try_inverse().unwrap_or_else(Matrix6::zeros)
                } else {
                    Matrix6::zeros()
                }
            }));
        // Joints on the bodies: Q = N (Nᵀ D N)⁻¹ Nᵀ over the held bodies (module doc).
        t.held.clear();
        t.held.resize(over.bodies.len(), false);
        if !over.joints.is_empty() {
            for &b in &over.joints.bodies {
                t.held[b] = true;
            }
            let blocks = &body.blocks;
            t.held_inverse = over.joints.filtered_inverse(|b| blocks[b]);
        }
    }

    /// Reduced right-hand side: Tᵀ(b̄ − Ā z) for the particles (`reduced`) and the bodies.
    #[inline(always)]
    fn reduce_rhs(&self, s: &mut Taken, over: &Over) {
        let n = self.rhs.len();
        let Taken { t, is_pinned, body } = s;
        let ties = over.ties;
        // z is 0 but at the tied particles: on a grid sheet A z is computed only in their rows
        // and their springs' other ends (`SpringOrder::row`, the bits of the whole product);
        // every other row of the whole product is +0 (all its terms are), and so it is here.
        if self.order.springs == self.blocks.len() && self.order.slots.len() == n {
            t.full.clear();
            t.full.resize(n, Vector3::zeros());
            t.rows.clear();
            t.marked.clear();
            t.marked.resize(n, false);
            for tie in ties.iter() {
                let i = tie.particle;
                for k in std::iter::once(i).chain(
                    (self.order.slots[i].iter())
                        .filter_map(|&s| self.blocks.get(s as usize))
                        .flat_map(|b| [b.i as usize, b.j as usize]),
                ) {
                    if !t.marked[k] {
                        t.marked[k] = true;
                        t.rows.push(k);
                    }
                }
            }
            for &k in &t.rows {
                t.full[k] = self.order.row(&self.blocks, self.diagonal[k], &t.offset, k);
            }
        } else {
            Self::multiply_plain(
                &self.blocks,
                &self.diagonal,
                &self.order,
                &mut t.terms,
                &t.offset,
                &mut t.full,
            );
        }
        t.wrenches.clear();
        t.reduced.resize(n, Vector3::zeros());
        for (((reduced, (b, full)), &k), &pinned) in (t.reduced[..n].iter_mut())
            .zip(self.rhs[..n].iter().zip(&t.full[..n]))
            .zip(&t.tie_of[..n])
            .zip(&is_pinned[..n])
        {
            let mut r = b - full;
            if k != u32::MAX {
                let tie = &ties[k as usize];
                r += tie.extra;
                if over.moves(tie) {
                    let b = tie.body.unwrap();
                    t.wrenches.push((
                        b,
                        wrench(&tie.tied(&r), &tie.arm) - wrench(&tie.extra, &tie.arm),
                    ));
                }
                r = tie.free(&r);
            }
            if pinned {
                r = Vector3::zeros();
            }
            *reduced = r;
        }
        body.rhs.clear();
        body.rhs.resize(over.bodies.len(), Vector6::zeros());
        add_wrenches(&mut body.rhs, &mut t.wrenches, &mut t.values);
        for (bv, r) in t.body.iter_mut().zip(&body.rhs) {
            bv.rhs = *r;
        }
    }

    /// The round's number, whether its warm start is to be tried (module doc, "Warm
    /// starts"), and δ₀ from the reduced right-hand side; x starts from the last solve's,
    /// filtered, the bodies' Y from 0.
    #[inline(always)]
    fn begin_round(&mut self, s: &mut Taken, over: &Over) -> Round {
        let n = self.rhs.len();
        let Taken { t, is_pinned, body } = s;
        let bodies = over.bodies;
        let round = t.round;
        t.round += 1;
        let mut candidate = (t.starts.get(round))
            .filter(|s| s.particles.len() == n && s.bodies.len() == bodies.len())
            .is_some()
            && over.ties.iter().any(|tie| over.moves(tie))
            && !over.ties.iter().any(|tie| tie.permanent);
        if candidate && t.starts[round].pause > 0 {
            t.starts[round].pause -= 1;
            candidate = false;
        }
        body.x.clear();
        body.x.resize(bodies.len(), Vector6::zeros());
        let mut delta0 = 0.0;
        for (r, inverse) in t.reduced[..n].iter().zip(&t.inverse[..n]) {
            delta0 += r.dot(&inverse.apply(r));
        }
        precondition_bodies(t, over.joints, true);
        for bv in &t.body {
            delta0 += bv.rhs.dot(&bv.z);
        }
        filter_start(&mut self.solution, &t.tie_of, over, is_pinned);
        Round {
            round,
            candidate,
            delta0,
        }
    }

    /// Preconditioned CG on the reduced system from the round's start (warm when it passes
    /// the gate, else cold); the bodies' Y left in their vectors' `x`.
    #[inline(always)]
    fn iterate_tied(
        &mut self,
        s: &mut Taken,
        over: &Over,
        round: &Round,
        (tolerance, max_iterations): (f64, usize),
    ) -> super::conjugate_gradient::Outcome {
        let n = self.rhs.len();
        let delta0 = round.delta0;
        let mut product = std::mem::take(&mut self.product);
        let (warm, mut delta) = self.start_tied(s, over, round, &mut product);
        let Taken { t, body, .. } = s;
        // p = z: swapped, not copied (every iteration writes all of z before reading it).
        std::mem::swap(&mut self.direction, &mut self.preconditioned);
        // Stop at ε of the right-hand side; from the round's warm start, not before its
        // residual has shrunk by CONTRACTION (module doc, "Warm starts").
        let target = match warm {
            Some(warm) => (CONTRACTION * CONTRACTION * warm).min(tolerance * tolerance * delta0),
            None => tolerance * tolerance * delta0,
        };
        let mut iterations = 0;
        body.direction.clear();
        body.direction.extend(t.body.iter().map(|b| b.z));
        while delta > target && iterations < max_iterations {
            let mut direction = std::mem::take(&mut self.direction);
            self.multiply_reduced(
                t,
                over,
                &mut direction,
                &body.direction,
                &mut product,
                &mut body.q,
            );
            self.direction = direction;
            let mut curvature: f64 = (self.direction[..n].iter())
                .zip(&product[..n])
                .map(|(p, q)| p.dot(q))
                .sum();
            for (b, q) in body.q.iter().enumerate() {
                curvature += body.direction[b].dot(q);
            }
            if curvature.is_nan() || curvature <= 0.0 {
                break;
            }
            let alpha = delta / curvature;
            let mut next = 0.0;
            for ((((x, r), z), (p, q)), inverse) in (self.solution[..n].iter_mut())
                .zip(&mut self.residual[..n])
                .zip(&mut self.preconditioned[..n])
                .zip(self.direction[..n].iter().zip(&product[..n]))
                .zip(&t.inverse[..n])
            {
                *x += p * alpha;
                *r -= q * alpha;
                *z = inverse.apply(r);
                next += r.dot(z);
            }
            for (b, bv) in t.body.iter_mut().enumerate() {
                body.x[b] += body.direction[b] * alpha;
                bv.r -= body.q[b] * alpha;
            }
            precondition_bodies(t, over.joints, false);
            for bv in &t.body {
                next += bv.r.dot(&bv.z);
            }
            let beta = next / delta;
            for (p, z) in (self.direction[..n].iter_mut()).zip(&self.preconditioned[..n]) {
                *p = z + *p * beta;
            }
            for (b, bv) in t.body.iter().enumerate() {
                body.direction[b] = bv.z + body.direction[b] * beta;
            }
            delta = next;
            iterations += 1;
        }
        self.product = product;
        for (bv, x) in t.body.iter_mut().zip(&body.x) {
            bv.x = *x;
        }
        super::conjugate_gradient::Outcome {
            iterations,
            relative_residual: (delta / delta0).max(0.0).sqrt(),
        }
    }

    /// The round's start: its warm start, kept only when its residual δ_w is already within
    /// WARM_GATE of the right-hand side's (module doc, "Warm starts"), else the cold start
    /// (the last solve's Δv, filtered; zero when that is worse than zero). Returns (δ_w when
    /// warm, δ of the start).
    #[inline(always)]
    fn start_tied(
        &mut self,
        s: &mut Taken,
        over: &Over,
        round: &Round,
        product: &mut [Vector3<f64>],
    ) -> (Option<f64>, f64) {
        let n = self.rhs.len();
        let Taken { t, is_pinned, body } = s;
        body.q.clear();
        body.q.resize(over.bodies.len(), Vector6::zeros());
        let mut warm = None;
        if round.candidate {
            let r = round.round;
            // The cold start is kept aside and the round's last Δv taken, both swapped,
            // not copied (the round's start is written anew at the end of the solve).
            std::mem::swap(&mut self.solution, &mut t.kept);
            std::mem::swap(&mut self.solution, &mut t.starts[r].particles);
            filter_start(&mut self.solution, &t.tie_of, over, is_pinned);
            body.x.copy_from_slice(&t.starts[r].bodies);
            // A body held by joints starts from 0: its last Y kept last step's rows.
            for (x, &held) in body.x.iter_mut().zip(&t.held) {
                if held {
                    *x = Vector6::zeros();
                }
            }
            let delta = self.start_residual(t, over, &body.x, product, &mut body.q);
            if delta <= WARM_GATE * WARM_GATE * round.delta0 {
                warm = Some(delta);
            } else {
                t.starts[r].pause = TRIAL_PAUSE;
                // Not good enough: the cold start below, as if never tried.
                std::mem::swap(&mut self.solution, &mut t.kept);
                body.x.iter_mut().for_each(|x| *x = Vector6::zeros());
            }
        }
        if let Some(warm) = warm {
            return (Some(warm), warm);
        }
        let mut delta = self.start_residual(t, over, &body.x, product, &mut body.q);
        if delta > round.delta0 {
            // A warm start worse than zero: start from zero.
            self.solution.iter_mut().for_each(|x| *x = Vector3::zeros());
            body.x.iter_mut().for_each(|x| *x = Vector6::zeros());
            delta = 0.0;
            for (((r, z), q), inverse) in (self.residual[..n].iter_mut())
                .zip(&mut self.preconditioned[..n])
                .zip(&product[..n])
                .zip(&t.inverse[..n])
            {
                *r += q;
                *z = inverse.apply(r);
                delta += r.dot(z);
            }
            for bv in t.body.iter_mut() {
                bv.r = bv.rhs;
            }
            precondition_bodies(t, over.joints, false);
            for bv in &t.body {
                delta += bv.r.dot(&bv.z);
            }
        }
        (None, delta)
    }

    /// Δv = T x + z (the warm start of the next step keeps the free parts); then, with
    /// nothing pinned and every tie to a moving body, none of them held by a joint, the
    /// untied particles take the uniform shift that closes Σ a Δv = Σ b − Σ M ΔV (module doc,
    /// momentum).
    #[inline(always)]
    fn expand_solution(&mut self, s: &Taken, over: &Over) {
        let n = self.rhs.len();
        let t = &s.t;
        let ties = over.ties;
        // (Only the tied rows change: each once, by the tie `tie_of` names.)
        for (k, tie) in ties.iter().enumerate() {
            let i = tie.particle;
            if t.tie_of[i] == k as u32 {
                let mut tied = t.offset[i];
                if over.moves(tie) {
                    tied += tie.tied(&point(&t.body[tie.body.unwrap()].x, &tie.arm));
                }
                let dv = &mut self.solution[i];
                *dv = tie.free(dv) + tied;
            }
        }
        let held_tie = |tie: &Tie| tie.body.is_some_and(|b| t.held[b]);
        if over.pinned.is_empty()
            && ties.iter().all(|tie| over.moves(tie))
            && !ties.iter().any(held_tie)
        {
            let mut gap = Vector3::zeros();
            let mut free_mass = 0.0;
            for (((b, dv), &a), &k) in (self.rhs[..n].iter())
                .zip(&self.solution[..n])
                .zip(&self.diagonal[..n])
                .zip(&t.tie_of[..n])
            {
                gap += b - dv * a;
                if k == u32::MAX {
                    free_mass += a;
                }
            }
            for (b, bv) in over.bodies.iter().zip(&t.body) {
                gap -= Vector3::new(bv.x[0], bv.x[1], bv.x[2]) * b.mass;
            }
            if free_mass > 0.0 {
                let shift = gap / free_mass;
                for (dv, &k) in self.solution[..n].iter_mut().zip(&t.tie_of[..n]) {
                    if k == u32::MAX {
                        *dv += shift;
                    }
                }
            }
        }
    }

    /// λ_i = (I − S_i)(A Δv − b − e)_i: A Δv at the tied particles only when the springs
    /// are the grid's (`SpringOrder::row`, the same bits as the whole product).
    #[inline(always)]
    fn tie_impulses(&self, s: &mut Taken, ties: &mut [Tie]) {
        let n = self.rhs.len();
        let t = &mut s.t;
        let by_rows = self.order.springs == self.blocks.len() && self.order.slots.len() == n;
        if !by_rows {
            Self::multiply_plain(
                &self.blocks,
                &self.diagonal,
                &self.order,
                &mut t.terms,
                &self.solution,
                &mut t.full,
            );
        }
        for tie in ties.iter_mut() {
            let i = tie.particle;
            let product = if by_rows {
                self.order
                    .row(&self.blocks, self.diagonal[i], &self.solution, i)
            } else {
                t.full[i]
            };
            tie.impulse = tie.tied(&(product - self.rhs[i] - tie.extra));
        }
    }

    /// Keeps this round's solution as its start for the next step, gives each body its
    /// correction, and puts the buffers back into the workspace.
    #[inline(always)]
    fn end_round(&mut self, s: Taken, bodies: &mut [TiedBody], round: usize, pinned: Vec<u32>) {
        let Taken {
            mut t,
            is_pinned,
            body,
        } = s;
        if t.starts.len() <= round {
            t.starts.resize(round + 1, Start::default());
        }
        let start = &mut t.starts[round];
        start.particles.clone_from(&self.solution);
        start.bodies.clear();
        start.bodies.extend(t.body.iter().map(|bv| bv.x));
        for (b, bv) in bodies.iter_mut().zip(&t.body) {
            if b.mass > 0.0 {
                b.correction = [
                    Vector3::new(bv.x[0], bv.x[1], bv.x[2]),
                    Vector3::new(bv.x[3], bv.x[4], bv.x[5]),
                ];
            } else {
                b.correction = [Vector3::zeros(); 2];
            }
        }
        self.pinned = pinned;
        t.is_pinned = is_pinned;
        t.body_scratch = body;
        self.ties = t;
    }

    /// out = A p, no filter (`conjugate_gradient::product`).
    fn multiply_plain(
        blocks: &[super::conjugate_gradient::Block],
        diagonal: &[f64],
        order: &super::conjugate_gradient::SpringOrder,
        terms: &mut super::conjugate_gradient::ProductBuffers,
        p: &[Vector3<f64>],
        out: &mut Vec<Vector3<f64>>,
    ) {
        out.resize(p.len(), Vector3::zeros());
        super::conjugate_gradient::product(blocks, diagonal, order, terms, p, out);
    }

    /// The start's residual r = b − (Tᵀ Ā T) x for x = (`solution`, `x_body`), with `reduced`
    /// and the bodies' `rhs` holding b on entry; its preconditioned z; returns δ = r·z.
    /// `product` and `q_body` keep Tᵀ Ā T x (a start worse than zero is undone with it).
    #[inline(always)]
    fn start_residual(
        &mut self,
        t: &mut TieBuffers,
        over: &Over,
        x_body: &[Vector6<f64>],
        product: &mut [Vector3<f64>],
        q_body: &mut [Vector6<f64>],
    ) -> f64 {
        let n = self.rhs.len();
        let mut solution = std::mem::take(&mut self.solution);
        self.multiply_reduced(t, over, &mut solution, x_body, product, q_body);
        self.solution = solution;
        let mut delta = 0.0;
        for ((((r, z), b), q), inverse) in (self.residual[..n].iter_mut())
            .zip(&mut self.preconditioned[..n])
            .zip(&t.reduced[..n])
            .zip(&product[..n])
            .zip(&t.inverse[..n])
        {
            *r = b - q;
            *z = inverse.apply(r);
            delta += r.dot(z);
        }
        for (b, bv) in t.body.iter_mut().enumerate() {
            bv.r = bv.rhs - q_body[b];
        }
        precondition_bodies(t, over.joints, false);
        for bv in &t.body {
            delta += bv.r.dot(&bv.z);
        }
        delta
    }

    /// (out, out_body) = Tᵀ Ā T (p, p_body) (module doc). `p` is expanded in place (its
    /// tied rows to S p + G Y, its pinned rows to 0) for the product and given back as it came.
    #[inline(always)]
    fn multiply_reduced(
        &self,
        t: &mut TieBuffers,
        over: &Over,
        p: &mut [Vector3<f64>],
        p_body: &[Vector6<f64>],
        out: &mut [Vector3<f64>],
        out_body: &mut [Vector6<f64>],
    ) {
        let (ties, bodies, pinned) = (over.ties, over.bodies, over.pinned);
        let n = p.len();
        t.saved.clear();
        for tie in ties {
            let i = tie.particle;
            let mut w = tie.free(&p[i]);
            if let Some(b) = tie.body.filter(|&b| bodies[b].mass > 0.0) {
                w += tie.tied(&point(&p_body[b], &tie.arm));
            }
            t.saved.push((i, p[i]));
            p[i] = w;
        }
        for &i in pinned {
            let i = i as usize;
            // A row already +0 (as the CG's vectors keep a pinned row) is left as it is: no
            // saving, the same bits.
            if p[i].iter().any(|x| x.to_bits() != 0) {
                t.saved.push((i, p[i]));
                p[i] = Vector3::zeros();
            }
        }
        // A p straight into `out`; then the tied rows, and the pinned rows zeroed.
        super::conjugate_gradient::product(
            &self.blocks,
            &self.diagonal,
            &self.order,
            &mut t.terms,
            p,
            &mut out[..n],
        );
        for &(i, value) in t.saved.iter().rev() {
            p[i] = value;
        }
        for (b, o) in out_body.iter_mut().enumerate() {
            *o = body_mass(&bodies[b], &p_body[b]);
        }
        t.wrenches.clear();
        t.tied_rows.clear();
        for tie in ties {
            let i = tie.particle;
            let full = out[i];
            if let Some(b) = tie.body.filter(|&b| bodies[b].mass > 0.0) {
                t.wrenches.push((b, wrench(&tie.tied(&full), &tie.arm)));
            }
            t.tied_rows.push((i, tie.free(&full)));
        }
        for &i in pinned {
            out[i as usize] = Vector3::zeros();
        }
        for &(i, row) in &t.tied_rows {
            out[i] = row;
        }
        add_wrenches(out_body, &mut t.wrenches, &mut t.values);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// The rows of a ball joint at arm r (from the barycentre) to the world, `V + ω × r = 0`:
    /// for each axis e_k, `e_k·V + (r × e_k)·ω = 0`; with `hinge` also `(u × t)·ω = 0` for the
    /// two t ⊥ u.
    fn joint_rows(r: &Vector3<f64>, hinge: Option<Vector3<f64>>) -> DMatrix<f64> {
        let mut rows: Vec<[f64; 6]> = (0..3)
            .map(|k| {
                let e = Vector3::ith(k, 1.0);
                let a = r.cross(&e);
                [e.x, e.y, e.z, a.x, a.y, a.z]
            })
            .collect();
        if let Some(u) = hinge {
            let p = u.cross(&Vector3::new(0.3, 1.0, 0.2)).normalize();
            for t in [p, u.cross(&p)] {
                let g = u.cross(&t);
                rows.push([0.0, 0.0, 0.0, g.x, g.y, g.z]);
            }
        }
        DMatrix::from_fn(rows.len(), 6, |i, c| rows[i][c])
    }

    /// Each column of the basis as (V, ω).
    fn motions(joints: &BodyJoints) -> Vec<(Vector3<f64>, Vector3<f64>)> {
        (joints.basis.column_iter())
            .map(|c| {
                (
                    Vector3::new(c[0], c[1], c[2]),
                    Vector3::new(c[3], c[4], c[5]),
                )
            })
            .collect()
    }

    #[test]
    fn a_ties_jacobian_is_its_projector_on_the_layers_point_jacobian() {
        // A body at (V, ω) and a particle at rest tied at arm r: a Full tie's G is the layer's
        // point Jacobian (G y = V + ω × r); a Normal tie's takes its n part, and that is n times
        // the rate of the layer's row along n (particle at lever 0, body at r), negated.
        use crate::physics::constraints::Axis;
        let (v, w) = (Vector3::new(0.3, -1.0, 0.2), Vector3::new(0.5, 2.0, -1.5));
        let r = Vector3::new(0.2, -0.175, 0.1);
        let n = Vector3::new(0.3, 0.9, -0.2).normalize();
        let y = Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z);
        let mut tie = Tie {
            particle: 0,
            body: Some(1),
            arm: r,
            normal: n,
            kind: TieKind::Full,
            target: Vector3::zeros(),
            extra: Vector3::zeros(),
            permanent: true,
            impulse: Vector3::zeros(),
        };
        assert_eq!(tie.jacobian(), point_jacobian(&r));
        assert!((tie.jacobian() * y - (v + w.cross(&r))).norm() < 1e-15);
        assert_eq!(tie.tied(&point(&y, &r)), v + w.cross(&r));
        tie.kind = TieKind::Normal;
        let mut body = [
            SolverBody::particle(Vector3::zeros(), 100.0),
            SolverBody::new(v, Vector3::zeros(), 0.5, Matrix3::zeros()),
        ];
        body[1].omega = w;
        let rate = Axis::new(n, (0, &Vector3::zeros()), Some((1, &r)), &body).velocity(&body);
        let g = tie.jacobian() * y;
        assert!((g + n * rate).norm() < 1e-15, "{g} {rate}");
        assert!((g - tie.tied(&point(&y, &r))).norm() < 1e-15);
        // Its transpose is the wrench the tie's tied impulse puts on the body.
        let u = Vector3::new(1.0, -2.0, 0.5);
        let back = tie.jacobian().transpose() * u;
        assert!((back - wrench(&tie.tied(&u), &r)).norm() < 1e-15);
    }

    #[test]
    fn a_ball_joint_leaves_the_three_turns_about_its_point() {
        // Free motions: turns about the joint's point, V = −ω × r (the point stays): 3.
        let r = Vector3::new(-0.8, 0.1, 0.2);
        let joints = BodyJoints::new(vec![0], &joint_rows(&r, None));
        let free = motions(&joints);
        assert_eq!(free.len(), 3);
        for (v, w) in &free {
            assert!((v + w.cross(&r)).norm() < 1e-14, "{v:?} {w:?}");
        }
        let gram = joints.basis.transpose() * &joints.basis;
        assert!((gram - DMatrix::<f64>::identity(3, 3)).norm() < 1e-14);
    }

    #[test]
    fn a_hinge_leaves_one_turn_about_its_axis_through_its_point() {
        let r = Vector3::new(-0.8, 0.0, 0.0);
        let u = Vector3::new(1.0, 2.0, -0.5).normalize();
        let joints = BodyJoints::new(vec![0], &joint_rows(&r, Some(u)));
        let free = motions(&joints);
        assert_eq!(free.len(), 1);
        let (v, w) = free[0];
        // A unit vector of the stacked (V, ω), turning about u: ω ∥ u, ω ≠ 0.
        assert!((v.norm_squared() + w.norm_squared() - 1.0).abs() < 1e-14);
        assert!(
            w.norm() > 0.1 && w.cross(&u).norm() < 1e-14,
            "about the axis: {w:?}"
        );
        assert!((v + w.cross(&r)).norm() < 1e-14, "the point stays: {v:?}");
    }

    #[test]
    fn a_fixed_joint_leaves_no_motion() {
        // Ball rows and the three angular rows ω = 0.
        let mut rows = joint_rows(&Vector3::new(0.3, -0.2, 0.1), None);
        rows = rows.insert_rows(3, 3, 0.0);
        for k in 0..3 {
            rows[(3 + k, 3 + k)] = 1.0;
        }
        let joints = BodyJoints::new(vec![0], &rows);
        assert_eq!(joints.basis.ncols(), 0);
    }
}
