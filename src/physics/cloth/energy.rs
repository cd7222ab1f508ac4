//! A sheet's energy, and the energy its dissipative forces and contacts took.
//!
//! ```text
//! kinetic        T = Σ_i ½ m_i |v_i|²
//! spring         U = Σ_springs ½ k (|x_j − x_i| − ℓ₀)²
//! gravitational  V = −Σ_i m_i g·x_i                (only when gravity is declared)
//! ```
//!
//! Damping, drag and contacts remove energy: each step measures what they took (the work of
//! the forces or impulses it applied, see `symplectic_euler`, `implicit_euler`, `contact`) and
//! [`Losses`] accumulates it, so that `T + U + V + losses` stays at its initial value up to the
//! integrator's own error — losses shown as losses, not as drift.

use super::loads::ClothLoads;
use super::sheet::Cloth;

/// Energies of a sheet, J.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClothEnergy {
    pub kinetic: f64,
    pub spring: f64,
    pub gravitational: f64,
}

impl ClothEnergy {
    /// T + U + V, J.
    pub fn total(&self) -> f64 {
        self.kinetic + self.spring + self.gravitational
    }
}

/// Energy taken by dissipative forces and contacts, J (≥ 0 when they dissipate).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Losses {
    /// By the springs' damping.
    pub damping: f64,
    /// By linear drag.
    pub drag: f64,
    /// By contacts with obstacles (and, when the world adds it, with bodies).
    pub contact: f64,
}

impl Losses {
    /// Everything taken, J.
    pub fn total(&self) -> f64 {
        self.damping + self.drag + self.contact
    }
}

impl Cloth {
    /// T, U and V now (V only when `loads` declares gravity).
    pub fn energy(&self, loads: &ClothLoads) -> ClothEnergy {
        ClothEnergy {
            kinetic: self.kinetic_energy(),
            spring: self.spring_energy(),
            gravitational: loads.gravity.map_or(0.0, |g| {
                -self
                    .masses
                    .iter()
                    .zip(&self.positions)
                    .map(|(&m, x)| m * g.dot(x))
                    .sum::<f64>()
            }),
        }
    }

    /// T = Σ ½ m |v|², J.
    pub fn kinetic_energy(&self) -> f64 {
        self.masses
            .iter()
            .zip(&self.velocities)
            .map(|(&m, v)| 0.5 * m * v.norm_squared())
            .sum()
    }

    /// U = Σ ½ k (ℓ − ℓ₀)², J.
    pub fn spring_energy(&self) -> f64 {
        self.springs.iter().map(|s| s.energy(&self.positions)).sum()
    }
}
