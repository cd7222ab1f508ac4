//! The particle integrators a sheet can use, selectable by name (`integrator = "…"` in a
//! `[[cloth]]` table).
//!
//! ```text
//! symplectic-euler   v ← v + h M⁻¹ f(x, v)            x ← x + h v          (explicit, order 1)
//! implicit-euler     (M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀)
//!                    v ← v + Δv                       x ← x + h v          (backward Euler
//!                                                      linearised once, Baraff & Witkin 1998)
//! ```
//!
//! The explicit step is stable only for h < 2/ω_max (see `stability`); the implicit one is
//! stable at any h, at the price of numerical damping that grows with h.

/// A particle integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClothIntegrator {
    /// Semi-implicit Euler: velocities first, then positions with the new velocities.
    SymplecticEuler,
    /// Backward Euler linearised once per step, solved by preconditioned conjugate gradients.
    ImplicitEuler,
}

impl ClothIntegrator {
    /// Every particle integrator, explicit first.
    pub const ALL: [ClothIntegrator; 2] = [
        ClothIntegrator::SymplecticEuler,
        ClothIntegrator::ImplicitEuler,
    ];

    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ClothIntegrator::SymplecticEuler => "symplectic-euler",
            ClothIntegrator::ImplicitEuler => "implicit-euler",
        }
    }

    /// The integrator with this name.
    pub fn from_name(name: &str) -> Option<ClothIntegrator> {
        ClothIntegrator::ALL.into_iter().find(|i| i.name() == name)
    }

    /// Every valid name, comma-separated (for error messages).
    pub fn names() -> String {
        ClothIntegrator::ALL.map(ClothIntegrator::name).join(", ")
    }

    /// Order of accuracy of the global error.
    pub fn order(self) -> u32 {
        1
    }

    /// Whether the step is explicit (then it has a stability limit on dt).
    pub fn is_explicit(self) -> bool {
        self == ClothIntegrator::SymplecticEuler
    }

    /// The update equations, one line each, for the loop strip and `walk`.
    pub fn formula(self) -> &'static [&'static str] {
        match self {
            ClothIntegrator::SymplecticEuler => &["v ← v + h M⁻¹ f(x, v)", "x ← x + h v"],
            ClothIntegrator::ImplicitEuler => &[
                "(M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀)   (PCG)",
                "v ← v + Δv,   x ← x + h v",
            ],
        }
    }

    /// The next integrator in [`ClothIntegrator::ALL`], wrapping around.
    pub fn next(self) -> ClothIntegrator {
        match self {
            ClothIntegrator::SymplecticEuler => ClothIntegrator::ImplicitEuler,
            ClothIntegrator::ImplicitEuler => ClothIntegrator::SymplecticEuler,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for i in ClothIntegrator::ALL {
            assert_eq!(ClothIntegrator::from_name(i.name()), Some(i));
        }
        assert_eq!(ClothIntegrator::from_name("rk4"), None);
        assert_eq!(ClothIntegrator::names(), "symplectic-euler, implicit-euler");
    }
}
