//! The measuring tools in the app (the logic is `crate::measure`): which are shown, how keys
//! and clicks set them, and their readouts as panels of `tables::Panel` rows — so the panels
//! column, the stage layout's essentials, `tumble shot` and `tumble record` show them as they
//! show every other panel.
//!
//! | key | tool |
//! |---|---|
//! | `w` | stopwatch: start / stop (on simulated time) |
//! | `o` | stopwatch: lap |
//! | `O` | stopwatch: zero and hide |
//! | `T` | period timer on / off: the quantity graphed (`p`), else the page's, else the first |
//! | `m` | ruler on, then its first end through the named points, then off |
//! | `M` | ruler: its second end through the named points |
//! | `A` | protractor on, then through every body axis, then off |
//! | `V` | protractor: against the vertical, then every other body axis |
//!
//! What a page sets (its `stopwatch`, `period`, `ruler`, `protractor` tables) applies while
//! it is shown unless a key or a click set the tool since.

use super::app::App;
use super::viewport::Axis;
use crate::measure::period::{self, Watch};
use crate::measure::protractor::{axis_name, BodyAxis, Protractor, Reference};
use crate::measure::ruler::{self, End, Point, Ruler};
use crate::measure::stopwatch::Stopwatch;
use crate::scene::PagePanel;
use crate::tables::{number, number_plain, Panel, Row, NUMBER_WIDTH};
use nalgebra::Vector3;

/// Laps the stopwatch panel lists (the latest).
pub const LAPS_SHOWN: usize = 3;

/// The tools' state in the app.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tools {
    pub stopwatch: Stopwatch,
    /// Shown by a key (`w`, `o`); a page may show it too.
    pub stopwatch_shown: bool,
    /// A key worked the stopwatch: it reads the keys' times, not the page's schedule.
    pub stopwatch_used: bool,
    /// Shown by `T`.
    pub period_shown: bool,
    /// What `T` chose (the quantity graphed then); None: the page's, else the first quantity.
    pub period: Option<Watch>,
    /// Shown by `m` or `M`.
    pub ruler_shown: bool,
    /// Set by keys or a click; None: the page's, else the first two named points.
    pub ruler: Option<Ruler>,
    pub protractor_shown: bool,
    /// Set by keys; None: the page's, else the first body's y axis against the vertical.
    pub protractor: Option<Protractor>,
    /// Clicks on empty drawing that set a ruler end (even: the next sets `from`, odd: `to`).
    pub ruler_clicks: usize,
}

/// The axis a view looks along: its coordinate of a clicked point is unknown.
pub fn depth_of(axis: Axis) -> usize {
    match axis {
        Axis::Front => 2,
        Axis::Side => 0,
        Axis::Top => 1,
    }
}

impl App {
    /// The page shown's tools.
    fn page_tools(&self) -> Option<&crate::measure::PageTools> {
        self.session
            .lesson
            .page_at(self.session.snapshot.time)
            .map(|(_, page)| &page.tools)
    }

    fn page_names(&self, panel: PagePanel) -> bool {
        self.session
            .lesson
            .page_at(self.session.snapshot.time)
            .is_some_and(|(_, page)| page.panels.contains(&panel))
    }

    /// The tools shown, in stacking order: by a key, or named by the page shown.
    pub fn tools_shown(&self) -> Vec<PagePanel> {
        let t = &self.ui.tools;
        PagePanel::TOOLS
            .into_iter()
            .filter(|&p| {
                self.page_names(p)
                    || match p {
                        PagePanel::Stopwatch => t.stopwatch_shown,
                        PagePanel::Period => t.period_shown,
                        PagePanel::Ruler => t.ruler_shown,
                        _ => t.protractor_shown,
                    }
            })
            .collect()
    }

    /// The named points of the scene (bodies' barycenters, joints' and springs' anchors).
    pub fn named_points(&self) -> Vec<End> {
        let s = &self.session.snapshot;
        let names: Vec<String> = s.bodies.iter().map(|b| b.name.clone()).collect();
        let joints = s.joints.iter().map(|j| {
            let [a, b] = j.local_anchors;
            (j.name.as_str(), j.body_indices.0, j.body_indices.1, a, b)
        });
        let springs = s.springs.iter().map(|j| {
            let [a, b] = j.local_anchors;
            (j.name.as_str(), j.body_indices.0, j.body_indices.1, a, b)
        });
        ruler::named_points_of(&names, joints.chain(springs))
    }

    /// The ruler in effect: set by keys or a click, else the page's, else from the first
    /// named point to the second (or to the origin).
    pub fn ruler(&self) -> Ruler {
        if let Some(r) = self
            .ui
            .tools
            .ruler
            .clone()
            .or_else(|| self.page_tools()?.ruler.clone())
        {
            return r;
        }
        let mut named = self.named_points().into_iter();
        let origin = || End {
            point: Point::World(Vector3::zeros()),
            name: "origin".into(),
        };
        let from = named.next().unwrap_or_else(origin);
        Ruler {
            from,
            to: named.next().unwrap_or_else(origin),
        }
    }

    /// The protractor in effect: set by keys, else the page's, else the first body's y axis
    /// against the vertical (None: no body).
    pub fn protractor(&self) -> Option<Protractor> {
        if self.session.snapshot.bodies.is_empty() {
            return None;
        }
        Some(
            self.ui
                .tools
                .protractor
                .or_else(|| self.page_tools()?.protractor)
                .unwrap_or(Protractor {
                    axis: BodyAxis { body: 0, axis: 1 },
                    against: Reference::Vertical,
                }),
        )
    }

    /// What the period timer watches: `T`'s choice, else the page's, else the first quantity
    /// of the plot list; and its column there (None: not in this scene's list).
    pub fn period_watch(&self) -> Option<(Watch, Option<usize>)> {
        let watch = self
            .ui
            .tools
            .period
            .clone()
            .or_else(|| self.page_tools()?.period.clone())
            .or_else(|| {
                self.session.plot_series.columns.first().map(|c| Watch {
                    quantity: c.name.clone(),
                    level: None,
                })
            })?;
        let column = self
            .session
            .plot_series
            .columns
            .iter()
            .position(|c| c.name == watch.quantity);
        Some((watch, column))
    }

    /// The period timer's reading over the run so far: the periods found (None: fewer than
    /// two crossings) and the level crossed (None: no quantity to time).
    pub fn period_reading(&self) -> (Option<period::Periods>, Option<f64>) {
        match self.period_watch() {
            Some((watch, Some(c))) => {
                let q: Vec<f64> = self.session.plot_series.column(c).collect();
                period::periods_at(self.session.plot_series.times(), &q, watch.level)
            }
            _ => (None, None),
        }
    }

    /// The stopwatch's reading now and whether it runs: the keys', or the page's schedule
    /// while no key worked it.
    pub fn stopwatch_reading(&self) -> (f64, bool) {
        let t = self.session.snapshot.time;
        match self.page_tools().and_then(|p| p.stopwatch) {
            Some(s) if !self.ui.tools.stopwatch_used => (s.reading(t), s.running(t)),
            _ => (
                self.ui.tools.stopwatch.reading(t),
                self.ui.tools.stopwatch.running(),
            ),
        }
    }

    /// A key of the tools (see the module's table).
    pub fn tool_key(&mut self, key: ToolKey) {
        let t = self.session.snapshot.time;
        let tidy = super::settings_form::tidy;
        match key {
            ToolKey::StartStop => {
                self.ui.tools.stopwatch_shown = true;
                self.ui.tools.stopwatch_used = true;
                self.ui.tools.stopwatch.toggle(t);
                let (r, running) = self.stopwatch_reading();
                self.ui.notice = Some(if running {
                    format!("stopwatch started at t = {} s (o lap, w stop)", tidy(t))
                } else {
                    format!(
                        "stopwatch stopped at t = {} s: {} s",
                        tidy(t),
                        number_plain(r)
                    )
                });
            }
            ToolKey::Lap => {
                self.ui.tools.stopwatch_shown = true;
                if self.ui.tools.stopwatch.running() {
                    self.ui.tools.stopwatch_used = true;
                    self.ui.tools.stopwatch.lap(t);
                    let laps = self.ui.tools.stopwatch.laps();
                    let (r, split) = laps.last().copied().unwrap_or_default();
                    self.ui.notice = Some(format!(
                        "lap {} at {} s (+{} s)",
                        laps.len(),
                        number_plain(r),
                        number_plain(split)
                    ));
                } else {
                    self.ui.notice = Some("the stopwatch is stopped: w starts it".into());
                }
            }
            ToolKey::Zero => {
                self.ui.tools.stopwatch = Stopwatch::default();
                self.ui.tools.stopwatch_shown = false;
                self.ui.tools.stopwatch_used = false;
                self.ui.notice = Some("stopwatch zeroed and hidden (w starts it)".into());
            }
            ToolKey::Period => {
                self.ui.tools.period_shown = !self.ui.tools.period_shown;
                // The graphed quantity, if any (against time: its y).
                self.ui.tools.period = self.ui.plot.map(|p| Watch {
                    quantity: self.session.plot_series.columns[p.y].name.clone(),
                    level: None,
                });
                self.ui.notice = Some(match (self.ui.tools.period_shown, self.period_watch()) {
                    (true, Some((w, _))) => format!(
                        "period timer on {}: upward crossings of its mid-range (p graphs \
                         another, then T T)",
                        w.quantity
                    ),
                    (true, None) => "period timer: nothing to time in this scene".into(),
                    (false, _) => "period timer off".into(),
                });
            }
            ToolKey::RulerFrom | ToolKey::RulerTo => {
                let named = self.named_points();
                if !self.ui.tools.ruler_shown && key == ToolKey::RulerFrom {
                    self.ui.tools.ruler_shown = true;
                } else if named.is_empty() {
                    self.ui.notice = Some("no named point in this scene (a click sets one)".into());
                    return;
                } else {
                    self.ui.tools.ruler_shown = true;
                    let mut r = self.ruler();
                    let end = if key == ToolKey::RulerFrom {
                        &mut r.from
                    } else {
                        &mut r.to
                    };
                    let at = named.iter().position(|e| e.name == end.name);
                    match at {
                        // Past the last named point, `m` puts the ruler away.
                        Some(i) if i + 1 == named.len() && key == ToolKey::RulerFrom => {
                            self.ui.tools.ruler_shown = false;
                            self.ui.tools.ruler = None;
                            self.ui.notice = Some("ruler off".into());
                            return;
                        }
                        Some(i) => *end = named[(i + 1) % named.len()].clone(),
                        None => *end = named[0].clone(),
                    }
                    self.ui.tools.ruler = Some(r);
                }
                let r = self.ruler();
                self.ui.notice = Some(format!(
                    "ruler {} → {} (m: next first end, M: next second end)",
                    r.from.name, r.to.name
                ));
            }
            ToolKey::ProtractorAxis | ToolKey::ProtractorAgainst => {
                let Some(mut p) = self.protractor() else {
                    self.ui.notice = Some("no body in this scene: no axis to measure".into());
                    return;
                };
                let count = self.session.snapshot.bodies.len();
                if key == ToolKey::ProtractorAxis {
                    if !self.ui.tools.protractor_shown {
                        self.ui.tools.protractor_shown = true;
                    } else {
                        let next = p.axis.body * 3 + p.axis.axis + 1;
                        if next >= 3 * count {
                            self.ui.tools.protractor_shown = false;
                            self.ui.tools.protractor = None;
                            self.ui.notice = Some("protractor off".into());
                            return;
                        }
                        p.axis = BodyAxis {
                            body: next / 3,
                            axis: next % 3,
                        };
                        self.ui.tools.protractor = Some(p);
                    }
                } else {
                    self.ui.tools.protractor_shown = true;
                    // vertical → every axis of the other bodies → vertical.
                    let others: Vec<BodyAxis> = (0..count)
                        .filter(|&b| b != p.axis.body)
                        .flat_map(|body| (0..3).map(move |axis| BodyAxis { body, axis }))
                        .collect();
                    p.against = match p.against {
                        Reference::Vertical => others
                            .first()
                            .map_or(Reference::Vertical, |&a| Reference::Axis(a)),
                        Reference::Axis(a) => match others.iter().position(|&o| o == a) {
                            Some(i) if i + 1 < others.len() => Reference::Axis(others[i + 1]),
                            _ => Reference::Vertical,
                        },
                    };
                    self.ui.tools.protractor = Some(p);
                }
                let p = self.protractor().expect("a body");
                self.ui.notice = Some(format!(
                    "protractor {} (A: next axis, V: against what)",
                    self.protractor_title(&p)
                ));
            }
        }
    }

    /// Shows a tool as its key does (`tumble shot --tool NAME`): the stopwatch started at
    /// t = 0, the period timer of the quantity graphed (else the page's or the first), the
    /// ruler and the protractor as the page or the defaults set them.
    pub fn show_tool(&mut self, tool: PagePanel) {
        match tool {
            PagePanel::Stopwatch => {
                self.ui.tools.stopwatch_shown = true;
                self.ui.tools.stopwatch_used = true;
                self.ui.tools.stopwatch.start(0.0);
            }
            PagePanel::Period => {
                self.ui.tools.period_shown = true;
                self.ui.tools.period = self.ui.plot.map(|p| Watch {
                    quantity: self.session.plot_series.columns[p.y].name.clone(),
                    level: None,
                });
            }
            PagePanel::Ruler => self.ui.tools.ruler_shown = true,
            PagePanel::Protractor => self.ui.tools.protractor_shown = true,
            _ => {}
        }
    }

    /// Sets an end of the ruler (0: from, 1: to) from a point of the world, as a click on
    /// the drawing does: on the body nearest in the view within `reach` (m) the point moves
    /// with it, else it stays fixed in the world. The ruler is shown.
    pub fn set_ruler_end(&mut self, end: usize, p: Vector3<f64>, reach: f64) {
        let movable: Vec<bool> = self
            .session
            .snapshot
            .bodies
            .iter()
            .map(|b| !b.fixed)
            .collect();
        let point = ruler::point_at(
            p,
            &self.session.snapshot.states,
            &movable,
            Some(depth_of(self.prefs.axis)),
            reach,
        );
        let name = match point {
            Point::World(p) => ruler::world_name(&p),
            Point::Body { body, offset } => format!(
                "{}+{}",
                self.session.snapshot.bodies[body].name,
                ruler::world_name(&offset.map(|c| (c * 1e4).round() / 1e4))
            ),
        };
        let mut r = self.ruler();
        let slot = if end == 0 { &mut r.from } else { &mut r.to };
        *slot = End { point, name };
        self.ui.tools.ruler = Some(r);
        self.ui.tools.ruler_shown = true;
    }

    fn body_axis_name(&self, a: &BodyAxis) -> String {
        let name = self
            .session
            .snapshot
            .bodies
            .get(a.body)
            .map_or("?", |b| b.name.as_str());
        format!("{name}.{}", axis_name(a.axis))
    }

    fn protractor_title(&self, p: &Protractor) -> String {
        let against = match &p.against {
            Reference::Vertical => "the vertical".to_string(),
            Reference::Axis(a) => self.body_axis_name(a),
        };
        format!("{} ∠ {against}", self.body_axis_name(&p.axis))
    }

    /// The readout of a tool as a panel.
    pub fn tool_panel(&self, tool: PagePanel) -> Panel {
        let row = |label: &str, cells: Vec<String>, unit: &'static str| Row {
            label: label.to_string(),
            cells,
            unit,
        };
        match tool {
            PagePanel::Stopwatch => {
                let (reading, running) = self.stopwatch_reading();
                let scheduled = !self.ui.tools.stopwatch_used
                    && self.page_tools().and_then(|p| p.stopwatch).is_some();
                let state = match (running, scheduled) {
                    (true, false) => "running: w stops, o laps",
                    (false, false) => "stopped: w starts",
                    (true, true) => "running from the page's start",
                    (false, true) => "the page's",
                };
                let mut rows = vec![row("time", vec![number(reading)], "s")];
                if !scheduled {
                    let laps = self.ui.tools.stopwatch.laps();
                    let skip = laps.len().saturating_sub(LAPS_SHOWN);
                    for (i, (r, split)) in laps.iter().enumerate().skip(skip) {
                        rows.push(row(
                            &format!("lap {}", i + 1),
                            vec![number(*r), number(*split)],
                            "s",
                        ));
                    }
                }
                Panel {
                    title: format!("stopwatch ({state})"),
                    rows,
                }
            }
            PagePanel::Period => {
                let Some((watch, column)) = self.period_watch() else {
                    return Panel {
                        title: "period timer: nothing to time".into(),
                        rows: Vec::new(),
                    };
                };
                let Some(c) = column else {
                    return Panel {
                        title: format!("period timer: no quantity {} here", watch.quantity),
                        rows: Vec::new(),
                    };
                };
                let unit = self.session.plot_series.columns[c].unit;
                let q: Vec<f64> = self.session.plot_series.column(c).collect();
                let (found, level) =
                    period::periods_at(self.session.plot_series.times(), &q, watch.level);
                let level = level.map_or_else(String::new, |l| {
                    format!(" ↑ {} {unit}", number_plain(tidy_level(l, &q)))
                });
                let mut rows = Vec::new();
                match found {
                    Some(p) => {
                        rows.push(row("T mean", vec![number(p.mean)], "s"));
                        rows.push(row("spread", vec![number(p.spread)], "s"));
                        rows.push(row(
                            "periods",
                            vec![format!("{:>w$}", p.count, w = NUMBER_WIDTH)],
                            "",
                        ));
                    }
                    None => rows.push(row(
                        "periods",
                        vec![format!("{:>w$}", 0, w = NUMBER_WIDTH)],
                        "(two upward crossings needed)",
                    )),
                }
                Panel {
                    title: format!("period of {}{level}", watch.quantity),
                    rows,
                }
            }
            PagePanel::Ruler => {
                let r = self.ruler();
                let title = format!("ruler {} → {}", r.from.name, r.to.name);
                let rows = match r.read(&self.session.snapshot.states) {
                    Some(m) => vec![
                        row("distance", vec![number(m.distance)], "m"),
                        row("Δ", m.delta.iter().map(|&c| number(c)).collect(), "m"),
                    ],
                    None => Vec::new(),
                };
                Panel { title, rows }
            }
            _ => match self.protractor() {
                Some(p) => Panel {
                    title: format!("protractor {}", self.protractor_title(&p)),
                    rows: p
                        .degrees(&self.session.snapshot.states)
                        .map(|d| row("angle", vec![number(d)], "°"))
                        .into_iter()
                        .collect(),
                },
                None => Panel {
                    title: "protractor: no body".into(),
                    rows: Vec::new(),
                },
            },
        }
    }
}

/// The tools' keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToolKey {
    StartStop,
    Lap,
    Zero,
    Period,
    RulerFrom,
    RulerTo,
    ProtractorAxis,
    ProtractorAgainst,
}

/// A level within round-off of 0 relative to the samples' size prints as 0 (a symmetric
/// swing's mid-range is 0 to 1e-17, not "1.0e-17").
fn tidy_level(level: f64, q: &[f64]) -> f64 {
    let size = q.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if level.abs() <= 1e-12 * size {
        0.0
    } else {
        level
    }
}
