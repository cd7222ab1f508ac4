//! Preconditioned conjugate gradients on the implicit step's matrix, with Baraff & Witkin's
//! filter for pinned particles.
//!
//! # The matrix: one 3×3 block per spring, matrix-free
//!
//! ```text
//! A = diag(a_i I) + Σ_springs (i, j)  [  S_s  −S_s ]   rows/columns i, j
//!                                     [ −S_s   S_s ]
//! a_i = m_i + h k_drag,i,     S_s = h c d̂d̂ᵀ + h² k J           (see `spring`, `implicit_euler`)
//!     = (h c + h² k (1 − t)) d̂d̂ᵀ + h² k t I,   t = max(0, 1 − ℓ₀/ℓ)   (stored as d̂ and 2 numbers)
//! (A p)_i = a_i p_i + Σ_{s ∋ i} ±S_s (p_i − p_j)
//! ```
//!
//! Every spring's block is built once per step and used twice per product (for i and for j).
//! Why not assemble a sparse matrix (CSR by 3×3 blocks): each particle's row would hold its
//! ~13 neighbour blocks, i.e. the same blocks stored twice plus index arrays, built every step
//! because the blocks change with the deformation; the spring loop does the same arithmetic
//! with half the memory and no assembly. A is symmetric positive definite (M > 0 and every
//! S_s positive semi-definite), which is what conjugate gradients need. A direct sparse
//! factorisation would have to be redone every step (the blocks change), and on a 2-D grid
//! its fill-in costs more than the ~10–30 iterations CG needs at the step sizes of interest.
//!
//! # Preconditioner: Jacobi by 3×3 particle blocks
//!
//! `P_i = a_i I + Σ_{s ∋ i} S_s` (the diagonal block of A), inverted once per step. It is the
//! Jacobi preconditioner taken per particle rather than per scalar, so that a particle whose
//! springs are much stiffer along one direction than across is scaled in each direction.
//!
//! # The filter (Baraff & Witkin 1998, §5.3)
//!
//! A pinned particle's Δv is prescribed (0): the filter zeroes its rows in every residual and
//! search direction, so CG works on the free particles only and never moves a pinned one.
//!
//! ```text
//! Δv ← filter(warm start);  r = filter(b − A Δv);  z = P⁻¹ r;  p = z;  δ = rᵀz
//! δ₀ = filter(b)ᵀ P⁻¹ filter(b)
//! while δ > ε² δ₀:   q = filter(A p);  α = δ / pᵀq;  Δv += α p;  r −= α q
//!                    z = P⁻¹ r;  δ' = rᵀz;  p = z + (δ'/δ) p;  δ = δ'
//! ```

use super::spring::Spring;
use nalgebra::{Matrix3, Vector3};

/// One spring's block `S = along·d̂d̂ᵀ + across·I` (module doc): 5 numbers, not 9.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Block {
    pub direction: Vector3<f64>,
    pub along: f64,
    pub across: f64,
}

impl Block {
    /// S r.
    #[inline]
    fn apply(&self, r: &Vector3<f64>) -> Vector3<f64> {
        self.direction * (self.along * self.direction.dot(r)) + r * self.across
    }

    /// S as a matrix.
    #[inline]
    fn matrix(&self) -> Matrix3<f64> {
        self.direction * self.direction.transpose() * self.along + Matrix3::identity() * self.across
    }
}

/// The solve's buffers, reused from step to step; `solution` is the last Δv (the warm start).
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    /// S_s, one per spring.
    pub blocks: Vec<Block>,
    /// a_i, one per particle.
    pub diagonal: Vec<f64>,
    /// P_i⁻¹, one per particle.
    pub preconditioner: Vec<Matrix3<f64>>,
    pub rhs: Vec<Vector3<f64>>,
    pub solution: Vec<Vector3<f64>>,
    residual: Vec<Vector3<f64>>,
    preconditioned: Vec<Vector3<f64>>,
    direction: Vec<Vector3<f64>>,
    product: Vec<Vector3<f64>>,
}

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    pub iterations: usize,
    /// √(δ/δ₀) at the end.
    pub relative_residual: f64,
}

impl Workspace {
    /// Sizes every per-particle buffer for `n` particles; the warm start is reset to 0 when the
    /// size changed.
    pub fn resize(&mut self, n: usize) {
        if self.solution.len() != n {
            self.solution = vec![Vector3::zeros(); n];
        }
        for buffer in [
            &mut self.rhs,
            &mut self.residual,
            &mut self.preconditioned,
            &mut self.direction,
            &mut self.product,
        ] {
            buffer.resize(n, Vector3::zeros());
        }
        self.preconditioner.resize(n, Matrix3::zeros());
        self.diagonal.resize(n, 0.0);
    }

    /// out = filter(A p).
    fn multiply(
        springs: &[Spring],
        blocks: &[Block],
        diagonal: &[f64],
        pinned: &[bool],
        p: &[Vector3<f64>],
        out: &mut [Vector3<f64>],
    ) {
        for ((o, &a), p) in out.iter_mut().zip(diagonal).zip(p) {
            *o = p * a;
        }
        for (s, block) in springs.iter().zip(blocks) {
            let y = block.apply(&(p[s.i] - p[s.j]));
            out[s.i] += y;
            out[s.j] -= y;
        }
        for (o, &held) in out.iter_mut().zip(pinned) {
            if held {
                *o = Vector3::zeros();
            }
        }
    }

    /// Solves A Δv = rhs for the particles not `pinned`, A built from `blocks` and
    /// `diagonal`; the result is in `solution`. Inverts the preconditioner blocks first.
    pub fn solve(
        &mut self,
        springs: &[Spring],
        pinned: &[bool],
        tolerance: f64,
        max_iterations: usize,
    ) -> Outcome {
        let n = pinned.len();
        // P_i = a_i I + Σ S_s, inverted (free particles only; pinned rows stay 0).
        for (p, &a) in self.preconditioner.iter_mut().zip(&self.diagonal) {
            *p = Matrix3::identity() * a;
        }
        for (s, block) in springs.iter().zip(&self.blocks) {
            let m = block.matrix();
            self.preconditioner[s.i] += m;
            self.preconditioner[s.j] += m;
        }
        for (p, &held) in self.preconditioner.iter_mut().zip(pinned) {
            *p = if held {
                Matrix3::zeros()
            } else {
                p.try_inverse().unwrap_or_else(Matrix3::zeros)
            };
        }
        let dot = |a: &[Vector3<f64>], b: &[Vector3<f64>]| -> f64 {
            a.iter().zip(b).map(|(a, b)| a.dot(b)).sum()
        };
        // δ₀ from the filtered right-hand side.
        for (i, &held) in pinned.iter().enumerate() {
            if held {
                self.rhs[i] = Vector3::zeros();
                self.solution[i] = Vector3::zeros();
            }
            self.preconditioned[i] = self.preconditioner[i] * self.rhs[i];
        }
        let delta0 = dot(&self.rhs, &self.preconditioned);
        if !delta0.is_finite() || delta0 <= 0.0 {
            self.solution.iter_mut().for_each(|x| *x = Vector3::zeros());
            return Outcome {
                iterations: 0,
                relative_residual: 0.0,
            };
        }
        // r = filter(b − A Δv) from the warm start.
        Self::multiply(
            springs,
            &self.blocks,
            &self.diagonal,
            pinned,
            &self.solution,
            &mut self.product,
        );
        for i in 0..n {
            self.residual[i] = self.rhs[i] - self.product[i];
            self.preconditioned[i] = self.preconditioner[i] * self.residual[i];
        }
        let mut delta = dot(&self.residual, &self.preconditioned);
        if delta > delta0 {
            // A warm start worse than zero: start from zero.
            self.solution.iter_mut().for_each(|x| *x = Vector3::zeros());
            self.residual.clone_from(&self.rhs);
            for i in 0..n {
                self.preconditioned[i] = self.preconditioner[i] * self.residual[i];
            }
            delta = delta0;
        }
        self.direction.clone_from(&self.preconditioned);
        let target = tolerance * tolerance * delta0;
        let mut iterations = 0;
        while delta > target && iterations < max_iterations {
            Self::multiply(
                springs,
                &self.blocks,
                &self.diagonal,
                pinned,
                &self.direction,
                &mut self.product,
            );
            let curvature = dot(&self.direction, &self.product);
            if curvature.is_nan() || curvature <= 0.0 {
                break;
            }
            let alpha = delta / curvature;
            let mut next = 0.0;
            for i in 0..n {
                self.solution[i] += self.direction[i] * alpha;
                self.residual[i] -= self.product[i] * alpha;
                self.preconditioned[i] = self.preconditioner[i] * self.residual[i];
                next += self.residual[i].dot(&self.preconditioned[i]);
            }
            let beta = next / delta;
            for i in 0..n {
                self.direction[i] = self.preconditioned[i] + self.direction[i] * beta;
            }
            delta = next;
            iterations += 1;
        }
        Outcome {
            iterations,
            relative_residual: (delta / delta0).max(0.0).sqrt(),
        }
    }
}
