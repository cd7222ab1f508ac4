//! Balls and capsules against any shape: a ball is a point swept by a radius, a capsule a
//! segment swept by a radius, so both reduce to the closest surface point of the other shape B
//! to a point of their core.
//!
//! ```text
//! ball (centre c, radius ρ) against B:  q = B's surface point nearest to c, δ its signed
//!     distance (< 0: c inside B), m B's outward normal at q
//!     depth = ρ − δ,  normal = m (from B toward the ball),
//!     point = (q + (c − ρ m))/2            midway between B's surface and the ball's
//! capsule (core segment s(t) = e₀ + t (e₁ − e₀), t ∈ [0, 1], radius ρ) against B:
//!     f(t) = signed distance of s(t) to B is convex in t (the signed distance to a convex
//!     set is a convex function), so its minimum t* is found by golden-section search;
//!     the contact is the ball contact at t = 0 and t = 1 (a capsule lying along a face or a
//!     plane touches at both ends: a 2-point line contact), plus the one at t* when it lies
//!     inside the segment and is deeper than both ends (a capsule across an edge or a ball)
//! ```
//!
//! Against a plane f is linear and the two ends are the whole answer; against a ball or another
//! capsule t* is the closed-form closest point of the two cores (Ericson §5.1.9); against a
//! box, a hull or a cylinder it is searched (to 4e-10 of the length).

use super::closest::Closest;
use super::shape::{ContactPoint, Feature};
use nalgebra::Vector3;

/// The contact of a ball at `center` with radius `radius`, given B's surface point nearest to
/// the centre; None when the gap is larger than `margin`.
pub fn ball_against(
    closest: &Closest,
    center: &Vector3<f64>,
    radius: f64,
    margin: f64,
) -> Option<ContactPoint> {
    let depth = radius - closest.distance;
    (depth >= -margin).then(|| ContactPoint {
        point: (closest.point + center - closest.normal * radius) / 2.0,
        normal: closest.normal,
        depth,
        feature: Feature::Round,
    })
}

/// Golden-section search iterations: the bracket shrinks by 0.618 each, 45 give 4e-10.
const SEARCH_STEPS: usize = 45;

/// Where along a capsule's core the distance to B is least, when B's shape gives it in
/// closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Nearest {
    /// Known: the parameter t ∈ [0, 1] (against a ball or another capsule's core: the
    /// closest points of a segment and a point or segment, `segments`).
    At(f64),
    /// The distance is linear along the core (a plane): the ends are the whole answer.
    Ends,
    /// Found by golden-section search (boxes, hulls, cylinders).
    Search,
}

/// The contact points of a capsule with core `ends` and radius `radius` against the shape
/// whose closest-point query is `closest`.
pub fn capsule_against(
    ends: &(Vector3<f64>, Vector3<f64>),
    radius: f64,
    margin: f64,
    nearest: Nearest,
    closest: impl Fn(&Vector3<f64>) -> Closest,
    out: &mut Vec<ContactPoint>,
) {
    let at = |t: f64| ends.0 + (ends.1 - ends.0) * t;
    let ends_closest = [closest(&ends.0), closest(&ends.1)];
    let t_min = match nearest {
        Nearest::At(t) => t,
        Nearest::Ends => {
            for (end, c) in [ends.0, ends.1].iter().zip(&ends_closest) {
                out.extend(ball_against(c, end, radius, margin));
            }
            return;
        }
        Nearest::Search => golden_section(&|t| closest(&at(t)).distance),
    };
    let middle = closest(&at(t_min));
    // Deeper than both ends by more than round-off: a contact in the middle of the segment.
    let tolerance = 1e-9 * (1.0 + radius);
    let ends_distance = ends_closest[0].distance.min(ends_closest[1].distance);
    if middle.distance < ends_distance - tolerance {
        out.extend(ball_against(&middle, &at(t_min), radius, margin));
        return;
    }
    for (end, c) in [ends.0, ends.1].iter().zip(&ends_closest) {
        out.extend(ball_against(c, end, radius, margin));
    }
}

/// The minimiser on [0, 1] of a convex function, by golden-section search.
fn golden_section(f: &dyn Fn(f64) -> f64) -> f64 {
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (0.0, 1.0);
    let (mut x1, mut x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..SEARCH_STEPS {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - ratio * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + ratio * (hi - lo);
            f2 = f(x2);
        }
    }
    (lo + hi) / 2.0
}
