//! What every obstacle kind answers ([`Kind`]): one file per kind under `kinds/` implements
//! it, and [`Obstacle`] asks the kind it holds.
//!
//! Only the shape, the outline and the bounds are required: the contact falls through to the
//! shape table's pair (`shape_shape`), and the point tests to the shape table's closest point
//! (`point_shape`), with the swept test the static test at the end point (as the half-spaces
//! do). A kind may answer with its own exact formulas (`detect`'s): those of the kinds written
//! so far are what the lessons' numbers were computed with.

use super::written::{Keys, Written};
use super::{Obstacle, Outline};
use crate::physics::collision::detect::Penetration;
use crate::physics::collision::geometry::{point_shape, shape_shape, ContactPoint, Pose, Shape};
use nalgebra::Vector3;

/// An obstacle kind: a fixed shape of the shape table, its point tests, what to draw, and how
/// the scene file writes it.
pub trait Kind: Copy {
    /// The scene-file name of its type (`type = "ground"`), shown in panels and `walk`.
    const WORD: &'static str;
    /// How the scene file writes it; None when it is written as another kind (a turned box is
    /// a `box` with an `orientation`).
    const WRITTEN: Option<Written>;

    /// The obstacle from its keys (asked only of a kind that is [`WRITTEN`](Kind::WRITTEN)).
    fn build<K: Keys>(keys: &K) -> Result<Obstacle, K::Error> {
        let _ = keys;
        unreachable!("{} is written as another kind", Self::WORD)
    }

    /// Its shape and pose in the shape table.
    fn shape(&self) -> (Shape, Pose);

    /// What a front end draws (world coordinates).
    fn outline(&self) -> Outline;

    /// The corners (low, high) of a box the view must hold to show it; `centre` is where the
    /// bodies are (an unbounded obstacle is shown where they are).
    fn bounds(&self, centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>);

    /// A half-space (a vertex below it is inside however fast it came: no swept test).
    fn is_half_space(&self) -> bool {
        false
    }

    /// Appends the contact points of shape A at `pa` against it (B) to `out`.
    fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
        let (shape, pose) = self.shape();
        shape_shape(a, pa, &shape, &pose, margin, out);
    }

    /// How deep a point lies inside (0 when outside), m.
    fn depth(&self, p: &Vector3<f64>) -> f64 {
        (-table_gap(self, p).0).max(0.0)
    }

    /// Static test: is `p` inside? Depth > 0 and the outward normal.
    fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        let (gap, normal) = table_gap(self, p);
        (gap < 0.0).then_some(Penetration {
            depth: -gap,
            normal,
        })
    }

    /// Swept test: the point moved from `a` (start of the step) to `b` (now).
    fn swept(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Penetration> {
        let _ = a;
        self.inside(b)
    }

    /// The gap from `p` to the surface (< 0 inside, where a kind's formula may have none) and
    /// the outward normal there.
    fn gap(&self, p: &Vector3<f64>) -> Option<(f64, Vector3<f64>)> {
        Some(table_gap(self, p))
    }
}

/// The shape table's signed gap (< 0 inside) and outward normal at the nearest surface point
/// (`geometry::point_shape`).
pub fn table_gap<T: Kind>(kind: &T, p: &Vector3<f64>) -> (f64, Vector3<f64>) {
    let (shape, pose) = kind.shape();
    let c =
        point_shape(p, &shape, &pose, f64::INFINITY).expect("an infinite margin takes every point");
    (-c.depth, c.normal)
}
