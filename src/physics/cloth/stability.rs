//! The explicit step's stability limit, from the sheet's own stiffness: dt < 2/ω_max.
//!
//! Near rest the free particles obey `M ẍ = −K x − C ẋ` with the assembled stiffness and
//! damping at rest (every spring contributes `k d̂d̂ᵀ`, resp. `c d̂d̂ᵀ`, in the pattern
//! [[1, −1], [−1, 1]] on its two particles; pinned particles' rows and columns removed; drag
//! adds k_drag (m_i/M) to C's diagonal). On a mode with M⁻¹K → ω² and M⁻¹C → γ, symplectic
//! Euler's step matrix on (x, v) is
//!
//! ```text
//! [ 1 − h²ω²   h(1 − hγ) ]      det = 1 − hγ,  trace = 2 − hγ − h²ω²
//! [ −hω²        1 − hγ   ]      stable ⇔ |det| < 1 and |trace| < 1 + det ⇔ h²ω² + 2hγ < 4
//! ⇔  h < h* = 4 / (γ + √(γ² + 4ω²))       (= 2/ω without damping, 2/γ without springs)
//! ```
//!
//! ω_max² is the largest eigenvalue of M⁻¹K, γ_max that of M⁻¹C, each found by power
//! iteration on the symmetric `M^(−½) K M^(−½)` (one spring loop per iteration, no matrix
//! stored) from a deterministic start close to the highest mode, in which neighbours move
//! against each other: `(−1)^(i+j) sin(π(i + ½)/nx) sin(π(j + ½)/nz) (1, ½, 1)` (a free
//! chain's highest mode is exactly `(−1)^i sin(π(i + ½)/n)`). The Rayleigh quotient converges
//! from below, so the limit is approached from above; the iteration stops when the quotient
//! changes by less than 1e-12 relatively, or after [`POWER_ITERATIONS`]. The top of a grid's
//! spectrum is crowded (gaps ~ 1/n²), so a few dozen iterations leave ω_max ~0.3 % low on the
//! 21 × 21 trampoline; 400 bring it within 1e-4 of a dense eigen-solve (a few ms, once per
//! scene).
//!
//! [`ExplicitLimit::dt`] combines ω_max and γ_max in h* as if they belonged to the same mode,
//! which can only make it smaller (h* decreases in both): a safe limit. With the same damping
//! c on every spring and one stiffness k (a chain, a stretch-only grid), C = (c/k)K and h* is
//! exact.
//!
//! Rules of thumb for equal masses m (`references.md`): a long chain's ω_max² → 4k/m; a grid
//! of stretch springs has dt_max ≈ 1.0 √(m/k), with shear springs of the same k ≈ 0.71 √(m/k),
//! with bend springs too ≈ 0.63 √(m/k).

use super::loads::ClothLoads;
use super::sheet::Cloth;
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Most power iterations per eigenvalue.
pub const POWER_ITERATIONS: usize = 400;

/// The explicit limit and its parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitLimit {
    /// ω_max, rad/s: the highest frequency of the undamped sheet at rest.
    pub omega_max: f64,
    /// γ_max, 1/s: the largest damping rate (springs' damping and drag).
    pub damping_rate: f64,
    /// Power iterations used for ω_max.
    pub iterations: usize,
}

impl ExplicitLimit {
    /// 2/ω_max, s (∞ when nothing is stiff).
    pub fn stiffness_limit(&self) -> f64 {
        2.0 / self.omega_max
    }

    /// 2/γ_max, s (∞ without damping).
    pub fn damping_limit(&self) -> f64 {
        2.0 / self.damping_rate
    }

    /// h* = 4/(γ + √(γ² + 4ω²)), s: the step below which `symplectic-euler` is stable.
    pub fn dt(&self) -> f64 {
        let (w, g) = (self.omega_max, self.damping_rate);
        4.0 / (g + (g * g + 4.0 * w * w).sqrt())
    }
}

impl Cloth {
    /// The explicit stability limit at the current directions of the springs, taken at their
    /// rest length (module doc).
    pub fn explicit_limit(&self, loads: &ClothLoads) -> ExplicitLimit {
        let (omega2, iterations) = self.largest_rate(|s| s.stiffness);
        let (gamma_springs, _) = if self.springs.iter().any(|s| s.damping > 0.0) {
            self.largest_rate(|s| s.damping)
        } else {
            (0.0, 0)
        };
        let drag = loads.drag.map_or(0.0, |k| k / self.total_mass);
        ExplicitLimit {
            omega_max: omega2.max(0.0).sqrt(),
            damping_rate: gamma_springs + drag,
            iterations,
        }
    }

    /// The largest eigenvalue of M^(−½) A M^(−½) over the free particles, A assembled from
    /// `coefficient(spring)·d̂d̂ᵀ`; and the iterations used.
    fn largest_rate(&self, coefficient: impl Fn(&super::spring::Spring) -> f64) -> (f64, usize) {
        let n = self.len();
        let scale: Vec<f64> = (0..n)
            .map(|i| {
                if self.pinned[i] {
                    0.0
                } else {
                    1.0 / self.masses[i].sqrt()
                }
            })
            .collect();
        let directions: Vec<(Vector3<f64>, f64)> = self
            .springs
            .iter()
            .map(|s| (s.axis(&self.positions).direction, coefficient(s)))
            .collect();
        let mut u: Vec<Vector3<f64>> = (0..n)
            .map(|p| {
                let (i, j) = self.grid(p);
                let sign = if (i + j) % 2 == 0 { 1.0 } else { -1.0 };
                let envelope = |k: usize, n: usize| (PI * (k as f64 + 0.5) / n as f64).sin();
                let e = envelope(i, self.count[0]) * envelope(j, self.count[1]);
                Vector3::new(1.0, 0.5, 1.0) * (sign * e * scale[p].signum())
            })
            .collect();
        let mut w = vec![Vector3::zeros(); n];
        let norm = |u: &[Vector3<f64>]| u.iter().map(|x| x.norm_squared()).sum::<f64>().sqrt();
        let first = norm(&u);
        if first == 0.0 {
            return (0.0, 0);
        }
        u.iter_mut().for_each(|x| *x /= first);
        let mut quotient = 0.0;
        for iteration in 1..=POWER_ITERATIONS {
            // w = M^(−½) A M^(−½) u
            w.iter_mut().for_each(|x| *x = Vector3::zeros());
            for (s, (d, k)) in self.springs.iter().zip(&directions) {
                let relative = u[s.i] * scale[s.i] - u[s.j] * scale[s.j];
                let y = d * (k * d.dot(&relative));
                w[s.i] += y;
                w[s.j] -= y;
            }
            for (x, &c) in w.iter_mut().zip(&scale) {
                *x *= c;
            }
            let next: f64 = u.iter().zip(&w).map(|(a, b)| a.dot(b)).sum();
            let size = norm(&w);
            if size == 0.0 {
                return (0.0, iteration);
            }
            for (a, b) in u.iter_mut().zip(&w) {
                *a = b / size;
            }
            let converged = (next - quotient).abs() <= 1e-12 * next.abs();
            quotient = next;
            if converged {
                return (quotient, iteration);
            }
        }
        (quotient, POWER_ITERATIONS)
    }
}

#[cfg(test)]
mod tests {
    use super::super::spec::{ClothSpec, Pinning};
    use super::*;
    use nalgebra::DMatrix;

    fn free_limit(spec: &ClothSpec) -> ExplicitLimit {
        Cloth::new(spec)
            .expect("valid")
            .explicit_limit(&ClothLoads::default())
    }

    #[test]
    fn two_particles_on_one_spring_have_omega_squared_2k_over_m() {
        // A flat 2 × 2 sheet with stretch springs only (m = 1 kg each): at rest an x-spring
        // couples only the x-components of its two particles and a z-spring the
        // z-components, so the sheet is four independent one-spring chains, each a two-body
        // oscillator: ω² = k/μ = k/(m/2) = 2k/m.
        let spec = ClothSpec::new([1.0, 1.0], [2, 2], 4.0, 50.0);
        let limit = free_limit(&spec);
        let (k, m) = (50.0f64, 1.0f64);
        let expected = (2.0 * k / m).sqrt();
        assert!(
            (limit.omega_max - expected).abs() < 1e-9 * expected,
            "ω_max = {} vs √(2k/m) = {expected}",
            limit.omega_max
        );
        assert_eq!(limit.stiffness_limit(), limit.dt());
    }

    #[test]
    fn a_long_chain_tends_to_4k_over_m() {
        // A free chain of n equal masses: ω² = (2k/m)(1 + cos(π/n)) exactly (the path
        // Laplacian's largest eigenvalue), → 4k/m as n grows.
        let n = 200;
        let spec = ClothSpec::new([10.0, 0.1], [n, 2], 2.0 * n as f64, 30.0);
        let limit = free_limit(&spec);
        let exact = (2.0 * 30.0 / 1.0 * (1.0 + (std::f64::consts::PI / n as f64).cos())).sqrt();
        assert!(
            (limit.omega_max - exact).abs() < 1e-6 * exact,
            "ω_max = {} vs {exact} ({} iterations)",
            limit.omega_max,
            limit.iterations
        );
        assert!((limit.omega_max / (4.0f64 * 30.0).sqrt() - 1.0).abs() < 1e-4);
    }

    /// The rules of thumb of `references.md` on a 21 × 21 free grid of unit particle mass,
    /// k = 1: dt_max ≈ 1.0 (stretch), 0.71 (+ shear, same k), 0.63 (+ bend, same k).
    #[test]
    fn a_grid_matches_the_rules_of_thumb() {
        let mut spec = ClothSpec::new([2.0, 2.0], [21, 21], 441.0, 1.0);
        let stretch = free_limit(&spec).dt();
        spec.shear = 1.0;
        let shear = free_limit(&spec).dt();
        spec.bend = 1.0;
        let bend = free_limit(&spec).dt();
        for (what, found, rule) in [
            ("stretch", stretch, 1.0),
            ("shear", shear, 0.71),
            ("bend", bend, 0.63),
        ] {
            assert!(
                (found / rule - 1.0).abs() < 0.03,
                "{what}: dt_max = {found:.4} √(m/k) vs rule {rule}"
            );
        }
    }

    /// Against a dense eigen-solve of the same M^(−½) K M^(−½), assembled here from the
    /// grid's geometry (not from the sheet's springs): 5 × 4 sheet, shear and bend, damping,
    /// one corner and two inner particles pinned.
    #[test]
    fn power_iteration_agrees_with_a_dense_eigen_solve() {
        let mut spec = ClothSpec::new([1.0, 0.6], [5, 4], 2.0, 300.0);
        spec.shear = 120.0;
        spec.bend = 40.0;
        spec.damping = 0.3;
        spec.pinned = Pinning::List(vec![[0, 0], [2, 1], [3, 2]]);
        let cloth = Cloth::new(&spec).unwrap();
        let limit = cloth.explicit_limit(&ClothLoads::default());
        let (nx, nz) = (5usize, 4usize);
        let m = 2.0 / 20.0;
        let at = |i: usize, j: usize| Vector3::new(i as f64 * 1.0 / 4.0, 0.0, j as f64 * 0.6 / 3.0);
        type Pair = ((usize, usize), (usize, usize), f64);
        let mut pairs: Vec<Pair> = Vec::new();
        for j in 0..nz {
            for i in 0..nx {
                let mut push = |a, b, k| pairs.push(((i, j), (a, b), k));
                if i + 1 < nx {
                    push(i + 1, j, 300.0)
                }
                if j + 1 < nz {
                    push(i, j + 1, 300.0)
                }
                if i + 2 < nx {
                    push(i + 2, j, 40.0)
                }
                if j + 2 < nz {
                    push(i, j + 2, 40.0)
                }
                if i + 1 < nx && j + 1 < nz {
                    push(i + 1, j + 1, 120.0)
                }
            }
        }
        for j in 0..nz - 1 {
            for i in 1..nx {
                pairs.push(((i, j), (i - 1, j + 1), 120.0));
            }
        }
        let pinned = [(0, 0), (2, 1), (3, 2)];
        let dense = |coefficient: &dyn Fn(f64) -> f64| {
            let mut a = DMatrix::<f64>::zeros(3 * nx * nz, 3 * nx * nz);
            for &((i, j), (p, q), k) in &pairs {
                let d = (at(p, q) - at(i, j)).normalize();
                let block = d * d.transpose() * coefficient(k) / m;
                let (u, w) = (3 * (j * nx + i), 3 * (q * nx + p));
                for r in 0..3 {
                    for c in 0..3 {
                        a[(u + r, u + c)] += block[(r, c)];
                        a[(w + r, w + c)] += block[(r, c)];
                        a[(u + r, w + c)] -= block[(r, c)];
                        a[(w + r, u + c)] -= block[(r, c)];
                    }
                }
            }
            let keep: Vec<usize> = (0..nx * nz)
                .filter(|&p| !pinned.contains(&(p % nx, p / nx)))
                .flat_map(|p| 3 * p..3 * p + 3)
                .collect();
            let reduced = a.select_rows(&keep).select_columns(&keep);
            reduced.symmetric_eigen().eigenvalues.max()
        };
        let omega2 = dense(&|k| k);
        let gamma = dense(&|_| 0.3);
        assert!(
            (limit.omega_max - omega2.sqrt()).abs() < 1e-6 * omega2.sqrt(),
            "ω_max {} vs dense {}",
            limit.omega_max,
            omega2.sqrt()
        );
        assert!(
            (limit.damping_rate - gamma).abs() < 1e-6 * gamma,
            "γ_max {} vs dense {gamma}",
            limit.damping_rate
        );
    }
}
