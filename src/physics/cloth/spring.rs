//! One damped Hooke spring between particles i and j, and its Jacobians.
//!
//! ```text
//! d = x_j − x_i,   ℓ = |d|,   d̂ = d/ℓ
//! f_i = k (ℓ − ℓ₀) d̂ + c ((v_j − v_i)·d̂) d̂,      f_j = −f_i        (design.md)
//! energy  U = ½ k (ℓ − ℓ₀)²
//!
//! ∂f_i/∂x_j = k J,   J = d̂d̂ᵀ + max(0, 1 − ℓ₀/ℓ)(I − d̂d̂ᵀ)     ∂f_i/∂x_i = −k J
//! ∂f_i/∂v_j = c d̂d̂ᵀ                                             ∂f_i/∂v_i = −c d̂d̂ᵀ
//! ```
//!
//! The exact stiffness has `1 − ℓ₀/ℓ` in place of its positive part: under compression (ℓ < ℓ₀)
//! it is negative and the Jacobian indefinite (a compressed spring buckles sideways); clamping
//! it at 0 keeps −∂f/∂x positive semi-definite, so the implicit step's matrix stays positive
//! definite (Baraff & Witkin 1998, §5; Choi & Ko 2002). The damping force's derivative with
//! respect to x (through d̂) is left out of the Jacobian, as Baraff & Witkin do: it is not
//! symmetric, and small next to c d̂d̂ᵀ/h.
//!
//! A spring of zero length has no direction: its force and Jacobians are taken as zero.

use nalgebra::{Matrix3, Vector3};

/// The three kinds of springs of a sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpringKind {
    /// Between neighbours along x or z.
    Stretch,
    /// Along both diagonals of a cell.
    Shear,
    /// Between second neighbours along x or z.
    Bend,
}

/// A spring between particles `i` and `j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    pub i: usize,
    pub j: usize,
    /// Rest length ℓ₀, m: the initial distance.
    pub rest_length: f64,
    /// Stiffness k, N/m.
    pub stiffness: f64,
    /// Damping c along the spring, N·s/m.
    pub damping: f64,
    pub kind: SpringKind,
}

/// The geometry of a spring at some positions: d̂ and ℓ (d̂ = 0 when ℓ = 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Axis {
    pub direction: Vector3<f64>,
    pub length: f64,
}

impl Spring {
    /// d̂ and ℓ at positions `x`.
    #[inline]
    pub fn axis(&self, x: &[Vector3<f64>]) -> Axis {
        let d = x[self.j] - x[self.i];
        let length = d.norm();
        let direction = if length > 0.0 {
            d / length
        } else {
            Vector3::zeros()
        };
        Axis { direction, length }
    }

    /// The elastic part of f_i, `k (ℓ − ℓ₀) d̂`, N.
    #[inline]
    pub fn elastic_force(&self, axis: &Axis) -> Vector3<f64> {
        axis.direction * (self.stiffness * (axis.length - self.rest_length))
    }

    /// The damping part's magnitude along d̂, `c (v_j − v_i)·d̂`, N.
    #[inline]
    pub fn damping_magnitude(&self, axis: &Axis, v: &[Vector3<f64>]) -> f64 {
        self.damping * (v[self.j] - v[self.i]).dot(&axis.direction)
    }

    /// The whole force on i, f_i (module doc); the force on j is −f_i.
    #[inline]
    pub fn force(&self, x: &[Vector3<f64>], v: &[Vector3<f64>]) -> Vector3<f64> {
        let axis = self.axis(x);
        self.elastic_force(&axis) + axis.direction * self.damping_magnitude(&axis, v)
    }

    /// Elastic energy ½ k (ℓ − ℓ₀)², J.
    #[inline]
    pub fn energy(&self, x: &[Vector3<f64>]) -> f64 {
        let stretch = (x[self.j] - x[self.i]).norm() - self.rest_length;
        0.5 * self.stiffness * stretch * stretch
    }

    /// t = max(0, 1 − ℓ₀/ℓ), the transverse factor of J = (1 − t) d̂d̂ᵀ + t I.
    #[inline]
    pub fn transverse(&self, axis: &Axis) -> f64 {
        if axis.length > 0.0 {
            (1.0 - self.rest_length / axis.length).max(0.0)
        } else {
            0.0
        }
    }

    /// k J w = k ((1 − t)(d̂·w) d̂ + t w), without forming the matrix.
    #[inline]
    pub fn stiffness_times(&self, axis: &Axis, w: &Vector3<f64>) -> Vector3<f64> {
        let t = self.transverse(axis);
        (axis.direction * ((1.0 - t) * axis.direction.dot(w)) + w * t) * self.stiffness
    }

    /// k J, the clamped stiffness block (module doc), N/m.
    #[inline]
    pub fn stiffness_block(&self, axis: &Axis) -> Matrix3<f64> {
        let dd = axis.direction * axis.direction.transpose();
        (dd + (Matrix3::identity() - dd) * self.transverse(axis)) * self.stiffness
    }

    /// c d̂d̂ᵀ, the damping block, N·s/m.
    #[inline]
    pub fn damping_block(&self, axis: &Axis) -> Matrix3<f64> {
        axis.direction * axis.direction.transpose() * self.damping
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spring() -> Spring {
        Spring {
            i: 0,
            j: 1,
            rest_length: 1.0,
            stiffness: 100.0,
            damping: 2.0,
            kind: SpringKind::Stretch,
        }
    }

    #[test]
    fn a_stretched_spring_pulls_i_towards_j_and_damps_separation() {
        let x = [Vector3::zeros(), Vector3::new(1.5, 0.0, 0.0)];
        let v = [Vector3::zeros(), Vector3::new(0.25, 3.0, 0.0)];
        // k (ℓ − ℓ₀) = 100 · 0.5 = 50 N along +x; c (v_j − v_i)·d̂ = 2 · 0.25 = 0.5 N.
        assert_eq!(spring().force(&x, &v), Vector3::new(50.5, 0.0, 0.0));
        // ½ k (ℓ − ℓ₀)² = ½ · 100 · 0.25 = 12.5 J.
        assert_eq!(spring().energy(&x), 12.5);
    }

    #[test]
    fn the_stiffness_block_is_the_derivative_of_the_force_when_stretched() {
        let s = spring();
        let x = [Vector3::new(0.1, -0.2, 0.3), Vector3::new(1.2, 0.4, -0.1)];
        let v = [Vector3::zeros(); 2];
        let block = s.stiffness_block(&s.axis(&x));
        // Central differences of f_i with respect to x_j, column by column.
        let h = 1e-6;
        for c in 0..3 {
            let mut plus = x;
            let mut minus = x;
            plus[1][c] += h;
            minus[1][c] -= h;
            let column = (s.force(&plus, &v) - s.force(&minus, &v)) / (2.0 * h);
            assert!(
                (column - block.column(c)).norm() < 1e-6,
                "column {c}: {column} vs {}",
                block.column(c)
            );
        }
    }

    #[test]
    fn a_compressed_spring_keeps_only_the_axial_stiffness() {
        let s = spring();
        let x = [Vector3::zeros(), Vector3::new(0.5, 0.0, 0.0)];
        // 1 − ℓ₀/ℓ = −1 is clamped to 0: k d̂d̂ᵀ = diag(100, 0, 0).
        let block = s.stiffness_block(&s.axis(&x));
        assert_eq!(
            block,
            Matrix3::from_diagonal(&Vector3::new(100.0, 0.0, 0.0))
        );
    }
}
