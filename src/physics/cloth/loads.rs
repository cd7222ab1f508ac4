//! The forces on the particles: the springs, and the scene's declared effects (gravity and
//! linear drag) — nothing else.
//!
//! ```text
//! f_i = Σ_springs ±[k (ℓ − ℓ₀) d̂ + c ((v_j − v_i)·d̂) d̂]  +  m_i g  −  k_drag (m_i/M) v_i
//! ```
//!
//! **Drag means what it means for a body.** `drag.linear` = k_drag is a force coefficient in
//! kg/s on the *whole object*: a body feels F = −k_drag v (`effects`). A sheet shares it among
//! its particles by mass, −k_drag (m_i/M) v_i, so a sheet moving as a whole at v feels the same
//! total force −k_drag v as a body, and its velocity decays at the same rate k_drag/M as a body
//! of the same mass (with equal particle masses, m_i/M = 1/N). `drag.angular` has no meaning
//! for points and is not used by a sheet.
//!
//! Pinned particles feel forces but never move: their rows are ignored by the integrators.

use super::sheet::Cloth;
use crate::physics::effects::{Effect, Effects};
use nalgebra::Vector3;

/// The declared effects that act on particles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClothLoads {
    /// Uniform gravity g, m/s², if declared.
    pub gravity: Option<Vector3<f64>>,
    /// Linear drag k_drag on the whole sheet, kg/s, if declared (and > 0).
    pub drag: Option<f64>,
}

impl ClothLoads {
    /// Gravity and linear drag as the scene declares them for bodies.
    pub fn from_effects(effects: &Effects) -> ClothLoads {
        let mut loads = ClothLoads::default();
        for effect in effects.list() {
            match *effect {
                Effect::Gravity(g) => loads.gravity = Some(g),
                Effect::Drag { linear, .. } => {
                    loads.drag = (linear > 0.0).then_some(linear);
                }
            }
        }
        loads
    }

    /// The drag coefficient of one particle of mass m in a sheet of total mass M,
    /// k_drag·m/M, kg/s (0 without drag).
    #[inline]
    pub fn particle_drag(&self, mass: f64, total_mass: f64) -> f64 {
        self.drag.map_or(0.0, |k| k * mass / total_mass)
    }
}

impl Cloth {
    /// f at the current (x, v) into the scratch force buffer, and the springs' damping force
    /// on each particle into the scratch damping forces (when some spring is damped; for the
    /// losses). One pass over the springs: one square root and one division each.
    pub(super) fn compute_forces(&mut self, loads: &ClothLoads) {
        let x = &self.positions;
        let v = &self.velocities;
        let n = x.len();
        let force = &mut self.scratch.force;
        force.clear();
        match loads.gravity {
            Some(g) => force.extend(self.masses.iter().map(|&m| g * m)),
            None => force.resize(n, Vector3::zeros()),
        }
        if loads.drag.is_some() {
            for ((f, &m), v) in force.iter_mut().zip(&self.masses).zip(v) {
                *f -= v * loads.particle_drag(m, self.total_mass);
            }
        }
        let damped = self.springs.iter().any(|s| s.damping > 0.0);
        let damping_force = &mut self.scratch.damping_force;
        damping_force.clear();
        // Slices of one length: the loops below index nothing else.
        let (x, v, force) = (&x[..n], &v[..n], &mut force[..n]);
        if damped {
            damping_force.resize(n, Vector3::zeros());
            let damping_force = &mut damping_force[..n];
            for s in &self.springs {
                let d = x[s.j] - x[s.i];
                let length = d.norm();
                let direction = if length > 0.0 { d * (1.0 / length) } else { d };
                let damping = s.damping * (v[s.j] - v[s.i]).dot(&direction);
                let f = direction * (s.stiffness * (length - s.rest_length) + damping);
                force[s.i] += f;
                force[s.j] -= f;
                let f = direction * damping;
                damping_force[s.i] += f;
                damping_force[s.j] -= f;
            }
        } else {
            for s in &self.springs {
                let d = x[s.j] - x[s.i];
                let length = d.norm();
                let direction = if length > 0.0 { d * (1.0 / length) } else { d };
                let f = direction * (s.stiffness * (length - s.rest_length));
                force[s.i] += f;
                force[s.j] -= f;
            }
        }
    }
}
