//! A chain of ball and hinge joints held inside f(Y) without building rows: each joint's rows
//! kept compact (its levers, the hinge's two angular parts and the J̇u terms), the banded
//! factor filled from them, and the right-hand side and the reactions summed from them.
//!
//! ```text
//! point row k (k < 3):  (e_k, r_A×e_k | −e_k, −r_B×e_k)       J̇u = ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)
//! hinge row (2):        (0, g | 0, −g),  g = u_A × t           J̇u = (ω_A − ω_B)·dg  (`kinds::hinge`)
//! rhs_i = −(J_i a_free + J̇u_i),   K λ = rhs (`solve`),   F += J_linᵀ λ,   τ += J_angᵀ λ
//! ```
//!
//! Each row's parts are the numbers `rows_of` would store (the same expressions), so K and
//! its factor are the row path's to the last bit; the right-hand side and the reactions are
//! summed a joint at a time (a point row's angular part r × e_k has the exact zero the row
//! path multiplies by), so they differ from the row path's by round-off. What is saved is
//! writing and reading the rows (208 bytes each), grouping them into blocks (a joint is a
//! block) and the zero terms.
//!
//! It applies when the joints are a chain in order (each joint shares bodies only with the
//! joint just before it, as `solve`'s banded factor needs, and no two consecutive joints join
//! the same two bodies, which the row path would merge into one block), of two or more ball
//! and hinge joints, with no Baumgarte term (which needs C and Ċ per row): anything else takes
//! the row path. A chain of hinges only, the first on the world, is solved through its joint
//! coordinates instead of K's banded factor (`reduced`: [`Chain::react`] for f(Y), the
//! reduced factor kept for the projection's chord passes, [`Nearby`]).

use super::kinds::{self, Anchors, JointKind};
use super::reduced::Reduced;
use super::rows::Pose;
use super::solve::{again, chain_multipliers, Inverse, Solver};
use super::Joint;
use crate::physics::effects::Loads;
use nalgebra::Vector3;

/// One joint's rows, compact: three point rows (levers r_A, r_B), then `angular` rows with
/// angular part g on A and −g on B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Link {
    pub a: usize,
    pub b: Option<usize>,
    pub ra: Vector3<f64>,
    pub rb: Vector3<f64>,
    /// The point rows' J̇u.
    pub centripetal: Vector3<f64>,
    /// 0 (ball) or 2 (hinge).
    pub angular: usize,
    pub g: [Vector3<f64>; 2],
    /// The angular rows' J̇u.
    pub bias: [f64; 2],
    /// C: the point rows' (the anchors' separation) and the angular rows'.
    pub separation: Vector3<f64>,
    pub c: [f64; 2],
}

impl Link {
    /// How many rows it has.
    #[inline(always)]
    pub fn rows(&self) -> usize {
        3 + self.angular
    }

    /// Row i's linear part on A (−it on B) and its angular parts on A and on B, as
    /// `Anchors::point_rows` and `hinge::rows` build them.
    #[inline(always)]
    pub fn row(&self, i: usize) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        if i < 3 {
            let e = Vector3::ith(i, 1.0);
            (e, self.ra.cross(&e), -self.rb.cross(&e))
        } else {
            let g = self.g[i - 3];
            (Vector3::zeros(), g, -g)
        }
    }
}

/// The compact rows of the last [`Chain::build`], per body the first joint on it, and the
/// reduced factor of the last [`Chain::solve`] when it was a hinge tree (`reduced`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Chain {
    pub(super) links: Vec<Link>,
    first: Vec<usize>,
    /// Whether every built joint is a hinge (the reduced solve's first condition).
    hinges: bool,
    /// The joints (A, B, kind) and body count `is_chain` last answered for, and its answer:
    /// the same topology is not walked again (an edited joint changes the key).
    checked: Vec<(usize, Option<usize>, JointKind)>,
    checked_bodies: usize,
    answer: bool,
    pub(super) reduced: Reduced,
}

/// A factor of K held from an earlier solve, to solve with again (the projection's chord
/// passes): a chain's reduced one, or a banded one in a [`Solver`] (`solve::again`).
pub struct Nearby<'a> {
    pub(super) solver: &'a mut Solver,
    pub(super) reduced: &'a mut Reduced,
}

impl Nearby<'_> {
    /// Whether it holds a factor of `rows` rows.
    #[inline(always)]
    pub(super) fn holds(&self, rows: usize) -> bool {
        self.reduced.holds(rows) || self.solver.holds(rows)
    }
}

/// What the projection asks of a solve K μ = rhs with a hinge chain's reduced factor, μ never
/// formed (`reduced::Reduced::displace`, `impulses`).
pub(super) enum Wanted<'a> {
    /// Each body's W Jᵀ μ = (Δx, θ) (a position pass), at its index (at rest off the chain).
    Moves(&'a mut Vec<(Vector3<f64>, Vector3<f64>)>),
    /// Each body's Jᵀ μ (a velocity pass), at its index (at rest off the chain), and each
    /// joint's share on its body A added to the reactions.
    Impulses(&'a mut Vec<Loads>, &'a mut [Loads]),
}

/// What a solve for the projection left.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Solved {
    /// Nothing: no factor of these rows was held.
    Not,
    /// μ over the right-hand side (a banded factor).
    Multipliers,
    /// What was [`Wanted`] (a reduced factor).
    Answered,
}

impl Reduced {
    /// What is `wanted` for K μ = `rhs` with the held factor, one entry per body of the
    /// factor's.
    #[inline(always)]
    pub(super) fn answer(&mut self, rhs: &[f64], wanted: Wanted) {
        let bodies = self.bodies();
        match wanted {
            Wanted::Moves(moves) => {
                moves.clear();
                moves.resize(bodies, (Vector3::zeros(), Vector3::zeros()));
                self.displace(rhs, moves);
            }
            Wanted::Impulses(moved, reactions) => {
                moved.clear();
                moved.resize(bodies, Loads::default());
                self.impulses(rhs, moved, reactions);
            }
        }
    }
}

impl Nearby<'_> {
    /// K μ = `rhs` with the held factor (K of its own configuration): what is `wanted` with
    /// a reduced one, μ over `rhs` with a banded one, nothing (`rhs` untouched) when it holds
    /// none of `rows` rows.
    #[inline(always)]
    pub(super) fn again_for(&mut self, rows: usize, rhs: &mut [f64], wanted: Wanted) -> Solved {
        if self.reduced.holds(rows) {
            self.reduced.answer(rhs, wanted);
            Solved::Answered
        } else if self.solver.holds(rows) && again(rhs, self.solver) {
            Solved::Multipliers
        } else {
            Solved::Not
        }
    }
}

impl Chain {
    /// K μ = `rhs` for the built rows as [`Chain::solve`], but through a hinge tree's
    /// reduced factor what is `wanted` instead of μ ([`Solved::Answered`]); μ over `rhs`
    /// otherwise ([`Solved::Multipliers`]).
    #[inline(always)]
    pub(super) fn solve_for(
        &mut self,
        inverse: &[Inverse],
        rhs: &mut [f64],
        solver: &mut Solver,
        wanted: Wanted,
    ) -> Solved {
        if self.hinges && self.reduced.factor(&self.links, inverse) {
            if solver.holds(self.rows()) {
                *solver = Solver::default();
            }
            self.reduced.answer(rhs, wanted);
            return Solved::Answered;
        }
        chain_multipliers(&self.links, inverse, rhs, solver);
        Solved::Multipliers
    }

    /// The joints' compact rows at `poses`, when they are a chain of ball and hinge joints in
    /// order (module doc); false (nothing built, no reduced factor held) otherwise.
    #[inline(always)]
    pub fn build(&mut self, joints: &[Joint], poses: &[Pose]) -> bool {
        self.build_with::<true, true>(joints, poses)
    }

    /// [`Chain::build`] without the rows' J̇u (each link's `centripetal` and `bias` left at
    /// zero): the rows the projection solves with, which read J and C only (the anchors'
    /// ω × (ω × r) and the hinges' (ω_A − ω_B)·ġ are not computed). Its J and C are
    /// [`Chain::build`]'s to the last bit (the same expressions).
    #[inline(always)]
    pub fn build_for_projection(&mut self, joints: &[Joint], poses: &[Pose]) -> bool {
        self.build_with::<true, false>(joints, poses)
    }

    /// [`Chain::build`] without the rows' C (each link's `separation` and `c` left at zero):
    /// the rows f(Y) solves with, which read J and J̇u only (the separation and the hinges'
    /// u·t are not computed).
    #[inline(always)]
    pub fn build_for_forces(&mut self, joints: &[Joint], poses: &[Pose]) -> bool {
        self.build_with::<false, true>(joints, poses)
    }

    /// [`Chain::build`], C computed when `ERRORS`, J̇u when `RATES` (what is not computed is
    /// left at zero, and the optimiser drops its arithmetic).
    #[inline(always)]
    fn build_with<const ERRORS: bool, const RATES: bool>(
        &mut self,
        joints: &[Joint],
        poses: &[Pose],
    ) -> bool {
        if !self.is_chain_cached(joints, poses.len()) {
            self.reduced.drop_factor();
            return false;
        }
        self.links.clear();
        self.hinges = true;
        for (index, joint) in joints.iter().enumerate() {
            let a = &poses[joint.a];
            let b = joint.b.map_or(&Pose::WORLD, |b| &poses[b]);
            let at = Anchors::of(joint, index, a, b);
            let mut link = Link {
                a: joint.a,
                b: joint.b,
                ra: at.ra,
                rb: at.rb,
                centripetal: if RATES {
                    at.centripetal
                } else {
                    Vector3::zeros()
                },
                angular: 0,
                g: [Vector3::zeros(); 2],
                bias: [0.0; 2],
                separation: if ERRORS {
                    at.separation
                } else {
                    Vector3::zeros()
                },
                c: [0.0; 2],
            };
            self.hinges &= joint.kind == JointKind::Hinge;
            if joint.kind == JointKind::Hinge {
                let axes = kinds::hinge_axes(joint, a, b);
                link.angular = 2;
                for (i, (g, c, bias)) in axes.into_iter().enumerate() {
                    link.g[i] = g;
                    link.c[i] = if ERRORS { c } else { 0.0 };
                    link.bias[i] = if RATES { bias } else { 0.0 };
                }
            }
            self.links.push(link);
        }
        true
    }

    /// [`Chain::is_chain`], asked again only when the joints' bodies or kinds or the body
    /// count changed since the last answer.
    #[inline(always)]
    fn is_chain_cached(&mut self, joints: &[Joint], bodies: usize) -> bool {
        let same = self.checked_bodies == bodies
            && self.checked.len() == joints.len()
            && (self.checked.iter().zip(joints))
                .all(|(&(a, b, kind), j)| a == j.a && b == j.b && kind == j.kind);
        if !same {
            self.answer = self.is_chain(joints, bodies);
            self.checked.clear();
            self.checked
                .extend(joints.iter().map(|j| (j.a, j.b, j.kind)));
            self.checked_bodies = bodies;
        }
        self.answer
    }

    /// Whether `joints` (on `bodies` bodies) are two or more ball and hinge joints in chain
    /// order: every joint's bodies first touched by it or the joint before, and no two
    /// consecutive joints on the same bodies.
    fn is_chain(&mut self, joints: &[Joint], bodies: usize) -> bool {
        const NONE: usize = usize::MAX;
        if joints.len() < 2
            || joints
                .iter()
                .any(|j| !matches!(j.kind, JointKind::Ball | JointKind::Hinge))
        {
            return false;
        }
        self.first.clear();
        self.first.resize(bodies, NONE);
        for (k, joint) in joints.iter().enumerate() {
            if k > 0 && joint.a == joints[k - 1].a && joint.b == joints[k - 1].b {
                return false;
            }
            for body in std::iter::once(joint.a).chain(joint.b) {
                if self.first[body] == NONE {
                    self.first[body] = k;
                }
                if self.first[body] + 1 < k {
                    return false;
                }
            }
        }
        true
    }

    /// K λ = `rhs` for the built rows, λ over `rhs`: a hinge tree rooted in the world through
    /// its joint coordinates (`reduced`: its factor kept here), anything else by
    /// `solve::chain_multipliers` (the factor kept in `solver` for `solve::again`, as the
    /// rows' would be). Only one of the two holds a factor of these rows afterwards.
    #[inline(always)]
    pub fn solve(&mut self, inverse: &[Inverse], rhs: &mut [f64], solver: &mut Solver) {
        if self.hinges && self.reduced.factor(&self.links, inverse) {
            if solver.holds(self.rows()) {
                *solver = Solver::default();
            }
            self.reduced.solve(rhs);
            return;
        }
        chain_multipliers(&self.links, inverse, rhs, solver);
    }

    /// The joints' loads on a hinge tree rooted in the world, through its joint coordinates
    /// (`reduced::Reduced::accelerate`: the numbers of [`Chain::rhs`], [`Chain::solve`] and
    /// [`Chain::apply`] to round-off, the factor kept here): each of its bodies' `loads`
    /// (F, τ of the applied loads in, the totals out) and each joint's reaction on A added to
    /// `reactions`; `gyroscopic(b)` is ω × L of body b. False (nothing done) for any other
    /// chain.
    #[inline(always)]
    pub fn react(
        &mut self,
        inverse: &[Inverse],
        solver: &mut Solver,
        gyroscopic: impl Fn(usize) -> Vector3<f64>,
        loads: &mut [Loads],
        reactions: &mut [Loads],
    ) -> bool {
        if !self.hinges || !self.reduced.factor(&self.links, inverse) {
            return false;
        }
        if solver.holds(self.rows()) {
            *solver = Solver::default();
        }
        let Chain { links, reduced, .. } = self;
        reduced.accelerate(links, gyroscopic, loads, reactions);
        true
    }

    /// This chain's held reduced factor with `solver`'s banded one, as a [`Nearby`] factor.
    pub fn nearby<'a>(&'a mut self, solver: &'a mut Solver) -> Nearby<'a> {
        Nearby {
            solver,
            reduced: &mut self.reduced,
        }
    }

    /// How many rows the built joints have.
    pub fn rows(&self) -> usize {
        self.links.iter().map(Link::rows).sum()
    }

    /// `rhs` = −C of every row; returns max |C|.
    #[inline(always)]
    pub fn errors(&self, rhs: &mut Vec<f64>) -> f64 {
        rhs.clear();
        let mut worst = 0.0_f64;
        for link in &self.links {
            let s = &link.separation;
            let [c0, c1] = link.c;
            let all = [-s.x, -s.y, -s.z, -c0, -c1];
            let c = &all[..link.rows()];
            worst = c.iter().fold(worst, |w, c| w.max(c.abs()));
            rhs.extend_from_slice(c);
        }
        worst
    }

    /// `rhs` = −J u of every row at the poses' velocities, a joint at a time (as [`Chain::rhs`]):
    /// `v_A + ω_A × r_A − v_B − ω_B × r_B` for the point rows, `g·(ω_A − ω_B)` for a hinge's.
    #[inline(always)]
    pub fn rates(&self, poses: &[Pose], rhs: &mut Vec<f64>) {
        rhs.clear();
        for link in &self.links {
            let a = &poses[link.a];
            let mut point = a.v + a.w.cross(&link.ra);
            let mut turn = a.w;
            if let Some(b) = link.b {
                let b = &poses[b];
                point -= b.v + b.w.cross(&link.rb);
                turn -= b.w;
            }
            let [g0, g1] = &link.g;
            let all = [-point.x, -point.y, -point.z, -g0.dot(&turn), -g1.dot(&turn)];
            rhs.extend_from_slice(&all[..link.rows()]);
        }
    }

    /// `rhs` = −(J a_free + J̇u) of every row, `free` each body's free accelerations (v̇, ω̇),
    /// a joint's three point rows at once: (r × e_k)·ω̇ = e_k·(ω̇ × r), so
    /// `J_point a = v̇_A + ω̇_A × r_A − v̇_B − ω̇_B × r_B`, and a hinge row `g·(ω̇_A − ω̇_B)`.
    #[inline(always)]
    pub fn rhs(&self, free: &[(Vector3<f64>, Vector3<f64>)], rhs: &mut Vec<f64>) {
        rhs.clear();
        for link in &self.links {
            let (la, aa) = &free[link.a];
            let mut point = la + aa.cross(&link.ra);
            let mut turn = *aa;
            if let Some(b) = link.b {
                let (lb, ab) = &free[b];
                point -= lb + ab.cross(&link.rb);
                turn -= ab;
            }
            point += link.centripetal;
            rhs.extend([-point.x, -point.y, -point.z]);
            for i in 0..link.angular {
                rhs.push(-(link.g[i].dot(&turn) + link.bias[i]));
            }
        }
    }

    /// Each joint's `J_kᵀ λ_k` added to its bodies' loads and to its reaction on A: the point
    /// rows' multipliers are a force f at the anchor, `(f, r_A × f + Σ g_i λ_i)` on A and the
    /// opposite `(−f, −r_B × f − Σ g_i λ_i)` on B.
    #[inline(always)]
    pub fn apply(&self, lambda: &[f64], loads: &mut [Loads], reactions: &mut [Loads]) {
        let mut p = 0;
        for (link, reaction) in self.links.iter().zip(reactions) {
            let f = Vector3::new(lambda[p], lambda[p + 1], lambda[p + 2]);
            let mut turn = Vector3::zeros();
            for i in 0..link.angular {
                turn += link.g[i] * lambda[p + 3 + i];
            }
            p += link.rows();
            let t = link.ra.cross(&f) + turn;
            loads[link.a].force += f;
            loads[link.a].torque += t;
            reaction.force += f;
            reaction.torque += t;
            if let Some(b) = link.b {
                loads[b].force -= f;
                loads[b].torque -= link.rb.cross(&f) + turn;
            }
        }
    }
}
