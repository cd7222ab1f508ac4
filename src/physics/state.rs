//! The state of a rigid body, in momentum form.
//!
//! ```text
//! X = (x, R or q, P, L)
//! x  barycenter position (world), m                          (_Position)
//! R  rotation matrix body → world   (euler-seed only)        (_Rotation)
//! q  unit quaternion body → world   (every other integrator)
//! P  linear momentum  = M v, kg·m/s                          (_QuantiteMouvement)
//! L  angular momentum = I_world ω, about the barycenter      (_MomentCinetique)
//! ```
//!
//! Velocities are not state: `v = P / M` and `ω = I⁻¹_world L` are derived every step, so a
//! torque-free body keeps L exactly, whatever the integrator does to the orientation.

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// Orientation, stored the way the integrator needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// A 3×3 matrix integrated directly (`euler-seed`); nothing keeps it a rotation.
    Matrix(Matrix3<f64>),
    /// A unit quaternion (w, x, y, z), Hamilton convention, body → world.
    Quaternion(UnitQuaternion<f64>),
}

impl Orientation {
    /// The orientation as a 3×3 matrix R (body → world).
    #[inline]
    pub fn matrix(&self) -> Matrix3<f64> {
        match self {
            Orientation::Matrix(m) => *m,
            Orientation::Quaternion(q) => q.to_rotation_matrix().into_inner(),
        }
    }

    /// The nearest rotation as a unit quaternion (a drifted matrix is projected back).
    #[inline]
    pub fn quaternion(&self) -> UnitQuaternion<f64> {
        match self {
            Orientation::Matrix(m) => nearest_rotation(m),
            Orientation::Quaternion(q) => *q,
        }
    }

    /// ‖RᵀR − 𝟙‖ (Frobenius): how far the orientation is from a rotation.
    pub fn orthonormality_error(&self) -> f64 {
        let r = self.matrix();
        (r.transpose() * r - Matrix3::identity()).norm()
    }

    /// The same orientation in the other representation.
    pub fn as_matrix(&self) -> Orientation {
        Orientation::Matrix(self.matrix())
    }

    /// The same orientation as a quaternion (the nearest rotation if the matrix drifted).
    pub fn as_quaternion(&self) -> Orientation {
        Orientation::Quaternion(self.quaternion())
    }
}

/// The rotation nearest to a matrix that has drifted away from one.
fn nearest_rotation(m: &Matrix3<f64>) -> UnitQuaternion<f64> {
    if !m.iter().all(|c| c.is_finite()) {
        return UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(f64::NAN, 0.0, 0.0, 0.0));
    }
    let rotation = Rotation3::from_matrix_eps(m, 1e-12, 100, Rotation3::identity());
    UnitQuaternion::from_rotation_matrix(&rotation)
}

/// The state X = (x, R|q, P, L).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Barycenter position x, m.
    pub position: Vector3<f64>,
    /// Orientation R or q, body → world.
    pub orientation: Orientation,
    /// Linear momentum P, kg·m/s.
    pub linear_momentum: Vector3<f64>,
    /// Angular momentum L about the barycenter, world frame, kg·m²/s.
    pub angular_momentum: Vector3<f64>,
}

impl State {
    /// At rest at the origin, identity orientation as a quaternion.
    pub fn at_rest() -> State {
        State {
            position: Vector3::zeros(),
            orientation: Orientation::Quaternion(UnitQuaternion::identity()),
            linear_momentum: Vector3::zeros(),
            angular_momentum: Vector3::zeros(),
        }
    }

    /// Every number in the state is finite.
    pub fn is_finite(&self) -> bool {
        let finite = |v: &Vector3<f64>| v.iter().all(|c| c.is_finite());
        finite(&self.position)
            && finite(&self.linear_momentum)
            && finite(&self.angular_momentum)
            && self.orientation.matrix().iter().all(|c| c.is_finite())
    }
}
