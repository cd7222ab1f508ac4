//! The collision responses a scene can choose (`contact = { response = "…" }`), each described
//! once: the scene-file name, what it is and what it keeps (the README's table), the formula
//! the loop strip shows in the collide phase, and its colour in the study's chart. Adding a
//! response is its file, one variant and one descriptor in [`Response::descriptor`] (a missing
//! one does not compile).

use super::soft_step::SoftStep;

/// Everything the front ends say about a collision response, in one place.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Descriptor {
    /// The name used in scene files and on the command line.
    pub name: &'static str,
    /// What it is, in one line (the README's response table).
    pub summary: &'static str,
    /// What it keeps and what it gives up (the README's response table).
    pub keeps: &'static str,
    /// What the collide phase does, in a few words (the loop strip before the first step).
    pub brief: &'static str,
    /// The collide phase's update for one body against obstacles, as the loop strip shows it.
    pub formula: &'static str,
    /// The same for bodies against bodies (two-sided rows).
    pub formula_bodies: &'static str,
    /// Whether the loop strip lists its contacts as impulses (n, uₙ, k, J); `seed` lists its
    /// push-out depth and momentum change instead.
    pub impulses: bool,
    /// Its colour in the study's chart and SVG, (r, g, b).
    pub colour: (u8, u8, u8),
}

/// Which collision response runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Response {
    /// The original report's response, reproduced with its failures.
    Seed,
    /// Sequential impulses with restitution and Coulomb friction.
    Impulse,
    /// Sub-stepped soft contacts with a relax pass (Box2D v3): fast, approximate, sags.
    SoftStep(SoftStep),
}

impl Response {
    /// Every response, in teaching order (`soft-step` with its documented defaults).
    pub const ALL: [Response; 3] = [
        Response::Seed,
        Response::Impulse,
        Response::SoftStep(SoftStep::DEFAULT),
    ];

    /// What the front ends say about this response.
    pub fn descriptor(self) -> &'static Descriptor {
        match self {
            Response::Seed => &Descriptor {
                name: "seed",
                summary: "the original report's response: the whole momentum reversed and scaled by 0.4, a squared push-out, a force added to L (one body, obstacles only)",
                keeps: "nothing promised: it reproduces the report's failures (a landing kicks the body into a spin)",
                brief: "push vertices out of obstacles",
                formula: "seed (the report's): x += d²·n,  L += (pₖ − x₀)×(−F),  P ← −0.4·P",
                formula_bodies: "seed (the report's): x += d²·n,  L += (pₖ − x₀)×(−F),  P ← −0.4·P",
                impulses: false,
                colour: (200, 40, 40),
            },
            Response::Impulse => &Descriptor {
                name: "impulse",
                summary: "impulses at every contact together, converged: restitution e, Coulomb friction μ, penetration removed by moving the body, speculative contacts within a step's reach",
                keeps: "never adds kinetic energy (a bounce pays for its lift); momentum between bodies; stacks stand to micrometres",
                brief: "impulses at every contact",
                formula: "uₙ = (v + ω×r)·n,  k = 1/M + n·((I⁻¹(r×n))×r),  j = −(1+e)·uₙ/k  (all contacts together, + friction)",
                formula_bodies: "uₙ = (v_A + ω_A×r_A − v_B − ω_B×r_B)·n,  k = Σ 1/M + (r×n)·I⁻¹(r×n),  j = −(1+e)·uₙ/k  on A, −j on B (all contacts together, + friction)",
                impulses: true,
                colour: (0, 0, 0),
            },
            Response::SoftStep(_) => &Descriptor {
                name: "soft-step",
                summary: "sub-stepped soft contacts with a relax pass (Box2D v3): each contact a damped spring of `hertz` and `damping_ratio`, one sweep per sub-step",
                keeps: "momentum between bodies; energy at most the lift out of penetration; sags N(N−1)g/ω² at the top of a stack of N, which buckles above (1.96 ω² a/g)^(1/3) cubes of side 2a",
                brief: "soft contacts over sub-steps",
                formula: "per sub-step h = dt/n:  Δλ = −m·a₂a₃·(uₙ + ω_c s/a₁) − a₃·λ,  λ ≥ 0;  x += h·v;  relax: Δλ = −m·uₙ  (m = 1/k, ω_c = 2π·hertz)",
                formula_bodies: "per sub-step h = dt/n:  Δλ = −m·a₂a₃·(uₙ + ω_c s/a₁) − a₃·λ on A, −Δλ on B;  x += h·v;  relax: Δλ = −m·uₙ  (m = 1/k, ω_c = 2π·hertz)",
                impulses: true,
                colour: (130, 130, 130),
            },
        }
    }

    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// The response with this name (soft-step with its documented defaults).
    pub fn from_name(name: &str) -> Option<Response> {
        Response::ALL.into_iter().find(|r| r.name() == name)
    }

    /// Every valid name, comma-separated.
    pub fn names() -> String {
        Response::ALL.map(Response::name).join(", ")
    }

    /// The next response in [`Response::ALL`], wrapping around (soft-step with its defaults).
    pub fn next(self) -> Response {
        let i = Response::ALL
            .iter()
            .position(|r| r.name() == self.name())
            .unwrap_or(0);
        Response::ALL[(i + 1) % Response::ALL.len()]
    }
}
