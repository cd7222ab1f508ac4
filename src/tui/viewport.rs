//! What the projection looks at: the view axis (front x–y, side z–y, top x–z) and the region of
//! the world kept in frame, which grows (a little at a time) whenever a body or a cloth would
//! leave it,
//! and the mapping to terminal cells with the right aspect ratio (a cell is about twice as tall
//! as wide); the user's zoom (mouse wheel, keys `z` `Z`) on top of it; and the way back from a
//! terminal cell to the world ([`Viewport::world_at`]: what the mouse points at).

use crate::physics::{Body, FixedView, Obstacle, Snapshot};
use nalgebra::Vector3;
use ratatui::layout::Rect;

/// The view direction of the orthographic projection.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Looking along −z: x to the right, y up.
    Front,
    /// Looking along +x: z to the right, y up.
    Side,
    /// Looking down along −y: x to the right, z down the screen.
    Top,
}

impl Axis {
    pub fn next(self) -> Axis {
        match self {
            Axis::Front => Axis::Side,
            Axis::Side => Axis::Top,
            Axis::Top => Axis::Front,
        }
    }

    /// The view's name and screen axes.
    pub fn name(self) -> &'static str {
        match self {
            Axis::Front => "front x–y",
            Axis::Side => "side z–y",
            Axis::Top => "top x–z",
        }
    }

    /// Which way the world axes point on screen.
    pub fn legend(self) -> &'static str {
        match self {
            Axis::Front => "x→ y↑",
            Axis::Side => "z→ y↑",
            Axis::Top => "x→ z↓",
        }
    }

    /// Screen coordinates (right, up) of a world point.
    pub fn project(self, p: &Vector3<f64>) -> (f64, f64) {
        match self {
            Axis::Front => (p.x, p.y),
            Axis::Side => (p.z, p.y),
            Axis::Top => (p.x, -p.z),
        }
    }

    /// The unit vector from the scene towards the viewer (depth grows along it).
    pub fn toward_viewer(self) -> Vector3<f64> {
        match self {
            Axis::Front => Vector3::z(),
            Axis::Side => -Vector3::x(),
            Axis::Top => Vector3::y(),
        }
    }

    /// The world point with screen coordinates (right, up) = (h, v) whose coordinate along the
    /// view direction is `through`'s (the inverse of [`Axis::project`] in the plane through
    /// that point).
    pub fn unproject(self, h: f64, v: f64, through: &Vector3<f64>) -> Vector3<f64> {
        match self {
            Axis::Front => Vector3::new(h, v, through.z),
            Axis::Side => Vector3::new(through.x, v, h),
            Axis::Top => Vector3::new(h, through.y, -v),
        }
    }

    /// Whether the ground plane shows as a line (it does not from above).
    pub fn shows_ground_line(self) -> bool {
        self != Axis::Top
    }
}

/// An axis-aligned region of the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    pub min: Vector3<f64>,
    pub max: Vector3<f64>,
    /// The region grows up to this extent along each axis, then slides instead,
    /// so a body that falls for ever stays drawn at a readable size, m.
    pub max_extent: f64,
}

/// How many body diameters the view may grow to before it slides instead of zooming out.
pub const MAX_BODY_DIAMETERS: f64 = 8.0;

impl Region {
    /// The initial region: the body where it starts, the obstacles, the ground height, padded by
    /// the body's size.
    pub fn initial(body: &Body, vertices: &[Vector3<f64>], obstacles: &[Obstacle]) -> Region {
        Region::padded(body.radius, vertices, &FixedView::all(obstacles, &[]))
    }

    /// The region around `vertices` and the fixed things (obstacles, fixed bodies), padded by
    /// `pad` (at least 1 mm).
    fn padded(pad: f64, vertices: &[Vector3<f64>], fixed: &[FixedView]) -> Region {
        let mut min = Vector3::repeat(f64::INFINITY);
        let mut max = Vector3::repeat(f64::NEG_INFINITY);
        let mut add = |p: Vector3<f64>| {
            min = min.inf(&p);
            max = max.sup(&p);
        };
        for v in vertices {
            add(*v);
        }
        let centre = vertices.iter().sum::<Vector3<f64>>() / vertices.len().max(1) as f64;
        for f in fixed {
            let (low, high) = f.bounds(&centre);
            add(low);
            add(high);
        }
        let pad = if pad.is_finite() { pad.max(1e-3) } else { 1e-3 };
        let (min, max) = (min - Vector3::repeat(pad), max + Vector3::repeat(pad));
        Region {
            min,
            max,
            max_extent: (max - min).max().max(MAX_BODY_DIAMETERS * 2.0 * pad),
        }
    }

    /// The initial region of a whole world (its snapshot at t = 0): every body's vertices and
    /// every cloth's particles where they start, the obstacles, padded by the first body's
    /// radius — or, with cloths only, by a tenth of the cloths' largest extent.
    pub fn of_world(snapshot: &Snapshot) -> Region {
        let points = shown_points(snapshot);
        let pad = if let Some(body) = snapshot.bodies.first() {
            body.radius
        } else {
            let (lo, hi) = points.iter().fold(
                (
                    Vector3::repeat(f64::INFINITY),
                    Vector3::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), p| (lo.inf(p), hi.sup(p)),
            );
            0.1 * (hi - lo).max()
        };
        Region::padded(pad, &points, &snapshot.fixed)
    }

    /// Moves until every point is inside, smoothly: a side a point has crossed moves out to
    /// it plus an eighth of the region's extent (no doubling: a teacher found the picture
    /// halving in size mid-flight confusing), so a body flying out pulls the view back a
    /// little at a time. Past `max_extent` along an axis the region keeps that size and moves
    /// with the points instead — unless they are spread wider than it (several bodies flying
    /// apart), when it grows anyway: every point stays in view. It never shrinks, and a body
    /// that falls for ever stays drawn at a readable size.
    pub fn include(&mut self, points: &[Vector3<f64>]) {
        let finite = points.iter().filter(|p| p.iter().all(|c| c.is_finite()));
        let (mut lo, mut hi) = (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        );
        for p in finite {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        for i in 0..3 {
            if lo[i] > hi[i] || (hi[i] <= self.max[i] && lo[i] >= self.min[i]) {
                continue;
            }
            let extent = (self.max[i] - self.min[i]).max(1e-9);
            let margin = extent / GROWTH_MARGIN;
            let new_min = if lo[i] < self.min[i] {
                lo[i] - margin
            } else {
                self.min[i]
            };
            let new_max = if hi[i] > self.max[i] {
                hi[i] + margin
            } else {
                self.max[i]
            };
            let grown = new_max - new_min;
            if grown <= self.max_extent || hi[i] - lo[i] > self.max_extent {
                // Grows (past the largest extent only for points spread wider than it, which
                // may then stay that wide).
                self.min[i] = new_min;
                self.max[i] = new_max;
                self.max_extent = self.max_extent.max(grown);
            } else {
                // As large as it may be: that size, moved just enough (with the margin, when
                // it fits) to hold the points.
                let size = self.max_extent.max(extent);
                let margin = (0.5 * (size - (hi[i] - lo[i]))).min(margin);
                let (min, max) = if hi[i] > self.max[i] {
                    (hi[i] + margin - size, hi[i] + margin)
                } else {
                    (lo[i] - margin, lo[i] - margin + size)
                };
                self.min[i] = min;
                self.max[i] = max;
            }
        }
    }
}

/// A side the points cross moves out by an extra 1/GROWTH_MARGIN of the region's extent.
pub const GROWTH_MARGIN: f64 = 8.0;

pub use crate::session::shown_points;

/// The mapping from screen coordinates (right, up) to a grid of `cols × rows` cells.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mapping {
    /// World units per column; a row is `2 ·` this tall.
    pub scale: f64,
    /// Screen coordinates of the left edge and the top edge.
    pub left: f64,
    pub top: f64,
    pub cols: u16,
    pub rows: u16,
}

impl Mapping {
    /// The region seen along `axis`, centred in the grid, square on screen.
    pub fn fit(region: &Region, axis: Axis, cols: u16, rows: u16) -> Mapping {
        let (a0, b0) = axis.project(&region.min);
        let (a1, b1) = axis.project(&region.max);
        let (h_lo, h_hi) = (a0.min(a1), a0.max(a1));
        let (v_lo, v_hi) = (b0.min(b1), b0.max(b1));
        let c = f64::from(cols.max(1));
        let r = f64::from(rows.max(1));
        let scale = ((h_hi - h_lo) / c)
            .max((v_hi - v_lo) / (2.0 * r))
            .max(1e-12);
        let left = 0.5 * (h_lo + h_hi) - 0.5 * c * scale;
        let top = 0.5 * (v_lo + v_hi) + 0.5 * r * 2.0 * scale;
        Mapping {
            scale,
            left,
            top,
            cols,
            rows,
        }
    }

    /// Fractional cell coordinates (column, row) of screen coordinates.
    pub fn cell(&self, h: f64, v: f64) -> (f64, f64) {
        (
            (h - self.left) / self.scale,
            (self.top - v) / (2.0 * self.scale),
        )
    }

    /// Screen coordinates of fractional cell coordinates (the inverse of [`Mapping::cell`]);
    /// a cell's centre is at (column + ½, row + ½).
    pub fn screen_at(&self, col: f64, row: f64) -> (f64, f64) {
        (
            self.left + col * self.scale,
            self.top - row * 2.0 * self.scale,
        )
    }

    /// Screen coordinates of the grid's centre.
    pub fn centre(&self) -> (f64, f64) {
        self.screen_at(0.5 * f64::from(self.cols), 0.5 * f64::from(self.rows))
    }

    /// This (fitted) mapping with the user's zoom: `ZOOM_STEP^steps` times larger, its centre
    /// moved by the zoom's offset.
    pub fn zoomed(&self, zoom: &Zoom) -> Mapping {
        if *zoom == Zoom::default() {
            return *self;
        }
        let scale = self.scale / zoom.factor();
        let (h, v) = self.centre();
        let (h, v) = (h + zoom.offset.0, v + zoom.offset.1);
        Mapping {
            scale,
            left: h - 0.5 * f64::from(self.cols) * scale,
            top: v + f64::from(self.rows) * scale,
            ..*self
        }
    }

    /// Horizontal and vertical screen bounds covered by the grid.
    pub fn bounds(&self) -> ([f64; 2], [f64; 2]) {
        let right = self.left + f64::from(self.cols) * self.scale;
        let bottom = self.top - f64::from(self.rows) * 2.0 * self.scale;
        ([self.left, right], [bottom, self.top])
    }
}

/// One notch of the wheel (or `z`) draws the view this many times larger.
pub const ZOOM_STEP: f64 = 1.25;
/// The most notches out and in from the fitted view (1.25⁻⁶ ≈ 0.26×, 1.25¹⁶ ≈ 36×).
pub const ZOOM_STEPS: std::ops::RangeInclusive<i32> = -6..=16;

/// The user's zoom over the fitted view: notches of [`ZOOM_STEP`] and where it looks.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Zoom {
    /// Notches in (> 0) or out (< 0); 0 is the fitted view, whatever the offset.
    pub steps: i32,
    /// The view's centre from the fitted view's centre, screen coordinates (right, up), m.
    pub offset: (f64, f64),
}

impl Zoom {
    /// How many times larger than the fitted view things are drawn.
    pub fn factor(&self) -> f64 {
        ZOOM_STEP.powi(self.steps)
    }

    /// `notches` more (in: > 0, out: < 0), keeping the point under fractional cell `at`
    /// (column, row of the grid; None: the centre) where it is on screen. `fit` is the fitted
    /// mapping the zoom applies to. Back at 0 notches the view is the fitted one again.
    ///
    /// ```text
    /// (h, v) = the screen point under `at` before;  s' = s_fit / 1.25^steps
    /// left' = h − col·s',  top' = v + 2 row·s'      (the same cell shows the same point)
    /// offset = centre(left', top') − centre(fit)
    /// ```
    pub fn wheel(&mut self, fit: &Mapping, notches: i32, at: Option<(f64, f64)>) {
        let steps = (self.steps + notches).clamp(*ZOOM_STEPS.start(), *ZOOM_STEPS.end());
        if steps == 0 {
            *self = Zoom::default();
            return;
        }
        let before = fit.zoomed(self);
        let (cols, rows) = (f64::from(fit.cols), f64::from(fit.rows));
        let (col, row) = at.unwrap_or((0.5 * cols, 0.5 * rows));
        let (h, v) = before.screen_at(col, row);
        let scale = fit.scale / ZOOM_STEP.powi(steps);
        let centre = (
            h + (0.5 * cols - col) * scale,
            v - (0.5 * rows - row) * 2.0 * scale,
        );
        let (fh, fv) = fit.centre();
        *self = Zoom {
            steps,
            offset: (centre.0 - fh, centre.1 - fv),
        };
    }
}

/// Where the projection was last drawn: its cells on the terminal, their mapping and the view
/// axis. The way back from a terminal cell to the world (the mouse; a ruler's clicked points).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewport {
    /// The drawing's cells, terminal coordinates.
    pub area: Rect,
    pub mapping: Mapping,
    pub axis: Axis,
}

impl Viewport {
    /// Whether terminal cell (column, row) is in the drawing.
    pub fn contains(&self, col: u16, row: u16) -> bool {
        let a = self.area;
        col >= a.x && col < a.x + a.width && row >= a.y && row < a.y + a.height
    }

    /// Fractional cell coordinates in the grid of terminal cell (column, row)'s centre (outside
    /// the drawing too: the mapping goes on).
    pub fn cell_of(&self, col: u16, row: u16) -> (f64, f64) {
        (
            f64::from(col) - f64::from(self.area.x) + 0.5,
            f64::from(row) - f64::from(self.area.y) + 0.5,
        )
    }

    /// The terminal cell (column, row) a world point is drawn in (None: outside the drawing).
    pub fn terminal_cell(&self, p: &Vector3<f64>) -> Option<(u16, u16)> {
        let (h, v) = self.axis.project(p);
        let (c, r) = self.mapping.cell(h, v);
        let (w, h) = (f64::from(self.area.width), f64::from(self.area.height));
        ((0.0..w).contains(&c) && (0.0..h).contains(&r)).then(|| {
            (
                self.area.x + c.floor() as u16,
                self.area.y + r.floor() as u16,
            )
        })
    }

    /// The world point under terminal cell (column, row)'s centre in the projection plane
    /// through the origin (the coordinate along the view direction is 0); None outside the
    /// drawing.
    pub fn world_at(&self, col: u16, row: u16) -> Option<Vector3<f64>> {
        self.contains(col, row)
            .then(|| self.world_through(col, row, &Vector3::zeros()))
    }

    /// The world point under terminal cell (column, row)'s centre in the projection plane
    /// through `through` (its coordinate along the view direction kept), also outside the
    /// drawing.
    pub fn world_through(&self, col: u16, row: u16, through: &Vector3<f64>) -> Vector3<f64> {
        let (c, r) = self.cell_of(col, row);
        let (h, v) = self.mapping.screen_at(c, r);
        self.axis.unproject(h, v, through)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_at_inverts_the_projection_in_every_view() {
        // A 40 × 20 drawing at terminal (10, 5) of the unit cube region: 1/40 m per column.
        // Cell (0, 0)'s centre is (0.0125, 0.975) on screen; in the front view that is
        // x = 0.0125, y = 0.975 in the plane z = 0; from the side z and y, from above x and −z.
        let region = Region {
            min: Vector3::zeros(),
            max: Vector3::repeat(1.0),
            max_extent: 1.0,
        };
        for axis in [Axis::Front, Axis::Side, Axis::Top] {
            let view = Viewport {
                area: Rect::new(10, 5, 40, 20),
                mapping: Mapping::fit(&region, axis, 40, 20),
                axis,
            };
            let p = view.world_at(10, 5).unwrap();
            let (h, v) = axis.project(&p);
            let (h0, v0) = axis.project(&region.min);
            let (h1, v1) = axis.project(&region.max);
            assert!((h - (h0.min(h1) + 0.0125)).abs() < 1e-12, "{axis:?} {p}");
            assert!((v - (v0.max(v1) - 0.025)).abs() < 1e-12, "{axis:?} {p}");
            assert!(
                p.dot(&axis.toward_viewer()).abs() < 1e-12,
                "in the plane through 0"
            );
            assert_eq!(view.world_at(9, 5), None, "left of the drawing");
            assert_eq!(view.world_at(50, 5), None, "right of it");
        }
    }

    #[test]
    fn the_wheel_zooms_about_the_pointer_and_back_to_the_fitted_view() {
        // Two notches in at cell (10, 5) of a 40 × 20 grid: 1.5625× larger, and the screen
        // point under that cell stays under it; two notches out: the fitted view again.
        let region = Region {
            min: Vector3::zeros(),
            max: Vector3::repeat(1.0),
            max_extent: 1.0,
        };
        let fit = Mapping::fit(&region, Axis::Front, 40, 20);
        let under = fit.screen_at(10.0, 5.0);
        let mut zoom = Zoom::default();
        zoom.wheel(&fit, 1, Some((10.0, 5.0)));
        zoom.wheel(&fit, 1, Some((10.0, 5.0)));
        let m = fit.zoomed(&zoom);
        assert!((m.scale - fit.scale / 1.5625).abs() < 1e-15);
        let (c, r) = m.cell(under.0, under.1);
        assert!(
            (c - 10.0).abs() < 1e-9 && (r - 5.0).abs() < 1e-9,
            "({c}, {r})"
        );
        zoom.wheel(&fit, -2, Some((30.0, 2.0)));
        assert_eq!(zoom, Zoom::default());
        assert_eq!(fit.zoomed(&zoom), fit);
    }

    #[test]
    fn a_square_spans_twice_as_many_columns_as_rows() {
        // A 1 m × 1 m square in a 40 × 20 grid: the vertical extent (1 m over 2·20 = 40 half
        // rows) and the horizontal one (1 m over 40 columns) give the same scale 1/40 m per
        // column, so the square covers 40 columns and 20 rows.
        let region = Region {
            min: Vector3::new(0.0, 0.0, 0.0),
            max: Vector3::new(1.0, 1.0, 1.0),
            max_extent: 1.0,
        };
        let m = Mapping::fit(&region, Axis::Front, 40, 20);
        let (c0, r0) = m.cell(0.0, 0.0);
        let (c1, r1) = m.cell(1.0, 1.0);
        assert!(((c1 - c0) - 40.0).abs() < 1e-9, "columns {}", c1 - c0);
        assert!(((r0 - r1) - 20.0).abs() < 1e-9, "rows {}", r0 - r1);
    }

    #[test]
    fn the_region_grows_to_a_point_outside_plus_an_eighth_not_by_doubling() {
        // Extent 2 along y; a point at y = −3 is 2 below min = −1: min moves to it less an
        // eighth of the extent (0.25): −3.25, extent 4.25 (doubling gave −3, then 8 at the
        // next crossing). The other side and the other axes stay.
        let mut region = Region {
            min: Vector3::new(-1.0, -1.0, -1.0),
            max: Vector3::new(1.0, 1.0, 1.0),
            max_extent: 8.0,
        };
        region.include(&[Vector3::new(0.0, -3.0, 0.0)]);
        assert_eq!((region.min.y, region.max.y), (-3.25, 1.0));
        assert_eq!((region.min.x, region.max.x), (-1.0, 1.0));
        // A body crossing a little further pulls it a little further: y = −3.5 → −4.03125.
        region.include(&[Vector3::new(0.0, -3.5, 0.0)]);
        assert_eq!(region.min.y, -3.5 - 4.25 / 8.0);
    }

    #[test]
    fn points_spread_wider_than_the_region_make_it_grow_past_its_largest_extent() {
        // Extent 4 = max_extent along x, points at x = −3 and x = 5 (spread 8): a 4 m region
        // would lose one of them. It grows to both, each with its margin of 0.5: [−3.5, 5.5].
        let mut region = Region {
            min: Vector3::new(-1.0, -1.0, -1.0),
            max: Vector3::new(3.0, 1.0, 1.0),
            max_extent: 4.0,
        };
        region.include(&[Vector3::new(-3.0, 0.0, 0.0), Vector3::new(5.0, 0.0, 0.0)]);
        assert_eq!((region.min.x, region.max.x), (-3.5, 5.5));
        assert_eq!(region.max_extent, 9.0, "it may grow that far from now on");
    }

    #[test]
    fn past_its_largest_extent_the_region_moves_at_the_same_scale() {
        // Extent 4 = max_extent along y: a point at y = −5 is below min = −3; growing would
        // give extent 6.5, so the region keeps its extent 4 and moves down to hold the point
        // with its margin 0.5: [−5.5, −1.5].
        let mut region = Region {
            min: Vector3::new(-1.0, -3.0, -1.0),
            max: Vector3::new(1.0, 1.0, 1.0),
            max_extent: 4.0,
        };
        region.include(&[Vector3::new(0.0, -5.0, 0.0)]);
        assert_eq!((region.min.y, region.max.y), (-5.5, -1.5));
        assert_eq!((region.min.x, region.max.x), (-1.0, 1.0), "x untouched");
    }
}
