//! A page's measuring tools (`measure`): its `stopwatch`, `period`, `ruler` and `protractor`
//! tables, checked against the scene's bodies, joints and springs; every error names the
//! key's file:line:column.
//!
//! ```toml
//! stopwatch = { start = 0.5, stop = 2.0 }          # s; start defaults to the page's `at`
//! period = { quantity = "bob.x", level = 0.0 }     # a quantity of the plot list; level optional
//! ruler = { from = "bob", to = "rod.b" }           # a body or a joint's/spring's anchor, or
//! ruler = { from = "cube", from_point = [0.5, 0.5, 0.0], to_point = [0.0, 0.0, 0.0] }
//! protractor = { axis = "cube.y", against = "vertical" }   # or against = "BODY.x|y|z"
//! ```

use super::raw::{RawPage, Vec3};
use super::{did_you_mean, LoadError, Scene, Validator};
use crate::measure::protractor::{BodyAxis, Protractor, Reference};
use crate::measure::ruler::{self, End, Point, Ruler};
use crate::measure::stopwatch::Schedule;
use crate::measure::{period, PageTools};
use toml::Spanned;

impl Validator<'_> {
    /// The tools a page sets (`at`: the page's time, the stopwatch's default start).
    pub(super) fn page_tools(
        &self,
        page: &RawPage,
        at: f64,
        scene: &Scene,
    ) -> Result<PageTools, LoadError> {
        let mut tools = PageTools::default();
        if let Some(w) = &page.stopwatch {
            let w = w.get_ref();
            let start = match &w.start {
                Some(s) => self.non_negative(s, "stopwatch `start` (s)")?,
                None => at,
            };
            let stop = match &w.stop {
                Some(s) => {
                    let stop = self.non_negative(s, "stopwatch `stop` (s)")?;
                    if stop < start {
                        return Err(self.error(
                            s.span(),
                            format!("stopwatch `stop` ({stop} s) is before its start ({start} s)"),
                        ));
                    }
                    Some(stop)
                }
                None => None,
            };
            tools.stopwatch = Some(Schedule { start, stop });
        }
        if let Some(p) = &page.period {
            let p = p.get_ref();
            let bodies: Vec<(String, bool)> = scene
                .bodies
                .iter()
                .map(|b| (b.name.clone(), b.body.fixed))
                .collect();
            let joints: Vec<String> = scene.links.joints.iter().map(|j| j.name.clone()).collect();
            let names = crate::measure::quantity_names(&bodies, &joints);
            let quantity = p.quantity.get_ref().trim();
            if !names.iter().any(|n| n == quantity) {
                let hint = did_you_mean(quantity, names.iter().map(String::as_str))
                    .map_or_else(String::new, |s| format!(" (did you mean `{s}`?)"));
                return Err(self.error(
                    p.quantity.span(),
                    format!(
                        "period: unknown quantity `{quantity}`{hint}: the period timer watches a \
                         quantity of the plot list (BODY.NAME of a moving body, energy, Px, Py, \
                         Pz, JOINT.error)"
                    ),
                ));
            }
            let level = match &p.level {
                Some(l) => Some(self.finite(l, "period `level`")?),
                None => None,
            };
            tools.period = Some(period::Watch {
                quantity: quantity.to_string(),
                level,
            });
        }
        if let Some(r) = &page.ruler {
            let raw = r.get_ref();
            let from = self.ruler_end(r, &raw.from, &raw.from_point, "from", scene)?;
            let to = self.ruler_end(r, &raw.to, &raw.to_point, "to", scene)?;
            tools.ruler = Some(Ruler { from, to });
        }
        if let Some(p) = &page.protractor {
            let p = p.get_ref();
            let axis = self.body_axis(&p.axis, "protractor `axis`", scene)?;
            let against = match &p.against {
                None => Reference::Vertical,
                Some(a) if a.get_ref().trim() == "vertical" => Reference::Vertical,
                Some(a) => Reference::Axis(self.body_axis(
                    a,
                    "protractor `against` (`vertical` or BODY.x|y|z)",
                    scene,
                )?),
            };
            tools.protractor = Some(Protractor { axis, against });
        }
        Ok(tools)
    }

    /// One end of a page's ruler: `from` (a named point) and/or `from_point`.
    fn ruler_end<T>(
        &self,
        table: &Spanned<T>,
        name: &Option<Spanned<String>>,
        point: &Option<Vec3>,
        key: &str,
        scene: &Scene,
    ) -> Result<End, LoadError> {
        let names: Vec<String> = scene.bodies.iter().map(|b| b.name.clone()).collect();
        let named = ruler::named_points(&names, &scene.links);
        let offset = match point {
            Some(p) => Some(self.vector(p, &format!("ruler `{key}_point`"))?),
            None => None,
        };
        match (name, offset) {
            (None, None) => Err(self.error(
                table.span(),
                format!(
                    "ruler: `{key}` or `{key}_point` is required (a body, a joint's or spring's \
                     anchor like `rod.b`, or a point [x, y, z])"
                ),
            )),
            (None, Some(p)) => Ok(End {
                point: Point::World(p),
                name: ruler::world_name(&p),
            }),
            (Some(n), offset) => {
                let text = n.get_ref().trim();
                let Some(end) = named.iter().find(|e| e.name == text) else {
                    let hint = did_you_mean(text, named.iter().map(|e| e.name.as_str()))
                        .map_or_else(String::new, |s| format!(" (did you mean `{s}`?)"));
                    let all: Vec<&str> = named.iter().map(|e| e.name.as_str()).collect();
                    return Err(self.error(
                        n.span(),
                        format!(
                            "ruler `{key}`: unknown point `{text}`{hint}: the named points are {}",
                            all.join(", ")
                        ),
                    ));
                };
                match (offset, end.point) {
                    (None, _) => Ok(end.clone()),
                    (Some(offset), Point::Body { body, .. }) if names.iter().any(|b| b == text) => {
                        Ok(End {
                            point: Point::Body { body, offset },
                            name: format!("{text}+{}", ruler::world_name(&offset)),
                        })
                    }
                    _ => Err(self.anchor_with_point(point, key, text)),
                }
            }
        }
    }

    fn anchor_with_point(&self, point: &Option<Vec3>, key: &str, name: &str) -> LoadError {
        let span = point.as_ref().map(|p| p.span()).unwrap_or_default();
        self.error(
            span,
            format!(
                "ruler `{key}_point` goes with a body's name (a point in its frame), not with the \
                 anchor `{name}`"
            ),
        )
    }

    /// `BODY.x`, `BODY.y` or `BODY.z`.
    fn body_axis(
        &self,
        text: &Spanned<String>,
        what: &str,
        scene: &Scene,
    ) -> Result<BodyAxis, LoadError> {
        let t = text.get_ref().trim();
        let names = || scene.bodies.iter().map(|b| b.name.as_str());
        let (body, axis) = t.rsplit_once('.').unwrap_or((t, ""));
        let axis = ["x", "y", "z"].iter().position(|a| *a == axis);
        let index = scene.body_index(body);
        match (index, axis) {
            (Some(body), Some(axis)) => Ok(BodyAxis { body, axis }),
            (None, _) => {
                let hint = did_you_mean(body, names())
                    .map_or_else(String::new, |s| format!(" (did you mean `{s}`?)"));
                let all: Vec<&str> = names().collect();
                Err(self.error(
                    text.span(),
                    format!(
                        "{what}: unknown body `{body}` in `{t}`{hint}: its bodies are {}",
                        all.join(", ")
                    ),
                ))
            }
            (Some(_), None) => Err(self.error(
                text.span(),
                format!("{what}: `{t}` is not BODY.x, BODY.y or BODY.z (a body axis)"),
            )),
        }
    }
}
