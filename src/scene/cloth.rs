//! `[[cloth]]` tables validated into [`ClothSpec`]s: every rule of `physics::cloth::spec`,
//! each broken rule a one-line error at the key at fault.
//!
//! | rule | error |
//! |---|---|
//! | `count` ≥ 1 along x and z, ≥ 2 particles in all (1 along an axis: a rope) | cloth `count` needs at least 1 particle along x and along z and 2 in all (a rope is [n, 1] or [1, n]), found [0, 5] |
//! | at most 250 000 particles | cloth `count` [100000, 100000] is too large: at most 250000 particles |
//! | `size` > 0 (≥ 0 along an axis of count 1) | cloth `size` needs two sides > 0 m, found [2.0, 0.0] |
//! | `mass`, `stretch` > 0; `shear`, `bend`, `damping` ≥ 0 | stretch must be > 0, found -5 |
//! | `pinned` keyword | unknown pinned `corner` (did you mean `corners`?); valid: corners, edges, none, or [[i, j], …] |
//! | `pinned` list in the grid | pinned particle [21, 0] is outside the 21×21 grid: i must be in 0..21 and j in 0..21 |
//! | `integrator` a particle integrator | unknown cloth integrator `rk4`; valid cloth integrators: … |
//! | absent `integrator`: the scene's must be one | cloth `sheet` has no `integrator` and the scene's `rk4` is not a particle integrator: … |
//! | names not empty | cloth `name` must not be empty |
//! | names unique | duplicate cloth name `sheet`: cloth names must be unique in the file |
//! | `attach` particle in the grid, body known, not pinned, once | attach: unknown body `bob`; bodies in this file: cube |
//! | `attach` names its `body` | this attach entry has no `body`: each entry names the body its particles move with, … |
//! | `attach` one of `particle` and `edge` | an attach entry needs one of `particle = [i, j]` or `edge = "-x"` (-x, +x, -z, +z, all), not both |
//! | `attach` edge a known name | unknown attach edge `top`; valid: -x, +x, -z, +z, all (-x is the edge i = 0, …) |
//! | a cloth touches things | a cloth needs a collision response: add `contact = …` to [scene] |

use super::error::did_you_mean;
use super::raw::RawCloth;
use super::{LoadError, Validator};
use crate::physics::cloth::{Attach, ClothIntegrator, ClothSpec, Pinning};
use toml::Spanned;

/// The edges an `attach` entry may name.
const EDGES: [&str; 5] = ["-x", "+x", "-z", "+z", "all"];

/// The particles of an edge of an nx × nz grid, in grid order (`all`: the rim, each once, in
/// row order j then i); None for an unknown name.
fn edge_particles(edge: &str, [nx, nz]: [usize; 2]) -> Option<Vec<[usize; 2]>> {
    let on = |i: usize, j: usize| match edge {
        "-x" => i == 0,
        "+x" => i == nx - 1,
        "-z" => j == 0,
        "+z" => j == nz - 1,
        _ => i == 0 || j == 0 || i == nx - 1 || j == nz - 1,
    };
    EDGES.contains(&edge).then(|| {
        (0..nz)
            .flat_map(|j| (0..nx).map(move |i| [i, j]))
            .filter(|&[i, j]| on(i, j))
            .collect()
    })
}

/// The most particles a sheet may have (500 × 500): beyond, a typo, not a lesson.
const MAX_PARTICLES: i64 = 250_000;

/// "unknown cloth integrator `WORD` (did you mean `…`?); valid cloth integrators: …" (the
/// settings form checks a typed name with the same words).
pub(super) fn unknown_cloth_integrator(word: &str) -> String {
    let hint = did_you_mean(word, ClothIntegrator::ALL.map(ClothIntegrator::name))
        .map(|s| format!(" (did you mean `{s}`?)"))
        .unwrap_or_default();
    format!(
        "unknown cloth integrator `{word}`{hint}; valid cloth integrators: {}",
        ClothIntegrator::names()
    )
}

impl Validator<'_> {
    /// Every `[[cloth]]` table, in file order. `scene_integrator` is the scene's (a cloth
    /// without its own takes it); `has_contact` whether [scene] declares a response.
    pub(super) fn cloths(
        &self,
        raw: &[Spanned<RawCloth>],
        scene_integrator: &Spanned<String>,
        has_contact: bool,
        bodies: &[&str],
    ) -> Result<Vec<ClothSpec>, LoadError> {
        let mut specs: Vec<ClothSpec> = Vec::with_capacity(raw.len());
        for (k, table) in raw.iter().enumerate() {
            let spec = self.cloth(table, k, scene_integrator, bodies)?;
            if specs.iter().any(|s| s.name == spec.name) {
                let span = table
                    .get_ref()
                    .name
                    .as_ref()
                    .map_or(table.span(), |n| n.span());
                return Err(self.error(
                    span,
                    format!(
                        "duplicate cloth name `{}`: cloth names must be unique in the file",
                        spec.name
                    ),
                ));
            }
            specs.push(spec);
        }
        // After each cloth's own values, so that `tumble check` reports those too (this
        // error blanks the cloth out to look further).
        if let (Some(first), false) = (raw.first(), has_contact) {
            return Err(self.error(
                first.span(),
                "a cloth needs a collision response (its particles touch bodies and obstacles): \
                 add `contact = { response = \"impulse\", restitution = 0.4, friction = 0.5 }` \
                 to [scene]",
            ));
        }
        Ok(specs)
    }

    /// One `[[cloth]]` table, the `index`-th (0-based) of the file.
    fn cloth(
        &self,
        table: &Spanned<RawCloth>,
        index: usize,
        scene_integrator: &Spanned<String>,
        bodies: &[&str],
    ) -> Result<ClothSpec, LoadError> {
        let c = table.get_ref();
        let name = c
            .name
            .as_ref()
            .map_or_else(|| format!("cloth{}", index + 1), |n| n.get_ref().clone());
        if let (true, Some(n)) = (name.trim().is_empty(), &c.name) {
            return Err(self.error(n.span(), "cloth `name` must not be empty"));
        }
        let [nx, nz] = *c.count.get_ref();
        if nx < 1 || nz < 1 || nx * nz < 2 {
            return Err(self.error(
                c.count.span(),
                format!(
                    "cloth `count` needs at least 1 particle along x and along z and 2 in all \
                     (a rope is [n, 1] or [1, n]), found [{nx}, {nz}]"
                ),
            ));
        }
        if nx.saturating_mul(nz) > MAX_PARTICLES {
            return Err(self.error(
                c.count.span(),
                format!(
                    "cloth `count` [{nx}, {nz}] is too large: at most {MAX_PARTICLES} particles"
                ),
            ));
        }
        let count = [nx as usize, nz as usize];
        let size = *c.size.get_ref();
        // Along an axis with one row (a rope) the side is unused and may be 0.
        let side_ok = |s: f64, n: usize| s.is_finite() && (s > 0.0 || (n == 1 && s == 0.0));
        if !(side_ok(size[0], count[0]) && side_ok(size[1], count[1])) {
            let message = if count.contains(&1) {
                format!(
                    "cloth `size` needs its side along the rope > 0 m (the other ≥ 0), found {size:?}"
                )
            } else {
                format!("cloth `size` needs two sides > 0 m, found {size:?}")
            };
            return Err(self.error(c.size.span(), message));
        }
        let optional = |value: &Option<Spanned<f64>>, what: &str| {
            value
                .as_ref()
                .map_or(Ok(0.0), |v| self.non_negative(v, what))
        };
        let integrator = match &c.integrator {
            Some(i) => ClothIntegrator::from_name(i.get_ref())
                .ok_or_else(|| self.error(i.span(), unknown_cloth_integrator(i.get_ref())))?,
            None => ClothIntegrator::from_name(scene_integrator.get_ref()).ok_or_else(|| {
                self.error(
                    table.span(),
                    format!(
                        "cloth `{name}` has no `integrator` and the scene's `{}` is not a particle \
                         integrator: add `integrator = \"implicit-euler\"` to the cloth (valid: {})",
                        scene_integrator.get_ref(),
                        ClothIntegrator::names()
                    ),
                )
            })?,
        };
        let pinning = match &c.pinned {
            None => Pinning::None,
            Some(p) => self.pinned(p, count)?,
        };
        let mut attach: Vec<Attach> = Vec::new();
        for entry in c.attach.iter().flatten() {
            let a = entry.get_ref();
            let Some(body_name) = &a.body else {
                return Err(self.error(
                    entry.span(),
                    "this attach entry has no `body`: each entry names the body its particles \
                     move with, e.g. { particle = [0, 0], body = \"bob\" }",
                ));
            };
            let particles: Vec<[usize; 2]> =
                match (a.particle.as_ref().map(|p| *p.get_ref()), &a.edge) {
                    (Some([i, j]), None) => {
                        if i < 0 || j < 0 || i as usize >= count[0] || j as usize >= count[1] {
                            return Err(self.error(
                                entry.span(),
                                format!(
                                "attached particle [{i}, {j}] is outside the {}×{} grid: i must \
                                 be in 0..{} and j in 0..{}",
                                count[0], count[1], count[0], count[1]
                            ),
                            ));
                        }
                        vec![[i as usize, j as usize]]
                    }
                    (None, Some(edge)) => {
                        edge_particles(edge.get_ref(), count).ok_or_else(|| {
                            let hint = did_you_mean(edge.get_ref(), EDGES)
                                .map(|s| format!(" (did you mean `{s}`?)"))
                                .unwrap_or_default();
                            self.error(
                                edge.span(),
                                format!(
                            "unknown attach edge `{}`{hint}; valid: {} (-x is the edge i = 0, \
                             +x i = {}, -z j = 0, +z j = {}, all the whole rim)",
                            edge.get_ref(),
                            EDGES.join(", "),
                            count[0] - 1,
                            count[1] - 1
                        ),
                            )
                        })?
                    }
                    _ => {
                        return Err(self.error(
                            entry.span(),
                            "an attach entry needs one of `particle = [i, j]` or `edge = \"-x\"` \
                         (-x, +x, -z, +z, all), not both",
                        ))
                    }
                };
            let Some(body) = bodies.iter().position(|b| *b == body_name.get_ref()) else {
                return Err(self.error(
                    body_name.span(),
                    format!(
                        "attach: unknown body `{}`; bodies in this file: {}",
                        body_name.get_ref(),
                        bodies.join(", ")
                    ),
                ));
            };
            for particle in particles {
                let [i, j] = particle;
                if pinning.holds(i, j, count) {
                    return Err(self.error(
                        entry.span(),
                        format!(
                            "particle [{i}, {j}] is both pinned and attached: a particle is held \
                             by one of them"
                        ),
                    ));
                }
                if attach.iter().any(|b| b.particle == particle) {
                    return Err(self.error(
                        entry.span(),
                        format!("particle [{i}, {j}] is attached twice"),
                    ));
                }
                attach.push(Attach { particle, body });
            }
        }
        let spec = ClothSpec {
            name,
            size,
            count,
            position: self.optional_vector(&c.position, "position")?,
            mass: self.positive(&c.mass, "mass")?,
            stretch: self.positive(&c.stretch, "stretch")?,
            shear: optional(&c.shear, "shear")?,
            bend: optional(&c.bend, "bend")?,
            damping: optional(&c.damping, "damping")?,
            pinned: pinning,
            velocity: self.optional_vector(&c.velocity, "velocity")?,
            integrator,
            attach,
        };
        // Every rule is checked above with its place; this is the physics core's own check.
        spec.validate()
            .map_err(|e| self.error(table.span(), e.to_string()))?;
        Ok(spec)
    }

    /// `pinned`: a keyword or a list of [i, j] inside the grid.
    fn pinned(&self, raw: &Spanned<toml::Value>, count: [usize; 2]) -> Result<Pinning, LoadError> {
        let valid = "valid: corners, edges, none, or a list [[i, j], …]";
        match raw.get_ref() {
            toml::Value::String(word) => Pinning::from_keyword(word).ok_or_else(|| {
                let hint = did_you_mean(word, Pinning::KEYWORDS)
                    .map(|s| format!(" (did you mean `{s}`?)"))
                    .unwrap_or_default();
                self.error(
                    raw.span(),
                    format!("unknown pinned `{word}`{hint}; {valid}"),
                )
            }),
            toml::Value::Array(items) => {
                let mut list = Vec::with_capacity(items.len());
                for item in items {
                    let pair = item.as_array().and_then(|a| match a.as_slice() {
                        [i, j] => Some((i.as_integer()?, j.as_integer()?)),
                        _ => None,
                    });
                    let Some((i, j)) = pair else {
                        return Err(self.error(
                            raw.span(),
                            format!(
                                "each pinned particle is a pair of integers [i, j], found {item}"
                            ),
                        ));
                    };
                    if i < 0 || j < 0 || i as usize >= count[0] || j as usize >= count[1] {
                        return Err(self.error(
                            raw.span(),
                            format!(
                                "pinned particle [{i}, {j}] is outside the {}×{} grid: i must be \
                                 in 0..{} and j in 0..{}",
                                count[0], count[1], count[0], count[1]
                            ),
                        ));
                    }
                    list.push([i as usize, j as usize]);
                }
                Ok(Pinning::List(list))
            }
            other => Err(self.error(
                raw.span(),
                format!(
                    "`pinned` must be a keyword or a list of [i, j] pairs, found {other}; {valid}"
                ),
            )),
        }
    }
}
