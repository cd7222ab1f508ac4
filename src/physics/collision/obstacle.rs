//! Obstacles: the scene's fixed things (`[[obstacle]]`), each a static body of the one shape
//! table — described here, in this one place, kind by kind.
//!
//! An obstacle is a shape of the contact geometry's table at a fixed pose ([`Obstacle::shape`]):
//! it never moves, takes no impulse, and enters the solvers as a static solver body
//! (`constraints::solver_body`: inverse mass and inertia zero). Everything the engine asks of an
//! obstacle goes through the methods below, so a new kind is one variant and one arm in each:
//!
//! | method | who asks | what |
//! |---|---|---|
//! | [`kind`](Obstacle::kind) | panels, labels | the scene-file name |
//! | [`shape`](Obstacle::shape) | the contact geometry, sweeps | its shape and pose in the shape table |
//! | [`contact`](Obstacle::contact) | bodies' detection, measured penetration | contact points of a body's shape against it |
//! | [`inside`](Obstacle::inside), [`near`](Obstacle::near), [`swept`](Obstacle::swept), [`depth`](Obstacle::depth) | vertices (`seed`, `impulse`), cloth particles | the report's point tests (`detect`) |
//! | [`outline`](Obstacle::outline), [`bounds`](Obstacle::bounds) | front ends, through the snapshot | what to draw, the region to show |
//!
//! The shape table answers for any kind whose shape is in it: the contact falls through to
//! `shape_shape`, and [`table_inside`](Obstacle::table_inside) and
//! [`table_near`](Obstacle::table_near) answer the point tests from `point_shape` (a swept
//! test can fall back to `inside` at the end point, as the half-spaces do). The kinds below
//! answer the point tests and some contacts with their own exact formulas (`detect`'s; the
//! ground's and the aligned box's contact without a pose): those are what the lessons'
//! numbers were computed with, and they keep a box's faces at its written `min` and `max` to
//! the last bit (its pose, centre ± half, is off by round-off), and the swept test's entry
//! face. A test checks that the two answers agree to round-off.
//!
//! A new kind: its variant and an arm in each method here; `scene` reads its keys (the scene
//! file's words `type`, `height`, `center`, … are read there, not here).

use super::detect::{self, Penetration};
use super::geometry::{
    closest_point, obstacles, point_shape, polyhedra, polyhedron::BoxView, polyhedron::HullView,
    shape_shape, ContactPoint, Pose, Shape,
};
use crate::physics::body::{box_corners, box_edges};
use nalgebra::{Matrix3, Vector3};

/// A fixed obstacle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    /// The plane y = `height`; everything below is solid.
    Ground { height: f64 },
    /// A fixed sphere.
    Sphere { center: Vector3<f64>, radius: f64 },
    /// A fixed axis-aligned box.
    Box {
        min: Vector3<f64>,
        max: Vector3<f64>,
    },
    /// An infinite fixed plane through `point` with unit outward `normal`; everything behind
    /// it is solid (a ramp).
    Plane {
        point: Vector3<f64>,
        normal: Vector3<f64>,
    },
    /// A fixed box turned about its centre: half-extents `half` along the columns of
    /// `rotation` (box → world). A box obstacle written without `orientation` stays a [`Box`].
    ///
    /// [`Box`]: Obstacle::Box
    RotatedBox {
        center: Vector3<f64>,
        half: Vector3<f64>,
        rotation: Matrix3<f64>,
    },
}

/// What a front end draws for an obstacle (`Obstacle::outline`), in world coordinates.
#[derive(Debug, Clone, PartialEq)]
pub enum Outline {
    /// The ground: the level y = height (a line in a view that shows the vertical).
    Level(f64),
    /// An infinite plane: its trace across the view.
    Plane {
        point: Vector3<f64>,
        normal: Vector3<f64>,
    },
    /// A ball: a circle in every view.
    Ball { center: Vector3<f64>, radius: f64 },
    /// An axis-aligned box: a rectangle between its two corners in every axis view.
    Aligned {
        min: Vector3<f64>,
        max: Vector3<f64>,
    },
    /// A wire frame: corners and the edges between them (corner indices).
    Wire {
        corners: Vec<Vector3<f64>>,
        edges: Vec<(usize, usize)>,
    },
}

impl Obstacle {
    /// The scene-file name of this obstacle's type.
    pub fn kind(&self) -> &'static str {
        match self {
            Obstacle::Ground { .. } => "ground",
            Obstacle::Sphere { .. } => "sphere",
            Obstacle::Box { .. } | Obstacle::RotatedBox { .. } => "box",
            Obstacle::Plane { .. } => "plane",
        }
    }

    /// Whether the obstacle is a half-space (ground, plane): a vertex below it is inside
    /// however fast it came, so it needs no swept test.
    pub fn is_half_space(&self) -> bool {
        matches!(self, Obstacle::Ground { .. } | Obstacle::Plane { .. })
    }

    /// The obstacle as a static body of the shape table: its shape and where it is. The ground
    /// and planes are [`Shape::Plane`], the sphere a [`Shape::Ball`], boxes a [`Shape::Box`].
    pub fn shape(&self) -> (Shape, Pose) {
        match *self {
            Obstacle::Ground { height } => (
                Shape::Plane {
                    normal: Vector3::y(),
                },
                Pose::at(Vector3::new(0.0, height, 0.0)),
            ),
            Obstacle::Plane { point, normal } => (Shape::Plane { normal }, Pose::at(point)),
            Obstacle::Sphere { center, radius } => (Shape::Ball { radius }, Pose::at(center)),
            Obstacle::Box { min, max } => (
                Shape::Box {
                    half: (max - min) / 2.0,
                },
                Pose::at((min + max) / 2.0),
            ),
            Obstacle::RotatedBox {
                center,
                half,
                rotation,
            } => (
                Shape::Box { half },
                Pose {
                    position: center,
                    rotation,
                },
            ),
        }
    }

    /// Appends the contact points of shape A at `pa` against the obstacle (B) to `out`: the
    /// shape table's pair (`geometry::shape_shape`), or the ground's and the aligned box's
    /// own (no pose to build).
    pub fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
        match (*self, a) {
            (Obstacle::Ground { height }, Shape::Box { half }) => {
                obstacles::against_ground(&BoxView::new(half, pa), height, margin, out)
            }
            (Obstacle::Ground { height }, Shape::Hull(hull)) => {
                obstacles::against_ground(&HullView { hull, pose: pa }, height, margin, out)
            }
            (Obstacle::Sphere { center, radius }, Shape::Box { .. } | Shape::Hull(_)) => {
                let closest = closest_point(a, pa, &center);
                out.extend(obstacles::against_sphere(&closest, &center, radius, margin));
            }
            (Obstacle::Box { min, max }, Shape::Box { half }) => polyhedra::box_box(
                &BoxView::new(half, pa),
                &BoxView::aligned(&min, &max),
                margin,
                out,
            ),
            (Obstacle::Box { min, max }, Shape::Hull(hull)) => polyhedra::contact(
                &HullView { hull, pose: pa },
                &BoxView::aligned(&min, &max),
                margin,
                out,
            ),
            _ => {
                let (shape, pose) = self.shape();
                shape_shape(a, pa, &shape, &pose, margin, out);
            }
        }
    }

    /// How deep a point lies inside the obstacle (0 when outside), m.
    pub fn depth(&self, p: &Vector3<f64>) -> f64 {
        match *self {
            Obstacle::Ground { height } => (height - p.y).max(0.0),
            Obstacle::Sphere { center, radius } => (radius - (p - center).norm()).max(0.0),
            Obstacle::Box { min, max } => {
                let inside = (p - min).inf(&(max - p));
                inside.min().max(0.0)
            }
            Obstacle::Plane { point, normal } => normal.dot(&(point - p)).max(0.0),
            Obstacle::RotatedBox {
                center,
                half,
                rotation,
            } => {
                let local = rotation.tr_mul(&(p - center));
                (half - local.abs()).min().max(0.0)
            }
        }
    }

    /// Static test (`detect`): is `p` inside? Depth > 0 and the outward normal.
    #[inline]
    pub fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        match *self {
            Obstacle::Ground { height } => detect::below_level(height, p),
            Obstacle::Sphere { center, radius } => detect::inside_ball(&center, radius, p),
            Obstacle::Box { min, max } => detect::inside_box(&min, &max, p),
            Obstacle::Plane { point, normal } => detect::behind_plane(&point, &normal, p),
            Obstacle::RotatedBox {
                center,
                half,
                rotation,
            } => detect::inside_box(&-half, &half, &rotation.tr_mul(&(p - center)))
                .map(|hit| hit.turned(&rotation)),
        }
    }

    /// Swept test (`detect`): the point moved from `a` (start of the step) to `b` (now). The
    /// contact through the entry face if the segment entered within the step and `b` lies
    /// beyond the entry plane; the static test at `b` if it was already inside at `a`.
    pub fn swept(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Penetration> {
        match *self {
            Obstacle::Ground { .. } | Obstacle::Plane { .. } => self.inside(b),
            Obstacle::Sphere { center, radius } => {
                // Inside at the start, or not moved: the static test.
                if self.depth(a) > 0.0 || (b - a).norm_squared() == 0.0 {
                    return self.inside(b);
                }
                detect::swept_ball(&center, radius, a, b)
            }
            Obstacle::Box { min, max } => {
                if self.depth(a) > 0.0 {
                    return self.inside(b);
                }
                detect::swept_box(&min, &max, a, b)
            }
            Obstacle::RotatedBox {
                center,
                half,
                rotation,
            } => {
                // The box test in the box's own frame, the normal turned back.
                let local = Obstacle::Box {
                    min: -half,
                    max: half,
                };
                let to_local = |x: &Vector3<f64>| rotation.tr_mul(&(x - center));
                (local.swept(&to_local(a), &to_local(b))).map(|hit| hit.turned(&rotation))
            }
        }
    }

    /// A point just *outside* (`detect`), less than `margin` from the surface: the gap ≥ 0 (m)
    /// and the outward normal of the nearest surface point. None inside or farther.
    #[inline]
    pub fn near(&self, p: &Vector3<f64>, margin: f64) -> Option<(f64, Vector3<f64>)> {
        let (gap, normal) = match *self {
            Obstacle::Ground { height } => (p.y - height, Vector3::y()),
            Obstacle::Sphere { center, radius } => detect::off_ball(&center, radius, p)?,
            Obstacle::Box { min, max } => detect::off_box(&min, &max, p)?,
            Obstacle::Plane { point, normal } => (normal.dot(&(p - point)), normal),
            Obstacle::RotatedBox {
                center,
                half,
                rotation,
            } => {
                let l = rotation.tr_mul(&(p - center));
                let (gap, n) = detect::off_box(&-half, &half, &l)?;
                (gap, rotation * n)
            }
        };
        (gap >= 0.0 && gap < margin).then_some((gap, normal))
    }

    /// The shape table's answer to [`inside`](Obstacle::inside) and
    /// [`near`](Obstacle::near) together: the signed gap (< 0 inside) and the outward normal
    /// at the nearest surface point (`geometry::point_shape`). What a kind without its own
    /// point formulas would use; the kinds above agree with it to round-off (tests).
    pub fn table_gap(&self, p: &Vector3<f64>) -> (f64, Vector3<f64>) {
        let (shape, pose) = self.shape();
        let c = point_shape(p, &shape, &pose, f64::INFINITY)
            .expect("an infinite margin takes every point");
        (-c.depth, c.normal)
    }

    /// The shape table's static test: inside when the signed gap is negative.
    pub fn table_inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        let (gap, normal) = self.table_gap(p);
        (gap < 0.0).then_some(Penetration {
            depth: -gap,
            normal,
        })
    }

    /// The shape table's near test: outside, closer than `margin`.
    pub fn table_near(&self, p: &Vector3<f64>, margin: f64) -> Option<(f64, Vector3<f64>)> {
        let (gap, normal) = self.table_gap(p);
        (gap >= 0.0 && gap < margin).then_some((gap, normal))
    }

    /// What a front end draws (world coordinates; read through the snapshot).
    pub fn outline(&self) -> Outline {
        match *self {
            Obstacle::Ground { height } => Outline::Level(height),
            Obstacle::Plane { point, normal } => Outline::Plane { point, normal },
            Obstacle::Sphere { center, radius } => Outline::Ball { center, radius },
            Obstacle::Box { min, max } => Outline::Aligned { min, max },
            Obstacle::RotatedBox {
                center,
                half,
                rotation,
            } => Outline::Wire {
                corners: (box_corners(half * 2.0).iter())
                    .map(|c| center + rotation * c)
                    .collect(),
                edges: box_edges(),
            },
        }
    }

    /// The corners (low, high) of a box the view must hold to show the obstacle; `centre` is
    /// where the bodies are (an unbounded obstacle is shown where they are).
    pub fn bounds(&self, centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        match *self {
            Obstacle::Ground { height } => {
                let p = Vector3::new(centre.x, height, centre.z);
                (p, p)
            }
            Obstacle::Sphere { center, radius } => (
                center - Vector3::repeat(radius),
                center + Vector3::repeat(radius),
            ),
            Obstacle::Box { min, max } => (min, max),
            Obstacle::Plane { point, .. } => (point, point),
            Obstacle::RotatedBox { center, half, .. } => (
                center - Vector3::repeat(half.norm()),
                center + Vector3::repeat(half.norm()),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    fn all() -> Vec<Obstacle> {
        vec![
            Obstacle::Ground { height: 0.25 },
            Obstacle::Sphere {
                center: Vector3::new(0.1, 0.2, -0.3),
                radius: 0.7,
            },
            Obstacle::Box {
                min: Vector3::new(-0.5, -0.25, -1.0),
                max: Vector3::new(0.75, 0.5, 0.3),
            },
            Obstacle::Plane {
                point: Vector3::new(0.0, 0.1, 0.0),
                normal: Vector3::new(-0.3, 1.0, 0.2).normalize(),
            },
            Obstacle::RotatedBox {
                center: Vector3::new(0.2, 0.1, 0.0),
                half: Vector3::new(0.5, 0.2, 0.4),
                rotation: Rotation3::from_axis_angle(&Vector3::z_axis(), 0.4).into_inner(),
            },
        ]
    }

    /// Points on a grid around the obstacles (none exactly on a face, edge or centre).
    fn points() -> Vec<Vector3<f64>> {
        let mut out = Vec::new();
        for i in 0..9 {
            for j in 0..9 {
                for k in 0..9 {
                    let at = |n: i32| -1.03 + 0.257 * n as f64;
                    out.push(Vector3::new(at(i), at(j) + 0.011, at(k) - 0.007));
                }
            }
        }
        out
    }

    #[test]
    fn every_kind_answers_as_its_static_body_in_the_shape_table() {
        // The exact point tests against the shape table's closest point: inside (depth and
        // normal), near (gap and normal) and depth agree to round-off.
        for o in all() {
            let (mut inside, mut outside) = (0, 0);
            for p in points() {
                match (o.inside(&p), o.table_inside(&p)) {
                    (Some(hit), Some(table)) => {
                        inside += 1;
                        assert!((hit.depth - table.depth).abs() < 1e-12, "{o:?} {p:?}");
                        assert!((hit.normal - table.normal).norm() < 1e-9, "{o:?} {p:?}");
                        assert!((o.depth(&p) - hit.depth).abs() < 1e-12);
                    }
                    (None, None) => {
                        outside += 1;
                        assert_eq!(o.depth(&p), 0.0);
                        let (g, n) = o.near(&p, f64::INFINITY).expect("outside is near");
                        let (tg, tn) = o.table_near(&p, f64::INFINITY).expect("and in the table");
                        assert!((g - tg).abs() < 1e-12, "{o:?} {p:?}");
                        assert!((n - tn).norm() < 1e-9, "{o:?} {p:?}");
                    }
                    (mine, table) => panic!("{o:?} at {p:?}: {mine:?} against {table:?}"),
                }
            }
            // Both sides of every kind's surface were tried.
            assert!(
                inside > 10 && outside > 10,
                "{o:?}: {inside} in, {outside} out"
            );
        }
    }

    #[test]
    fn a_half_space_is_a_plane_of_the_shape_table_and_nothing_else_is() {
        let half: Vec<bool> = all().iter().map(Obstacle::is_half_space).collect();
        assert_eq!(half, [true, false, false, true, false]);
    }
}
