//! A sheet: the particles (x, v, m, pinned) and springs built from a [`ClothSpec`].
//!
//! ```text
//! particle (i, j) ↦ index j·nx + i
//! x(i, j) = position + (−size.x/2 + i·size.x/(nx − 1), 0, −size.z/2 + j·size.z/(nz − 1))
//!           (offset 0 along an axis of count 1: a rope)
//! m_i = mass/(nx·nz);   v_i = velocity (free) or 0 (pinned)
//! springs, ℓ₀ = the initial distance:
//!   stretch (i, j)–(i+1, j), (i, j)–(i, j+1)            k = stretch
//!   shear   (i, j)–(i+1, j+1), (i+1, j)–(i, j+1)        k = shear   (if > 0)
//!   bend    (i, j)–(i+2, j), (i, j)–(i, j+2)            k = bend    (if > 0)
//!   every spring has damping c = damping
//! ```
//!
//! Pinned particles keep their place and zero velocity for ever: the integrators skip them,
//! their inverse mass is 0 and an impulse on them does nothing.

use super::conjugate_gradient::Workspace;
use super::energy::Losses;
use super::integrator::ClothIntegrator;
use super::loads::ClothLoads;
use super::spec::{ClothSpec, ClothSpecError};
use super::spring::{Spring, SpringKind};
use super::{implicit_euler, symplectic_euler};
use nalgebra::Vector3;

/// Settings of the implicit step's conjugate-gradient solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Stop when the preconditioned residual norm falls below this fraction of the right-hand
    /// side's: √(rᵀP⁻¹r) ≤ tolerance·√(bᵀP⁻¹b). Default 1e-3: far below the step's own
    /// error (`implicit_euler`, where the choice is measured).
    pub tolerance: f64,
    /// At most this many iterations per step.
    pub max_iterations: usize,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            tolerance: 1e-3,
            max_iterations: 500,
        }
    }
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Conjugate-gradient iterations (0 for an explicit step).
    pub iterations: usize,
    /// Final relative residual of the solve (0 for an explicit step).
    pub residual: f64,
    /// Energy the damping and the drag took during this step, J (≥ 0 when they dissipate).
    pub dissipated: Losses,
}

/// Buffers reused from step to step (not part of the state).
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    pub force: Vec<Vector3<f64>>,
    /// Per particle: the springs' damping force the step used, Σ ±c ((v_j − v_i)·d̂₀) d̂₀ (v at
    /// the start for the explicit step, at the end for the implicit one); empty when no spring
    /// is damped.
    pub damping_force: Vec<Vector3<f64>>,
    /// The velocities at the start of the step.
    pub start_velocity: Vec<Vector3<f64>>,
    /// The velocities the step's drag used (only when drag is declared).
    pub drag_velocity: Vec<Vector3<f64>>,
    pub start: Vec<Vector3<f64>>,
    pub solver: Workspace,
    /// Per particle: how the last tied step ended (the next step's first guess of its
    /// contact set, [`Held`]).
    pub held: Vec<Held>,
    /// What the last step's linear solves took.
    pub solves: SolveCounts,
}

/// What the last step's linear solves took (0 for an explicit step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SolveCounts {
    /// Solves: 1, or one per contact set a tied step tried.
    pub solves: usize,
    /// Conjugate-gradient iterations over those solves.
    pub iterations: usize,
}

/// How a particle ended the last tied step (`cloth_coupling::tied_step`), the next step's
/// first guess of its contact set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Held {
    /// No contact candidate.
    #[default]
    Free,
    /// A candidate, not held.
    Near,
    /// Held by a contact tie.
    Touching,
}

/// A mass–spring sheet.
#[derive(Debug, Clone)]
pub struct Cloth {
    pub name: String,
    /// Particles along x and z.
    pub count: [usize; 2],
    /// Positions x_i, m (index j·nx + i).
    pub positions: Vec<Vector3<f64>>,
    /// Velocities v_i, m/s (0 for pinned particles).
    pub velocities: Vec<Vector3<f64>>,
    /// Particle masses m_i, kg.
    pub masses: Vec<f64>,
    /// Pinned particles never move.
    pub pinned: Vec<bool>,
    /// Particles held to bodies: (particle index, body index), from the spec's `attach`.
    pub attached: Vec<(usize, usize)>,
    pub springs: Vec<Spring>,
    pub integrator: ClothIntegrator,
    pub solver: SolverSettings,
    /// Energy taken by damping, drag and contacts since the start, J.
    pub losses: Losses,
    /// Σ m_i, kg.
    pub total_mass: f64,
    pub(super) scratch: Scratch,
}

impl Cloth {
    /// The bytes it holds on the heap: particles, springs, and the buffers reused from step
    /// to step (what a copy of it costs; a history of the world counts them).
    pub fn heap_bytes(&self) -> usize {
        use super::conjugate_gradient::bytes_of;
        let sc = &self.scratch;
        self.name.capacity()
            + bytes_of(&self.positions, self.positions.capacity())
            + bytes_of(&self.velocities, self.velocities.capacity())
            + bytes_of(&self.masses, self.masses.capacity())
            + bytes_of(&self.pinned, self.pinned.capacity())
            + bytes_of(&self.attached, self.attached.capacity())
            + bytes_of(&self.springs, self.springs.capacity())
            + [
                &sc.force,
                &sc.damping_force,
                &sc.start_velocity,
                &sc.drag_velocity,
                &sc.start,
            ]
            .iter()
            .map(|v| bytes_of(v, v.capacity()))
            .sum::<usize>()
            + bytes_of(&sc.held, sc.held.capacity())
            + sc.solver.heap_bytes()
    }

    /// Builds the sheet of a spec (module doc), after validating it.
    pub fn new(spec: &ClothSpec) -> Result<Cloth, ClothSpecError> {
        spec.validate()?;
        let [nx, nz] = spec.count;
        let n = nx * nz;
        let m = spec.mass / n as f64;
        let mut positions = Vec::with_capacity(n);
        let mut pinned = Vec::with_capacity(n);
        // Along an axis with one row (a rope), the row is on the centre line. The offset is
        // side·(2k − (n − 1))/(2(n − 1)), an integer times side divided by an integer, so that
        // particles k and n − 1 − k sit at exactly opposite offsets: the sheet is
        // mirror-symmetric to the last bit (what `conjugate_gradient`'s summation order keeps).
        let offset = |k: usize, n: usize, side: f64| {
            if n > 1 {
                (2.0 * k as f64 - (n - 1) as f64) * side / (2 * (n - 1)) as f64
            } else {
                0.0
            }
        };
        for j in 0..nz {
            for i in 0..nx {
                positions.push(
                    spec.position
                        + Vector3::new(
                            offset(i, nx, spec.size[0]),
                            0.0,
                            offset(j, nz, spec.size[1]),
                        ),
                );
                pinned.push(spec.pinned.holds(i, j, spec.count));
            }
        }
        let velocities = pinned
            .iter()
            .map(|&p| if p { Vector3::zeros() } else { spec.velocity })
            .collect();
        let index = |i: usize, j: usize| j * nx + i;
        let mut springs = Vec::new();
        let mut add = |a: usize, b: usize, stiffness: f64, kind: SpringKind| {
            springs.push(Spring {
                i: a,
                j: b,
                rest_length: (positions[b] - positions[a]).norm(),
                stiffness,
                damping: spec.damping,
                kind,
            })
        };
        for j in 0..nz {
            for i in 0..nx {
                if i + 1 < nx {
                    add(
                        index(i, j),
                        index(i + 1, j),
                        spec.stretch,
                        SpringKind::Stretch,
                    );
                }
                if j + 1 < nz {
                    add(
                        index(i, j),
                        index(i, j + 1),
                        spec.stretch,
                        SpringKind::Stretch,
                    );
                }
            }
        }
        if spec.shear > 0.0 {
            // A rope (nx or nz = 1) has no cells: no shear springs.
            for j in 0..nz.saturating_sub(1) {
                for i in 0..nx - 1 {
                    add(
                        index(i, j),
                        index(i + 1, j + 1),
                        spec.shear,
                        SpringKind::Shear,
                    );
                    add(
                        index(i + 1, j),
                        index(i, j + 1),
                        spec.shear,
                        SpringKind::Shear,
                    );
                }
            }
        }
        if spec.bend > 0.0 {
            for j in 0..nz {
                for i in 0..nx {
                    if i + 2 < nx {
                        add(index(i, j), index(i + 2, j), spec.bend, SpringKind::Bend);
                    }
                    if j + 2 < nz {
                        add(index(i, j), index(i, j + 2), spec.bend, SpringKind::Bend);
                    }
                }
            }
        }
        Ok(Cloth {
            name: spec.name.clone(),
            count: spec.count,
            positions,
            velocities,
            masses: vec![m; n],
            pinned,
            attached: spec
                .attach
                .iter()
                .map(|a| (a.particle[1] * nx + a.particle[0], a.body))
                .collect(),
            springs,
            integrator: spec.integrator,
            solver: SolverSettings::default(),
            losses: Losses::default(),
            total_mass: spec.mass,
            scratch: Scratch::default(),
        })
    }

    /// Number of particles.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the sheet has no particles (never, for a built sheet).
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The index of particle (i, j).
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.count[0] + i
    }

    /// The (i, j) of a particle index.
    pub fn grid(&self, index: usize) -> (usize, usize) {
        (index % self.count[0], index / self.count[0])
    }

    /// 1/m_i, 1/kg: 0 for a pinned particle (it does not move, whatever the impulse).
    #[inline]
    pub fn inv_mass(&self, i: usize) -> f64 {
        if self.pinned[i] {
            0.0
        } else {
            1.0 / self.masses[i]
        }
    }

    /// v_i, m/s.
    #[inline]
    pub fn particle_velocity(&self, i: usize) -> Vector3<f64> {
        self.velocities[i]
    }

    /// Applies impulse J (N·s) to particle i: v_i ← v_i + J/m_i (nothing if pinned). Returns
    /// the particle's kinetic-energy change, J (for the caller's energy bookkeeping).
    #[inline]
    pub fn apply_impulse(&mut self, i: usize, impulse: &Vector3<f64>) -> f64 {
        let w = self.inv_mass(i);
        if w == 0.0 {
            return 0.0;
        }
        let before = self.velocities[i].norm_squared();
        self.velocities[i] += impulse * w;
        0.5 * self.masses[i] * (self.velocities[i].norm_squared() - before)
    }

    /// Moves particle i by `offset` (a contact's push-out; nothing if pinned).
    #[inline]
    pub fn displace(&mut self, i: usize, offset: &Vector3<f64>) {
        if !self.pinned[i] {
            self.positions[i] += offset;
        }
    }

    /// Linear momentum Σ m_i v_i, kg·m/s.
    pub fn linear_momentum(&self) -> Vector3<f64> {
        self.masses
            .iter()
            .zip(&self.velocities)
            .map(|(&m, v)| v * m)
            .sum()
    }

    /// Angular momentum about the origin Σ x_i × m_i v_i, kg·m²/s.
    pub fn angular_momentum(&self) -> Vector3<f64> {
        self.masses
            .iter()
            .zip(self.positions.iter().zip(&self.velocities))
            .map(|(&m, (x, v))| x.cross(&(v * m)))
            .sum()
    }

    /// Largest spring stretch (ℓ − ℓ₀)/ℓ₀ over the springs (negative: all compressed).
    pub fn max_stretch(&self) -> f64 {
        self.springs
            .iter()
            .map(|s| (self.positions[s.j] - self.positions[s.i]).norm() / s.rest_length - 1.0)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Largest particle speed, m/s.
    pub fn max_speed(&self) -> f64 {
        self.velocities.iter().map(|v| v.norm()).fold(0.0, f64::max)
    }

    /// One whole step of length `dt` with the sheet's integrator under the declared loads,
    /// without contacts: [`Cloth::velocity_step`] then [`Cloth::advance_positions`].
    pub fn step(&mut self, loads: &ClothLoads, dt: f64) -> StepReport {
        let mut report = self.velocity_step(loads, dt);
        report.dissipated = self.advance_positions(loads, dt);
        report
    }

    /// The velocity half of a step: v₀ → v₁ by the sheet's integrator (positions unchanged).
    /// Contact impulses on velocities (obstacles, bodies) go between this and
    /// [`Cloth::advance_positions`].
    pub fn velocity_step(&mut self, loads: &ClothLoads, dt: f64) -> StepReport {
        self.scratch.start_velocity.clone_from(&self.velocities);
        let report = match self.integrator {
            ClothIntegrator::SymplecticEuler => symplectic_euler::velocities(self, loads, dt),
            ClothIntegrator::ImplicitEuler => implicit_euler::velocities(self, loads, dt),
        };
        self.scratch.solves = SolveCounts {
            solves: usize::from(self.integrator == ClothIntegrator::ImplicitEuler),
            iterations: report.iterations,
        };
        report
    }

    /// What the last step's linear solves took.
    pub fn solve_counts(&self) -> SolveCounts {
        self.scratch.solves
    }

    /// Records what a tied step's solves took ([`Cloth::solve_counts`]).
    pub fn record_solves(&mut self, counts: SolveCounts) {
        self.scratch.solves = counts;
    }

    /// The implicit step with ties (`ties`), in three calls: this one records the start
    /// velocities and assembles the step's matrix and right-hand side (`implicit_euler`); then
    /// [`Cloth::solve_tied`] (as often as the caller's contact set changes); then
    /// [`Cloth::finish_tied_step`]. Only for `implicit-euler` sheets.
    pub fn begin_tied_step(&mut self, loads: &ClothLoads, dt: f64) {
        debug_assert_eq!(self.integrator, ClothIntegrator::ImplicitEuler);
        self.scratch.start_velocity.clone_from(&self.velocities);
        implicit_euler::assemble(self, loads, dt);
    }

    /// Solves the step assembled by [`Cloth::begin_tied_step`] with these ties: v = v₀ + Δv,
    /// each tie's impulse and each body's correction filled in; the bodies' corrections kept
    /// on `joints`' rows (`ties`, "Joints on the bodies").
    pub fn solve_tied(
        &mut self,
        ties: &mut [super::ties::Tie],
        bodies: &mut [super::ties::TiedBody],
        joints: &super::ties::BodyJoints,
    ) -> StepReport {
        implicit_euler::solve_tied(self, ties, bodies, joints)
    }

    /// Ends a tied step's velocity half (the damping and drag the step used, for the losses).
    pub fn finish_tied_step(&mut self, loads: &ClothLoads) {
        implicit_euler::finish(self, loads);
    }

    /// The position half: x ← x + h v for the free particles. Returns what the step's damping
    /// and drag took, and adds it to [`Cloth::losses`]: the work of the forces the velocity
    /// half used along the displacement, negated,
    ///
    /// ```text
    /// W_damping = −Σ_i f_damping,i·Δx_i,   f_damping,i = Σ_springs ±c_used d̂₀
    /// W_drag    = Σ_i k_drag,i v_used,i·Δx_i
    /// ```
    pub fn advance_positions(&mut self, loads: &ClothLoads, dt: f64) -> Losses {
        // x₁ is written into the scratch and the two swapped: the scratch keeps x₀, uncopied.
        let next = &mut self.scratch.start;
        next.clear();
        let free = self
            .positions
            .iter()
            .zip(&self.velocities)
            .zip(&self.pinned);
        next.extend(free.map(|((x, v), &pinned)| if pinned { *x } else { x + v * dt }));
        std::mem::swap(&mut self.positions, &mut self.scratch.start);
        let mut dissipated = Losses::default();
        let start = &self.scratch.start;
        if self.scratch.damping_force.len() == self.len() {
            for ((f, x1), x0) in (self.scratch.damping_force.iter())
                .zip(&self.positions)
                .zip(&start[..self.len()])
            {
                dissipated.damping -= f.dot(&(x1 - x0));
            }
        }
        if loads.drag.is_some() && self.scratch.drag_velocity.len() == self.len() {
            for (i, (v, x0)) in self.scratch.drag_velocity.iter().zip(start).enumerate() {
                let k = loads.particle_drag(self.masses[i], self.total_mass);
                dissipated.drag += k * v.dot(&(self.positions[i] - x0));
            }
        }
        self.losses.damping += dissipated.damping;
        self.losses.drag += dissipated.drag;
        dissipated
    }

    /// Velocity of particle `i` at the start of the current step (after
    /// [`Cloth::velocity_step`]); its current velocity before any step.
    pub fn start_velocity(&self, i: usize) -> Vector3<f64> {
        self.scratch
            .start_velocity
            .get(i)
            .copied()
            .unwrap_or_else(|| self.velocities[i])
    }

    /// Per particle, how the last tied step ended (empty before the first).
    pub fn held(&self) -> &[Held] {
        &self.scratch.held
    }

    /// Records the candidates and the contact set a tied step ended with ([`Cloth::held`]).
    pub fn set_held(
        &mut self,
        candidates: impl Iterator<Item = usize>,
        held: impl Iterator<Item = usize>,
    ) {
        let n = self.len();
        self.scratch.held.clear();
        self.scratch.held.resize(n, Held::Free);
        for i in candidates {
            self.scratch.held[i] = Held::Near;
        }
        for i in held {
            self.scratch.held[i] = Held::Touching;
        }
    }

    /// Positions at the start of the last step (for swept contact tests); the current
    /// positions before any step.
    pub fn start_positions(&self) -> &[Vector3<f64>] {
        if self.scratch.start.len() == self.positions.len() {
            &self.scratch.start
        } else {
            &self.positions
        }
    }
}
