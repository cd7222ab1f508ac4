//! The collision responses a scene can choose (`contact = { response = "…" }`), each described
//! once: the scene-file name, what it is and what it keeps (the README's table), the formula
//! the loop strip shows in the collide phase, and its colour in the study's chart.
//!
//! As with the integrators, one list builds everything: `responses!` (invoked once, in
//! `collision/mod.rs`) takes `Variant => module` lines and declares the modules, the
//! [`Response`] enum, [`Response::ALL`] (the name lookup, the error messages' list of names,
//! the `r` cycle, the compare key, the study and the README's table all read it),
//! [`Response::descriptor`] (each module's `DESCRIPTOR`) and [`Response::collide`] (each
//! module's `collide`). Adding a response is **its file** (a `pub const DESCRIPTOR:
//! Descriptor` and a `collide` with the signature below; a missing one does not compile) and
//! **one line** in the list, plus its row in the README's table (a test checks it):
//!
//! ```text
//! pub fn collide(input: &CollideInput, [params: &Params,] states: &mut [State],
//!                contacts: &mut Vec<Contact>, scratch: &mut impulse::Scratch)
//!                -> Option<EnergyChange>
//! ```
//!
//! and a particle verb (`pub fn particle([params: &Params]) -> impl ParticleLaw`: how its
//! contact treats a cloth particle, `collision::particle`; a missing one does not compile
//! either).
//!
//! A response with scene-file keys carries them in its variant, written
//! `Variant(params: Params = DEFAULT) => module` (the keys are read by the scene loader).

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
    /// Whether the study's contact-solver chart runs it on every scene with contact (`seed`
    /// does not: it knows one body, and reproduces a report's failures).
    pub charted: bool,
}

/// Declares the collision responses from one list (module doc): the modules, the enum,
/// [`Response::ALL`], [`Response::descriptor`], [`Response::collide`] and
/// [`Response::particle`].
macro_rules! responses {
    ($($(#[$doc:meta])* $variant:ident $(($params:ident: $kind:ty = $default:expr))? => $module:ident,)*) => {
        $(pub mod $module;)*

        /// Which collision response runs.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Response {
            $($(#[$doc])* $variant $(($kind))?,)*
        }

        impl Response {
            /// Every response, in teaching order (each with its documented defaults).
            pub const ALL: [Response; [$(stringify!($variant),)*].len()] =
                [$(Response::$variant $(($default))?,)*];

            /// What the front ends say about this response (its module's `DESCRIPTOR`).
            pub fn descriptor(self) -> &'static $crate::physics::collision::response::Descriptor {
                match self {
                    $(Response::$variant { .. } => &$module::DESCRIPTOR,)*
                }
            }

            /// Runs detection and this response on `states` (its module's `collide`; see
            /// [`collide`](crate::physics::collision::collide)).
            pub fn collide(
                self,
                input: &CollideInput,
                states: &mut [$crate::physics::state::State],
                contacts: &mut Vec<Contact>,
                scratch: &mut impulse::Scratch,
            ) -> Option<EnergyChange> {
                match self {
                    $(Response::$variant $(($params))? =>
                        $module::collide(input, $(&$params,)? states, contacts, scratch),)*
                }
            }

            /// How this response treats a particle (its module's `particle`; see
            /// [`collision::particle`](crate::physics::collision::particle)): the cloths'
            /// contact passes ask it.
            pub fn particle(self) -> Box<dyn $crate::physics::collision::particle::ParticleLaw> {
                match self {
                    $(Response::$variant $(($params))? =>
                        Box::new($module::particle($(&$params)?)),)*
                }
            }
        }
    };
}

use super::Response;

impl Response {
    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// The response with this name (with its documented defaults).
    pub fn from_name(name: &str) -> Option<Response> {
        Response::ALL.into_iter().find(|r| r.name() == name)
    }

    /// Every valid name, comma-separated.
    pub fn names() -> String {
        Response::ALL.map(Response::name).join(", ")
    }

    /// The next response in [`Response::ALL`], wrapping around (with its defaults).
    pub fn next(self) -> Response {
        let i = Response::ALL
            .iter()
            .position(|r| r.name() == self.name())
            .unwrap_or(0);
        Response::ALL[(i + 1) % Response::ALL.len()]
    }
}
