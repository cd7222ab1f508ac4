//! Scene and lesson files: TOML with the keys of `design.md`, parsed and validated into a
//! [`Lesson`] whose [`Scene`] builds a [`World`].
//!
//! Every error is one line naming file:line:column, what was expected and what was found.
//! A missing effect key means the effect is absent; missing initial conditions mean rest.

mod cloth;
mod diagnose;
pub mod edit;
mod error;
mod keys;
mod links;
pub mod live;
mod mesh;
mod messages;
mod obstacle;
mod page_panels;
mod page_tools;
mod raw;

pub use diagnose::check as check_every_error;
pub use edit::{ClothEdit, SceneEdits};
pub use error::{did_you_mean, printable, LoadError};
pub use page_panels::PagePanel;

use crate::physics::cloth::{Cloth, ClothIntegrator, ClothSpec};
use crate::physics::joints::Links;
use crate::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, Orientation,
    Response, SoftStep, State, World,
};
use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};
use raw::{RawBodies, RawBody, RawLesson, RawObstacle, RawScene, Vec3};
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A page of a lesson's narrative.
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// The page applies from this time on, s.
    pub at: f64,
    pub title: String,
    /// As written: live numbers (`{{…}}`) unfilled; see [`Page::live`].
    pub text: String,
    /// The live numbers of `text`, in order.
    pub live: Vec<live::LiveNumber>,
    /// What the student is asked to predict on this page.
    pub predict: Option<live::Prediction>,
    /// The panels the page names (`panels = [...]`), shown first at any size; a tool's
    /// table (`ruler = {...}`) names its panel too.
    pub panels: Vec<PagePanel>,
    /// What the page sets its measuring tools to (`stopwatch`, `period`, `ruler`,
    /// `protractor`).
    pub tools: crate::measure::PageTools,
}

/// Everything a world is built from.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Time step, s.
    pub dt: f64,
    /// How long the scene is meant to run, s.
    pub duration: Option<f64>,
    pub integrator: Integrator,
    pub effects: Effects,
    pub contact: Option<ContactModel>,
    pub obstacles: Vec<Obstacle>,
    /// The bodies, in file order (at least one, unless the scene has a cloth).
    pub bodies: Vec<SceneBody>,
    /// The `[[cloth]]` sheets, in file order.
    pub cloths: Vec<ClothSpec>,
    /// The `[[joint]]`s and `[[spring]]`s, and `joint_correction`.
    pub links: Links,
}

/// A body of a scene: `[body]` or one `[[body]]`.
#[derive(Debug, Clone)]
pub struct SceneBody {
    /// Unique in the file (default body1, body2, …).
    pub name: String,
    pub body: Body,
    /// The body's shape name as written (box, points, mesh).
    pub shape: String,
    pub initial: State,
}

impl Scene {
    /// A world at the scene's initial state: the one place a scene becomes a world.
    pub fn world(&self) -> World {
        self.world_with(self.integrator, self.dt)
    }

    /// The same world stepped by another integrator or time step (the study's runs).
    pub fn world_with(&self, integrator: Integrator, dt: f64) -> World {
        let bodies = self
            .bodies
            .iter()
            .map(|b| NamedBody {
                name: b.name.clone(),
                body: b.body.clone(),
                initial: b.initial,
            })
            .collect();
        let world = World::with_bodies(
            bodies,
            self.effects.clone(),
            self.obstacles.clone(),
            self.contact,
            integrator,
            dt,
        );
        let world = if self.links.is_empty() {
            world
        } else {
            world.with_links(self.links.clone())
        };
        if self.cloths.is_empty() {
            return world;
        }
        // Specs were validated when the scene was loaded: `Cloth::new` cannot fail here.
        world.with_cloths(
            self.cloths
                .iter()
                .filter_map(|s| Cloth::new(s).ok())
                .collect(),
        )
    }

    /// The first body (the one `run` prints by default).
    pub fn first(&self) -> &SceneBody {
        &self.bodies[0]
    }

    /// The index of the body with this name.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }
}

/// How a broken scene rule names the setting at fault: as the file's key (`dt`,
/// `response = "impulse"`), as the command line's flag (`--dt`, `--response impulse`), or as
/// the app's keys (`dt (e)`, `the impulse response (c)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Naming {
    File,
    Flags,
    Keys,
}

impl Naming {
    fn dt(self) -> &'static str {
        match self {
            Naming::File => "dt",
            Naming::Flags => "--dt",
            Naming::Keys => "dt (e)",
        }
    }

    fn response(self, name: &str) -> String {
        match self {
            Naming::File => format!("response = \"{name}\""),
            Naming::Flags => format!("--response {name}"),
            Naming::Keys => format!("the `{name}` response (c)"),
        }
    }
}

/// A scene setting a rule is about: each can come from the file or from a flag.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setting {
    Dt,
    Response,
}

impl Scene {
    /// The rules between the settings the command line may replace (`dt`, the collision
    /// response) and the rest of the scene: the loader checks the file with them, and every
    /// command checks the scene again after its flags (`--dt`, `--response`) replaced a
    /// setting, so a flag can never say what the file may not. The error names the setting
    /// at fault in `naming`'s words.
    pub fn check_rules(&self, naming: Naming) -> Result<(), (Setting, String)> {
        if !(self.dt > 0.0 && self.dt.is_finite()) {
            return Err((
                Setting::Dt,
                format!(
                    "{} must be > 0 and finite, found {}",
                    naming.dt(),
                    crate::limits::short(self.dt)
                ),
            ));
        }
        if let Some(model) = &self.contact {
            if model.response == Response::Seed && self.bodies.len() > 1 {
                return Err((
                    Setting::Response,
                    format!(
                        "the `seed` response knows one body and fixed obstacles only, and this \
                         scene has {} bodies: use {}",
                        self.bodies.len(),
                        naming.response("impulse")
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// A lesson (or a bare scene): title, summary, scene and pages.
#[derive(Debug, Clone)]
pub struct Lesson {
    pub path: PathBuf,
    pub title: String,
    pub summary: String,
    pub scene: Scene,
    /// Pages in order of `at`.
    pub pages: Vec<Page>,
}

impl Lesson {
    /// The page that applies at time `t` (the last one whose `at` ≤ t).
    pub fn page_at(&self, t: f64) -> Option<(usize, &Page)> {
        self.pages
            .iter()
            .enumerate()
            .rev()
            .find(|(_, p)| p.at <= t + 1e-12)
    }
}

/// Reads and validates a lesson or scene file.
pub fn load(path: &Path) -> Result<Lesson, LoadError> {
    parse(&read(path)?, path)
}

/// The text of a scene file: read as every input is ([`crate::limits::read_bounded_bytes`]:
/// at most [`crate::limits::MAX_FILE_BYTES`] bytes read, special files refused), UTF-8.
pub fn read(path: &Path) -> Result<String, LoadError> {
    let bytes =
        crate::limits::read_bounded_bytes(path, crate::limits::MAX_FILE_BYTES, "scene file")
            .map_err(|e| LoadError::file(path, e.reason))?;
    if bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]) {
        return Err(LoadError::file(
            path,
            "UTF-16 text: a scene file is UTF-8 (save it as UTF-8)",
        ));
    }
    String::from_utf8(bytes).map_err(|_| {
        LoadError::file(
            path,
            "not a text file (invalid UTF-8): expected a TOML scene",
        )
    })
}

/// Parses and validates a lesson from its source text; `path` names it in errors and anchors
/// relative mesh paths.
pub fn parse(source: &str, path: &Path) -> Result<Lesson, LoadError> {
    if source.trim().is_empty() {
        return Err(LoadError::file(
            path,
            "empty file: expected a TOML scene with at least `title`, [scene] and [body]",
        ));
    }
    if source.contains('\0') {
        return Err(LoadError::file(
            path,
            "not a text file (contains NUL bytes): expected a TOML scene",
        ));
    }
    // A file that does not deserialize is read again as plain TOML: a syntax error is called
    // one (it comes first), else the error is about the shape of a scene. (One parse of a
    // valid file, not two.)
    let raw: RawLesson = toml::from_str(source).map_err(|shape| {
        if let Err(e) = source.parse::<toml::Table>() {
            let token = e.span().and_then(|s| source.get(s)).unwrap_or("");
            return located(path, source, e.span(), messages::syntax(e.message(), token));
        }
        located(path, source, shape.span(), messages::shape(shape.message()))
    })?;
    Validator { source, path }.lesson(raw)
}

/// An error at a span when the parser gave one, else about the whole file.
fn located(path: &Path, source: &str, span: Option<Range<usize>>, message: String) -> LoadError {
    match span {
        Some(span) => LoadError::at(path, source, span, message),
        None => LoadError::file(path, message),
    }
}

struct Validator<'a> {
    source: &'a str,
    path: &'a Path,
}

impl Validator<'_> {
    fn error(&self, span: Range<usize>, message: impl Into<String>) -> LoadError {
        LoadError::at(self.path, self.source, span, message)
    }

    fn lesson(&self, raw: RawLesson) -> Result<Lesson, LoadError> {
        self.counts(&raw)?;
        let bodies = self.bodies(raw.body, !raw.cloths.is_empty())?;
        let links = self.links(&raw.scene, &raw.joints, &raw.springs, &bodies)?;
        self.no_overlap(&bodies, &links)?;
        let title = raw.title.into_inner();
        let scene_integrator = raw.scene.get_ref().integrator.clone();
        let body_spans: Vec<Range<usize>> = bodies.iter().map(|(_, s)| s.clone()).collect();
        if let Some(contact) = &raw.scene.get_ref().contact {
            let response = contact.get_ref().response.get_ref();
            let round = bodies
                .iter()
                .find(|(b, _)| b.body.shape.as_ref().is_some_and(|s| s.is_round()));
            if let (true, Some((b, _))) = (response == "seed", round) {
                return Err(self.error(
                    contact.get_ref().response.span(),
                    format!(
                        "the `seed` response tests vertices, and the {} `{}` has none: use \
                         response = \"impulse\"",
                        b.shape, b.name
                    ),
                ));
            }
        }
        let mut scene = self.scene(raw.scene, bodies, &raw.obstacles, &links)?;
        scene.links = links;
        let names: Vec<&str> = scene.bodies.iter().map(|b| b.name.as_str()).collect();
        scene.cloths = self.cloths(
            &raw.cloths,
            &scene_integrator,
            scene.contact.is_some(),
            &names,
        )?;
        scene.obstacles = raw
            .obstacles
            .iter()
            .map(|o| self.obstacle(o))
            .collect::<Result<_, _>>()?;
        self.finite_start(&scene, &body_spans, &raw.cloths)?;
        let mut pages = Vec::new();
        for page in raw.pages {
            let span = page.span();
            let page = page.into_inner();
            let at = self.finite(&page.at, "page time `at`")?;
            if at < 0.0 {
                return Err(self.error(
                    page.at.span(),
                    format!("page time `at` must be ≥ 0 s, found {at}"),
                ));
            }
            if pages.last().is_some_and(|p: &Page| p.at > at) {
                return Err(self.error(span, "pages must be in order of `at`"));
            }
            let tools = self.page_tools(&page, at, &scene)?;
            let names: Vec<String> = scene.bodies.iter().map(|b| b.name.clone()).collect();
            let text_span = page.text.span();
            let text = page.text.into_inner();
            let live = live::live_numbers(&text, at, &names).map_err(|(offset, message)| {
                self.error(
                    self.placeholder_span(text_span.clone(), &text, offset),
                    message,
                )
            })?;
            let predict = match page.predict {
                None => None,
                Some(p) => {
                    let p = p.into_inner();
                    let quantity = live::quantity(p.quantity.get_ref(), &names)
                        .map_err(|e| self.error(p.quantity.span(), format!("predict: {e}")))?;
                    let when = self.non_negative(&p.at, "predict `at` (s)")?;
                    Some(live::Prediction { quantity, at: when })
                }
            };
            let mut panels = page
                .panels
                .iter()
                .flatten()
                .map(|name| {
                    PagePanel::from_name(name.get_ref())
                        .map_err(|e| self.error(name.span(), format!("page `panels`: {e}")))
                })
                .collect::<Result<Vec<_>, _>>()?;
            for (set, panel) in [
                (tools.stopwatch.is_some(), PagePanel::Stopwatch),
                (tools.period.is_some(), PagePanel::Period),
                (tools.ruler.is_some(), PagePanel::Ruler),
                (tools.protractor.is_some(), PagePanel::Protractor),
            ] {
                if set && !panels.contains(&panel) {
                    panels.push(panel);
                }
            }
            pages.push(Page {
                at,
                title: page.title,
                text,
                live,
                predict,
                panels,
                tools,
            });
        }
        Ok(Lesson {
            path: self.path.to_path_buf(),
            title,
            summary: raw.summary.unwrap_or_default(),
            scene,
            pages,
        })
    }

    /// Where, in the file, the `{{` at byte `offset` of a page's text is: the same
    /// occurrence of `{{` inside the string as written (escapes and the newline after `"""`
    /// shift offsets, never the count of `{{`); the string's start if it cannot be found.
    fn placeholder_span(&self, text_span: Range<usize>, text: &str, offset: usize) -> Range<usize> {
        let nth = text[..offset].matches("{{").count();
        let written = self.source.get(text_span.clone()).unwrap_or("");
        written
            .match_indices("{{")
            .nth(nth)
            .map_or(text_span.clone(), |(i, _)| {
                text_span.start + i..text_span.start + i + 2
            })
    }

    fn finite(&self, value: &Spanned<f64>, what: &str) -> Result<f64, LoadError> {
        let v = *value.get_ref();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(
                value.span(),
                format!("{what} must be a finite number, found {v}"),
            ))
        }
    }

    fn positive(&self, value: &Spanned<f64>, what: &str) -> Result<f64, LoadError> {
        let v = self.finite(value, what)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.error(value.span(), format!("{what} must be > 0, found {v}")))
        }
    }

    /// A mass: > 0, finite, and a normal number (a subnormal mass, below 2.2e-308 kg, has lost
    /// its precision and its inertia tensor vanishes).
    fn mass(&self, value: &Spanned<f64>) -> Result<f64, LoadError> {
        let v = self.positive(value, "mass")?;
        if v.is_normal() {
            Ok(v)
        } else {
            Err(self.error(
                value.span(),
                format!(
                    "mass {v:e} kg is too small to compute with: at least 2.2e-308 kg (a \
                     normal number)"
                ),
            ))
        }
    }

    fn non_negative(&self, value: &Spanned<f64>, what: &str) -> Result<f64, LoadError> {
        let v = self.finite(value, what)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(self.error(value.span(), format!("{what} must be ≥ 0, found {v}")))
        }
    }

    fn vector(&self, value: &Vec3, what: &str) -> Result<Vector3<f64>, LoadError> {
        let v = value.get_ref();
        if v.iter().all(|c| c.is_finite()) {
            Ok(Vector3::from(*v))
        } else {
            Err(self.error(
                value.span(),
                format!("{what} must have finite components, found {v:?}"),
            ))
        }
    }

    fn optional_vector(&self, value: &Option<Vec3>, what: &str) -> Result<Vector3<f64>, LoadError> {
        value
            .as_ref()
            .map_or(Ok(Vector3::zeros()), |v| self.vector(v, what))
    }

    /// `[body]` or `[[body]]`: names unique (default body1, body2, …). None at all only when
    /// the file has a cloth (`has_cloth`).
    fn bodies(
        &self,
        raw: Option<Spanned<RawBodies>>,
        has_cloth: bool,
    ) -> Result<Vec<(SceneBody, Range<usize>)>, LoadError> {
        let Some(raw) = raw else {
            if has_cloth {
                return Ok(Vec::new());
            }
            return Err(self.error(
                0..0,
                "missing table `[body]`: a scene file needs `title`, [scene] and [body] (or [[body]])",
            ));
        };
        let span = raw.span();
        let list = match raw.into_inner() {
            RawBodies::One(body) => vec![Spanned::new(span.clone(), *body)],
            RawBodies::Many(list) => list,
        };
        if list.is_empty() {
            return Err(self.error(span, "`body` is empty: give at least one [[body]]"));
        }
        let mut bodies: Vec<(SceneBody, Range<usize>)> = Vec::with_capacity(list.len());
        for (i, raw) in list.into_iter().enumerate() {
            let span = raw.span();
            let name = raw
                .get_ref()
                .name
                .as_ref()
                .map(|n| (n.get_ref().clone(), n.span()));
            let name = match name {
                Some((name, at)) => {
                    if name.trim().is_empty() {
                        return Err(self.error(at, "body `name` must not be empty"));
                    }
                    if bodies.iter().any(|(b, _)| b.name == name) {
                        return Err(self.error(
                            at,
                            format!(
                                "duplicate body name `{name}`: each [[body]] needs its own name"
                            ),
                        ));
                    }
                    name
                }
                None => {
                    let mut n = i + 1;
                    while bodies.iter().any(|(b, _)| b.name == format!("body{n}")) {
                        n += 1;
                    }
                    format!("body{n}")
                }
            };
            let (body, shape, initial) = self.body(raw)?;
            bodies.push((
                SceneBody {
                    name,
                    body,
                    shape,
                    initial,
                },
                span,
            ));
        }
        Ok(bodies)
    }

    /// No body may start inside another: the first pair whose shapes overlap at their initial
    /// poses (geometric depth > 1e-9 m; touching is fine) is an error at the later body.
    /// Bodies joined directly by a joint may overlap (they do not collide).
    ///
    /// Only pairs whose bounding spheres meet are tested (sweep and prune along x: bodies
    /// sorted by x − r, each compared with those whose interval is still open), so a chain of
    /// n links costs n log n, not n²; the pairs are tested in the order of the file (later
    /// body, then earlier), so the error names the same pair as a test of every pair would.
    fn no_overlap(
        &self,
        bodies: &[(SceneBody, Range<usize>)],
        links: &Links,
    ) -> Result<(), LoadError> {
        use crate::physics::collision::geometry::{deepest, shape_shape, Pose};
        let pose = |b: &SceneBody| Pose {
            position: b.initial.position,
            rotation: b.initial.orientation.matrix(),
        };
        let joined: std::collections::HashSet<(usize, usize)> =
            links.joined_pairs().into_iter().collect();
        // (index, centre, bounding radius) of every body with a shape, by x − r.
        let mut spheres: Vec<(usize, Vector3<f64>, f64)> = bodies
            .iter()
            .enumerate()
            .filter_map(|(i, (b, _))| {
                let shape = b.body.shape.as_ref()?;
                Some((i, b.initial.position, shape.bounding_radius()))
            })
            .collect();
        spheres.sort_by(|a, b| (a.1.x - a.2).total_cmp(&(b.1.x - b.2)));
        let mut open: Vec<(usize, Vector3<f64>, f64)> = Vec::new();
        let mut candidates: Vec<(usize, usize)> = Vec::new();
        for &(j, centre, radius) in &spheres {
            open.retain(|(_, c, r)| c.x + r >= centre.x - radius);
            for &(i, c, r) in &open {
                let (low, high) = (i.min(j), i.max(j));
                // A margin of 1e-9 m over the radii: the depth threshold of the test below.
                let apart = (c - centre).norm() > r + radius + 1e-9;
                if !apart && !joined.contains(&(low, high)) {
                    candidates.push((high, low));
                }
            }
            open.push((j, centre, radius));
        }
        candidates.sort_unstable();
        let mut points = Vec::new();
        for (j, i) in candidates {
            let (later, span) = &bodies[j];
            let earlier = &bodies[i].0;
            let (Some(shape_j), Some(shape_i)) = (&later.body.shape, &earlier.body.shape) else {
                continue;
            };
            points.clear();
            shape_shape(
                shape_j,
                &pose(later),
                shape_i,
                &pose(earlier),
                0.0,
                &mut points,
            );
            let depth = deepest(&points);
            if depth > 1e-9 {
                return Err(self.error(
                    span.clone(),
                    format!(
                        "body `{}` starts inside body `{}` (overlap {depth:.3e} m): move \
                         them apart so that they at most touch",
                        later.name, earlier.name
                    ),
                ));
            }
        }
        Ok(())
    }

    /// At most [`crate::limits::MAX_BODIES`] bodies and [`crate::limits::MAX_LINKS`] joints
    /// and springs: past a limit, an error at the first table beyond it, before any of them
    /// is validated.
    fn counts(&self, raw: &RawLesson) -> Result<(), LoadError> {
        use crate::limits::{MAX_BODIES, MAX_LINKS};
        if let Some(RawBodies::Many(list)) = raw.body.as_ref().map(Spanned::get_ref) {
            if let Some(past) = list.get(MAX_BODIES) {
                return Err(self.error(
                    past.span(),
                    format!(
                        "this scene has {} bodies, more than the limit of {MAX_BODIES} bodies a \
                         scene may have",
                        list.len()
                    ),
                ));
            }
        }
        let links = raw.joints.len() + raw.springs.len();
        if links > MAX_LINKS {
            let past = raw
                .joints
                .get(MAX_LINKS)
                .map(Spanned::span)
                .or_else(|| {
                    raw.springs
                        .get(MAX_LINKS - raw.joints.len())
                        .map(Spanned::span)
                })
                .unwrap_or(0..0);
            return Err(self.error(
                past,
                format!(
                    "this scene has {} joints and {} springs, {links} links, more than the limit \
                     of {MAX_LINKS} joints and springs together a scene may have",
                    raw.joints.len(),
                    raw.springs.len()
                ),
            ));
        }
        Ok(())
    }

    fn scene(
        &self,
        raw: Spanned<RawScene>,
        bodies: Vec<(SceneBody, Range<usize>)>,
        obstacles: &[Spanned<RawObstacle>],
        links: &Links,
    ) -> Result<Scene, LoadError> {
        let raw = raw.into_inner();
        let dt = self.positive(&raw.dt, "dt")?;
        let duration = raw
            .duration
            .as_ref()
            .map(|d| self.positive(d, "duration"))
            .transpose()?;
        // A scene of cloths only may name a particle integrator: no body uses the scene's.
        let cloths_only =
            bodies.is_empty() && ClothIntegrator::from_name(raw.integrator.get_ref()).is_some();
        let integrator = if cloths_only {
            Some(Integrator::ALL[0])
        } else {
            Integrator::from_name(raw.integrator.get_ref())
        };
        let integrator = integrator.ok_or_else(|| {
            let name = raw.integrator.get_ref();
            let hint = did_you_mean(name, Integrator::ALL.map(Integrator::name))
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            self.error(
                raw.integrator.span(),
                format!(
                    "unknown integrator `{name}`{hint}; valid integrators: {}",
                    Integrator::names()
                ),
            )
        })?;
        let mut effects = Vec::new();
        if let Some(g) = &raw.gravity {
            effects.push(Effect::Gravity(self.vector(g, "gravity")?));
        }
        if let Some(drag) = &raw.drag {
            let d = drag.get_ref();
            let coefficient = |c: &Option<Spanned<f64>>, what| {
                c.as_ref().map_or(Ok(0.0), |c| self.non_negative(c, what))
            };
            let linear = coefficient(&d.linear, "drag.linear")?;
            let angular = coefficient(&d.angular, "drag.angular")?;
            if d.linear.is_none() && d.angular.is_none() {
                return Err(self.error(
                    drag.span(),
                    "drag needs `linear` and/or `angular` coefficients",
                ));
            }
            effects.push(Effect::Drag { linear, angular });
        }
        let contact = raw.contact.as_ref().map(|c| self.contact(c)).transpose()?;
        if contact.is_none() {
            if let Some(first) = obstacles.first() {
                return Err(self.error(
                    first.span(),
                    "obstacles need a collision response: add `contact = { response = \"impulse\", \
                     restitution = 0.4, friction = 0.5 }` to [scene]",
                ));
            }
            // Bodies joined directly do not collide: a response is needed only when some
            // pair is not joined.
            // (The pairs joined are distinct and ordered: all are when they are n(n−1)/2.)
            let n = bodies.len();
            let all_joined = links.joined_pairs().len() == n * n.saturating_sub(1) / 2;
            if let (Some((_, second)), false) = (bodies.get(1), all_joined) {
                return Err(self.error(
                    second.clone(),
                    "several bodies need a collision response: add `contact = { response = \
                     \"impulse\", restitution = 0.4, friction = 0.5 }` to [scene]",
                ));
            }
        }
        let scene = Scene {
            dt,
            duration,
            integrator,
            effects: Effects::new(effects),
            contact,
            obstacles: Vec::new(),
            bodies: bodies.into_iter().map(|(b, _)| b).collect(),
            cloths: Vec::new(),
            links: Links::default(),
        };
        scene
            .check_rules(Naming::File)
            .map_err(|(setting, message)| {
                let at = match (setting, &raw.contact) {
                    (Setting::Response, Some(c)) => c.get_ref().response.span(),
                    _ => raw.dt.span(),
                };
                self.error(at, message)
            })?;
        Ok(scene)
    }

    fn contact(&self, raw: &Spanned<raw::RawContact>) -> Result<ContactModel, LoadError> {
        let c = raw.get_ref();
        let name = c.response.get_ref();
        let response = Response::from_name(name).ok_or_else(|| {
            let hint = did_you_mean(name, Response::ALL.map(Response::name))
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            self.error(
                c.response.span(),
                format!(
                    "unknown collision response `{name}`{hint}; valid responses: {}",
                    Response::names()
                ),
            )
        })?;
        let restitution = match &c.restitution {
            Some(e) => {
                let e_value = self.non_negative(e, "restitution")?;
                if e_value > 1.0 {
                    return Err(self.error(
                        e.span(),
                        format!("restitution must be between 0 and 1, found {e_value}"),
                    ));
                }
                e_value
            }
            None => 0.0,
        };
        let friction = c
            .friction
            .as_ref()
            .map_or(Ok(0.0), |f| self.non_negative(f, "friction"))?;
        let impacts = match &c.impacts {
            Some(word) => self.impacts(word, response)?,
            None => Impacts::default(),
        };
        let response = match response {
            Response::SoftStep(defaults) => Response::SoftStep(self.soft_step(c, defaults)?),
            other => {
                let keys = [
                    ("hertz", c.hertz.as_ref().map(Spanned::span)),
                    ("damping_ratio", c.damping_ratio.as_ref().map(Spanned::span)),
                    ("substeps", c.substeps.as_ref().map(Spanned::span)),
                ];
                if let Some((key, Some(at))) = keys.into_iter().find(|(_, s)| s.is_some()) {
                    return Err(self.error(
                        at,
                        format!(
                            "`{key}` is a key of the `soft-step` response, not of `{}`",
                            other.name()
                        ),
                    ));
                }
                other
            }
        };
        Ok(ContactModel {
            response,
            restitution,
            friction,
            impacts,
        })
    }

    /// `impacts = "propagate" | "simultaneous"`: a key of the `impulse` response only (`seed`
    /// and `soft-step` have no impact law to choose, so the key on them is refused).
    fn impacts(&self, word: &Spanned<String>, response: Response) -> Result<Impacts, LoadError> {
        let name = word.get_ref();
        if response != Response::Impulse {
            return Err(self.error(
                word.span(),
                format!(
                    "`impacts` is a key of the `impulse` response, not of `{}`",
                    response.name()
                ),
            ));
        }
        Impacts::from_name(name).ok_or_else(|| {
            let hint = did_you_mean(name, Impacts::ALL.map(Impacts::name))
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            self.error(
                word.span(),
                format!(
                    "unknown impact law `{name}`{hint}; valid laws: {}",
                    Impacts::names()
                ),
            )
        })
    }

    /// `hertz` (> 0, Hz), `damping_ratio` (≥ 0) and `substeps` (1 ..= 64) of `soft-step`,
    /// each defaulting to [`SoftStep::DEFAULT`]'s.
    fn soft_step(&self, c: &raw::RawContact, defaults: SoftStep) -> Result<SoftStep, LoadError> {
        let hertz = c
            .hertz
            .as_ref()
            .map_or(Ok(defaults.hertz), |h| self.positive(h, "hertz"))?;
        let damping_ratio = c
            .damping_ratio
            .as_ref()
            .map_or(Ok(defaults.damping_ratio), |z| {
                self.non_negative(z, "damping_ratio")
            })?;
        let substeps = match &c.substeps {
            Some(n) => {
                let v = *n.get_ref();
                let max = crate::physics::collision::soft_step::MAX_SUBSTEPS;
                if v < 1 || v > i64::from(max) {
                    return Err(self.error(
                        n.span(),
                        format!("substeps must be a whole number from 1 to {max}, found {v}"),
                    ));
                }
                v as u32
            }
            None => defaults.substeps,
        };
        Ok(SoftStep {
            hertz,
            damping_ratio,
            substeps,
        })
    }

    fn body(&self, raw: Spanned<RawBody>) -> Result<(Body, String, State), LoadError> {
        let span = raw.span();
        let b = raw.into_inner();
        let shape = b.shape.get_ref().as_str();
        // The shape word first (an unknown one is blamed, not its keys), then its keys.
        let kind = keys::SHAPES
            .kind(shape)
            .map_err(|message| self.error(b.shape.span(), message))?;
        if let Some((at, message)) = keys::SHAPES.misplaced(kind, &b.present()) {
            return Err(self.error(at, message));
        }
        let needs = |key: &str| self.error(span.clone(), format!("a {shape} body needs `{key}`"));
        let fixed = b.fixed.as_ref().is_some_and(|f| *f.get_ref());
        let mass = b.mass.as_ref().map(|m| self.mass(m)).transpose()?;
        // A fixed body's mass is ignored (it never moves): any positive number builds it.
        let mass = if fixed {
            Some(mass.unwrap_or(1.0))
        } else {
            mass
        };
        let inertia = match &b.inertia {
            None => None,
            Some(i) => match i.get_ref().as_str() {
                "solid" | "points" | "shell" => Some((i.get_ref().as_str(), i.span())),
                other => {
                    return Err(self.error(
                        i.span(),
                        format!("unknown inertia `{other}`; valid: solid, points, shell"),
                    ))
                }
            },
        };
        let round = matches!(shape, "sphere" | "capsule" | "cylinder");
        match inertia {
            Some(("shell", at)) if !matches!(shape, "sphere" | "cylinder") => {
                return Err(self.error(
                    at,
                    format!(
                        "`inertia = \"shell\"` is for a sphere or a cylinder, not a {shape} body"
                    ),
                ))
            }
            Some(("points", at)) if round => {
                return Err(self.error(
                    at,
                    format!(
                        "a {shape} has no mass points: use `inertia = \"solid\"`{}",
                        if shape == "capsule" {
                            ""
                        } else {
                            " or \"shell\""
                        }
                    ),
                ))
            }
            _ => {}
        }
        if fixed {
            let moving = [&b.velocity, &b.angular_velocity, &b.angular_velocity_body];
            if let Some(v) = moving.into_iter().flatten().next() {
                return Err(self.error(
                    v.span(),
                    "a fixed body never moves: remove its velocity (or `fixed = true`)",
                ));
            }
        }
        let body_error =
            |at: Range<usize>, e: crate::physics::BodyError| self.error(at, e.to_string());
        let body = match shape {
            "box" => {
                let size_raw = b.size.as_ref().ok_or_else(|| needs("size"))?;
                let size = self.vector(size_raw, "size")?;
                if size.iter().any(|s| *s <= 0.0) {
                    return Err(self.error(
                        size_raw.span(),
                        format!(
                            "box `size` needs three sides > 0 m, found {:?}",
                            size_raw.get_ref()
                        ),
                    ));
                }
                let mass = mass.ok_or_else(|| needs("mass"))?;
                match inertia.map(|i| i.0) {
                    Some("points") => Body::box_of_corners(size, mass),
                    _ => Body::solid_box(size, mass),
                }
                .map_err(|e| body_error(size_raw.span(), e))?
            }
            "sphere" | "capsule" | "cylinder" => {
                let radius_raw = b.radius.as_ref().ok_or_else(|| needs("radius"))?;
                let radius = self.positive(radius_raw, "radius")?;
                // (`length` on a sphere was refused with the shape's keys.)
                let length = match (&b.length, shape) {
                    (Some(l), _) => self.positive(l, "length")?,
                    (None, "sphere") => 0.0,
                    (None, _) => return Err(needs("length")),
                };
                let mass = mass.ok_or_else(|| needs("mass"))?;
                let shell = inertia.is_some_and(|i| i.0 == "shell");
                match shape {
                    "sphere" => Body::sphere(radius, mass, shell),
                    "capsule" => Body::capsule(radius, length, mass),
                    _ => Body::cylinder(radius, length, mass, shell),
                }
                .map_err(|e| body_error(radius_raw.span(), e))?
            }
            "points" => {
                let points_raw = b.points.as_ref().ok_or_else(|| needs("points"))?;
                self.no_solid(inertia)?;
                let points: Vec<Vector3<f64>> = points_raw
                    .get_ref()
                    .iter()
                    .map(|p| Vector3::from(*p))
                    .collect();
                let masses = match &b.masses {
                    Some(m) => {
                        for &value in m.get_ref() {
                            if !(value > 0.0 && value.is_normal()) {
                                return Err(self.error(
                                    m.span(),
                                    format!(
                                        "point masses must be > 0, finite and at least 2.2e-308 \
                                         kg (a normal number), found {value:e}"
                                    ),
                                ));
                            }
                        }
                        if let (Some(total), Some(mass_raw)) = (mass, &b.mass) {
                            let sum: f64 = m.get_ref().iter().sum();
                            if (sum - total).abs() > 1e-9 * total {
                                return Err(self.error(
                                    mass_raw.span(),
                                    format!("`mass` = {total} but the point masses sum to {sum}: give one or the other"),
                                ));
                            }
                        }
                        m.get_ref().clone()
                    }
                    None => {
                        mass.ok_or_else(|| needs("mass (or `masses`, one per point)"))?;
                        Vec::new()
                    }
                };
                Body::from_points(&points, &masses, mass.unwrap_or(0.0), Vec::new())
                    .map_err(|e| body_error(points_raw.span(), e))?
            }
            "mesh" => {
                let file_raw = b.file.as_ref().ok_or_else(|| needs("file"))?;
                self.no_solid(inertia)?;
                let mass = mass.ok_or_else(|| needs("mass"))?;
                let mesh_path = self
                    .path
                    .parent()
                    .unwrap_or(Path::new("."))
                    .join(file_raw.get_ref());
                let (points, edges) = mesh::load_obj(&mesh_path).map_err(|why| {
                    self.error(
                        file_raw.span(),
                        format!("mesh `{}`: {why}", mesh_path.display()),
                    )
                })?;
                Body::from_points(&points, &[], mass, edges)
                    .map_err(|e| body_error(file_raw.span(), e))?
            }
            // Every shape of `keys::SHAPES` is built above.
            other => {
                let message = keys::SHAPES.kind(other).err().unwrap_or_default();
                return Err(self.error(b.shape.span(), message));
            }
        };
        let orientation = match &b.orientation {
            None => UnitQuaternion::identity(),
            Some(o) => self.orientation(o)?,
        };
        let rotation = orientation.to_rotation_matrix().into_inner();
        let omega =
            match (&b.angular_velocity, &b.angular_velocity_body) {
                (Some(_), Some(both)) => return Err(self.error(
                    both.span(),
                    "give `angular_velocity` (world frame) or `angular_velocity_body`, not both",
                )),
                (Some(w), None) => self.vector(w, "angular_velocity")?,
                (None, Some(w)) => rotation * self.vector(w, "angular_velocity_body")?,
                (None, None) => Vector3::zeros(),
            };
        let inertia_world = rotation * body.inertia_body * rotation.transpose();
        let initial = State {
            position: self.optional_vector(&b.position, "position")?,
            orientation: Orientation::Quaternion(orientation),
            linear_momentum: self.optional_vector(&b.velocity, "velocity")? * body.mass,
            angular_momentum: inertia_world * omega,
        };
        let body = if fixed { body.fixed() } else { body };
        Ok((body, shape.to_string(), initial))
    }

    /// Every number of the initial state, and every number formed from it (momenta, weight,
    /// energies), is finite: a file of huge but finite values (a velocity of 1e308 m/s, a mass
    /// of 1e308 kg under gravity, a sheet of 1e200 m) is refused here, naming the keys whose
    /// product overflowed, rather than "diverging" at step 0 or 1 without having diverged.
    fn finite_start(
        &self,
        scene: &Scene,
        body_spans: &[Range<usize>],
        cloths: &[Spanned<raw::RawCloth>],
    ) -> Result<(), LoadError> {
        let finite = |v: &Vector3<f64>| v.iter().all(|c| c.is_finite());
        let g = scene.effects.gravity().unwrap_or_else(Vector3::zeros);
        for (b, span) in scene.bodies.iter().zip(body_spans) {
            let s = &b.initial;
            let v = s.linear_momentum * b.body.inv_mass;
            let rotation = s.orientation.matrix();
            let omega =
                rotation * b.body.inv_inertia_body * rotation.transpose() * s.angular_momentum;
            let weight = g * b.body.mass;
            let overflow = if !finite(&s.linear_momentum) {
                Some("its momentum M·v overflows: `velocity` × `mass`")
            } else if !finite(&s.angular_momentum) || !finite(&omega) {
                Some("its angular momentum I·ω overflows: `angular_velocity` × the inertia of `mass` and the shape")
            } else if !(0.5 * s.linear_momentum.dot(&v)).is_finite() {
                Some("its kinetic energy ½ M v² overflows: `velocity` (and `mass`)")
            } else if !(0.5 * omega.dot(&s.angular_momentum)).is_finite() {
                Some("its rotational energy ½ ω·L overflows: `angular_velocity` (and `mass`)")
            } else if !finite(&weight) {
                Some("its weight M·g overflows: `mass` × `gravity`")
            } else if !weight.dot(&s.position).is_finite() {
                Some("its potential energy −M g·x overflows: `position` × `mass` × `gravity`")
            } else {
                None
            };
            if let Some(why) = overflow {
                return Err(self.error(
                    span.clone(),
                    format!(
                        "body `{}`: {why} (a number beyond ±1.8e308): give smaller values",
                        b.name
                    ),
                ));
            }
        }
        if let Some(first) = cloths.first() {
            let energy = scene.world().total_energy();
            if !(energy.kinetic.is_finite()
                && energy.potential.is_finite()
                && energy.total.is_finite())
            {
                return Err(self.error(
                    first.span(),
                    "the scene's initial energy overflows (a number beyond ±1.8e308): a \
                     cloth's `size`, `position`, `mass`, `stretch` or `velocity` is too large",
                ));
            }
        }
        Ok(())
    }

    fn no_solid(&self, inertia: Option<(&str, Range<usize>)>) -> Result<(), LoadError> {
        match inertia {
            Some(("solid", span)) => Err(self.error(
                span,
                "`inertia = \"solid\"` needs a closed-form shape (box); points and meshes use `points`",
            )),
            _ => Ok(()),
        }
    }

    fn orientation(
        &self,
        raw: &Spanned<raw::RawOrientation>,
    ) -> Result<UnitQuaternion<f64>, LoadError> {
        let o = raw.get_ref();
        match (&o.axis, &o.degrees, &o.quaternion) {
            (Some(axis), Some(degrees), None) => {
                let a = self.vector(axis, "orientation axis")?;
                let angle = self.finite(degrees, "orientation degrees")?;
                let unit = Unit::try_new(a, 1e-12).ok_or_else(|| {
                    self.error(axis.span(), "orientation axis has zero length: give a non-zero axis")
                })?;
                Ok(UnitQuaternion::from_axis_angle(&unit, angle.to_radians()))
            }
            (None, None, Some(q)) => {
                let [w, x, y, z] = *q.get_ref();
                let quaternion = Quaternion::new(w, x, y, z);
                // Scaled by its largest component before it is normalised: the norm of
                // [1e300, 0, 0, 1e300] overflows, the norm of [1, 0, 0, 1] does not.
                let largest = quaternion.coords.amax();
                if !(quaternion.coords.iter().all(|c| c.is_finite()) && largest > 0.0) {
                    return Err(self.error(q.span(), "orientation quaternion must be finite and non-zero"));
                }
                let norm = quaternion.norm();
                let scaled = if norm.is_finite() && norm > 1e-100 {
                    quaternion
                } else {
                    quaternion / largest
                };
                if scaled.norm() <= 1e-12 {
                    return Err(self.error(q.span(), "orientation quaternion must be finite and non-zero"));
                }
                Ok(UnitQuaternion::from_quaternion(scaled))
            }
            _ => Err(self.error(
                raw.span(),
                "orientation is either { axis = [x, y, z], degrees = a } or { quaternion = [w, x, y, z] }",
            )),
        }
    }
}
