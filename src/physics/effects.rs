//! The *forces* phase's inputs: the effects a scene declares, and nothing else.
//!
//! ```text
//! gravity:  F = M g,              τ = 0
//! drag:     F = −k v,             τ = −k_a ω          (the report's `visco`)
//! ```
//!
//! Gravity makes no torque about the barycenter: the torque of the weights of the points is
//! `Σ rᵢ × mᵢ g = (Σ mᵢ rᵢ) × g` and `Σ mᵢ rᵢ = 0` by definition of the barycenter. The original
//! loop summed `rᵢ × M g` over vertices instead, which is the same zero only when all points
//! weigh the same (see `integrators::euler_seed`).
//!
//! An undeclared effect is not in the list at all, so it is never evaluated.

use super::body::Body;
use super::derive::Kinematics;
use nalgebra::Vector3;

/// One declared effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Effect {
    /// Uniform gravity g, m/s² (force M g at the barycenter).
    Gravity(Vector3<f64>),
    /// Viscous drag: force −`linear`·v (kg/s), torque −`angular`·ω (kg·m²/s).
    Drag { linear: f64, angular: f64 },
}

/// Force and torque about the barycenter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Loads {
    /// Total force F, N.
    pub force: Vector3<f64>,
    /// Total torque τ about the barycenter, N·m.
    pub torque: Vector3<f64>,
}

/// The effects a scene declares.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Effects {
    list: Vec<Effect>,
}

impl Effects {
    /// The given effects, evaluated in this order.
    pub fn new(list: Vec<Effect>) -> Effects {
        Effects { list }
    }

    /// The declared effects.
    pub fn list(&self) -> &[Effect] {
        &self.list
    }

    /// Gravity, if declared.
    #[inline]
    pub fn gravity(&self) -> Option<Vector3<f64>> {
        self.list.iter().find_map(|e| match e {
            Effect::Gravity(g) => Some(*g),
            _ => None,
        })
    }

    /// Whether some declared effect depends on v or ω (drag): then F and τ change within a step
    /// even when x and R do not.
    pub fn depends_on_velocity(&self) -> bool {
        self.list.iter().any(|e| matches!(e, Effect::Drag { .. }))
    }

    /// Short names of the declared effects, for status lines.
    pub fn names(&self) -> Vec<&'static str> {
        self.list
            .iter()
            .map(|e| match e {
                Effect::Gravity(_) => "gravity",
                Effect::Drag { .. } => "drag",
            })
            .collect()
    }

    /// F and τ at the given velocities: the sum over the declared effects only.
    #[inline]
    pub fn loads(&self, body: &Body, kinematics: &Kinematics) -> Loads {
        self.loads_at(body, &kinematics.velocity, &kinematics.angular_velocity)
    }

    /// F and τ at velocity v and angular velocity ω (world frame).
    #[inline]
    pub fn loads_at(
        &self,
        body: &Body,
        velocity: &Vector3<f64>,
        angular_velocity: &Vector3<f64>,
    ) -> Loads {
        let mut loads = Loads::default();
        for effect in &self.list {
            match *effect {
                Effect::Gravity(g) => loads.force += g * body.mass,
                Effect::Drag { linear, angular } => {
                    loads.force -= velocity * linear;
                    loads.torque -= angular_velocity * angular;
                }
            }
        }
        loads
    }

    /// Potential energy of the declared conservative effects: `−M g·x` for gravity, J.
    pub fn potential_energy(&self, body: &Body, position: &Vector3<f64>) -> f64 {
        self.gravity().map_or(0.0, |g| -body.mass * g.dot(position))
    }
}
