//! Contact detection, one body vertex at a time (as in the report): is the vertex inside an
//! obstacle, how deep, and which way is out? The formulas per shape; `Obstacle::inside`,
//! `Obstacle::swept` and `Obstacle::near` (`obstacle`) pick them per kind.
//!
//! ```text
//! ground  y = h:        depth = h − p.y,              n = +y
//! sphere  (c, ρ):       depth = ρ − |p − c|,          n = (p − c)/|p − c|
//! box     [min, max]:   depth = min over the 6 faces of the distance to that face,
//!                       n = the outward normal of that face (the face of least penetration)
//! plane   (o, n):       depth = n·(o − p),            n (a ramp: the ground tilted)
//! rotated box (c, R, h): the box test in the box's frame l = Rᵀ(p − c), normal turned back by R
//! ```
//!
//! # Catching fast vertices: a swept test
//!
//! A static test only sees where a vertex *is* at the end of a step. A vertex moving 50 m/s at
//! dt = 1e-2 s travels 0.5 m per step: it can jump clean over a 1 cm box (never inside at the end
//! of any step), or land past the middle of a thin box, where "least penetration" picks the far
//! face and pushes the body *through*. So the `impulse` response sweeps each vertex along its
//! motion over the step, the segment from its position in the state before the step `a` to its
//! position now `b`:
//!
//! ```text
//! s(t) = a + t (b − a),  t ∈ [0, 1]
//! sphere: |s(t) − c|² = ρ²   →  smallest root t_in          (a quadratic in t)
//! box:    slabs: per axis k, t between (minₖ − aₖ)/dₖ and (maxₖ − aₖ)/dₖ;
//!         t_in = largest entry time, entered through that axis' face; hit if t_in ≤ t_out
//! contact: the entry face (box) or the radial direction at the entry point e = s(t_in)
//!          (sphere) is the normal n; depth = n·(e − b), how far b lies beyond the entry plane
//! ```
//!
//! Why a swept test rather than sub-steps: sub-steps only shrink the distance a vertex travels
//! per test (a thin enough obstacle is still jumped), and they cost a whole integrator step
//! each; the swept test is exact for the straight segment, costs a few flops per vertex, and
//! also gives the right face when the vertex ends past the middle. The segment is straight
//! while the real vertex path is slightly curved by rotation; within one step the difference
//! is O(|ω|² dt²·r), far below the obstacle sizes of interest.
//!
//! The ground is a half-space: a vertex below the plane at the end of a step is inside it, however
//! far it travelled, so it cannot be tunnelled and needs only the static test.
//!
//! A vertex that was already inside at the start of the step (a resting contact, corrected to
//! depth 0 up to round-off) has no entry this step: it gets the static test at `b`.
//!
//! `Obstacle::near` finds the vertices just *outside* an obstacle (the `impulse` response's speculative
//! contacts): the gap to the nearest surface point and the outward normal there.

use nalgebra::{Matrix3, Vector3};

/// Where a vertex is inside an obstacle: penetration depth > 0 (m) and unit outward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Penetration {
    pub depth: f64,
    pub normal: Vector3<f64>,
}

impl Penetration {
    /// A penetration found in a turned shape's own frame, back in the world (`rotation`:
    /// shape → world).
    pub fn turned(self, rotation: &Matrix3<f64>) -> Penetration {
        Penetration {
            depth: self.depth,
            normal: rotation * self.normal,
        }
    }
}

/// The ground y = h: depth h − p.y, normal +y.
#[inline]
pub fn below_level(height: f64, p: &Vector3<f64>) -> Option<Penetration> {
    let depth = height - p.y;
    (depth > 0.0).then(|| Penetration {
        depth,
        normal: Vector3::y(),
    })
}

/// A plane through `point` with outward `normal`: depth n·(o − p).
#[inline]
pub fn behind_plane(
    point: &Vector3<f64>,
    normal: &Vector3<f64>,
    p: &Vector3<f64>,
) -> Option<Penetration> {
    let depth = normal.dot(&(point - p));
    (depth > 0.0).then_some(Penetration {
        depth,
        normal: *normal,
    })
}

/// A ball (c, ρ): depth ρ − |p − c|, normal (p − c)/|p − c| (+y at the exact centre).
#[inline]
pub fn inside_ball(center: &Vector3<f64>, radius: f64, p: &Vector3<f64>) -> Option<Penetration> {
    let offset = p - center;
    let distance = offset.norm();
    let depth = radius - distance;
    if depth <= 0.0 {
        return None;
    }
    // At the exact centre every direction is as good: take +y.
    let normal = if distance > 0.0 {
        offset / distance
    } else {
        Vector3::y()
    };
    Some(Penetration { depth, normal })
}

/// An axis-aligned box [min, max]: the face of least penetration.
#[inline]
pub fn inside_box(min: &Vector3<f64>, max: &Vector3<f64>, p: &Vector3<f64>) -> Option<Penetration> {
    let mut best = Penetration {
        depth: f64::INFINITY,
        normal: Vector3::zeros(),
    };
    for axis in 0..3 {
        let below = p[axis] - min[axis];
        let above = max[axis] - p[axis];
        if below <= 0.0 || above <= 0.0 {
            return None;
        }
        if above < best.depth {
            best = Penetration {
                depth: above,
                normal: unit(axis, 1.0),
            };
        }
        if below < best.depth {
            best = Penetration {
                depth: below,
                normal: unit(axis, -1.0),
            };
        }
    }
    Some(best)
}

/// The swept test against a ball, from `a` outside to `b` (a ≠ b): the entry point's radial
/// normal (module doc).
pub fn swept_ball(
    center: &Vector3<f64>,
    radius: f64,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> Option<Penetration> {
    // |a − c + t d|² = ρ²:  (d·d) t² + 2 (f·d) t + (f·f − ρ²) = 0,  f = a − c.
    let d = b - a;
    let f = a - center;
    let dd = d.norm_squared();
    let fd = f.dot(&d);
    let discriminant = fd * fd - dd * (f.norm_squared() - radius * radius);
    if discriminant <= 0.0 {
        return None;
    }
    let root = discriminant.sqrt();
    let (t_in, t_out) = ((-fd - root) / dd, (-fd + root) / dd);
    // `a` is outside, so both roots have the same sign: a hit needs 0 ≤ t_in ≤ 1.
    if t_in > 1.0 || t_out < 0.0 {
        return None;
    }
    let entry = a + d * t_in;
    let normal = (entry - center).normalize();
    let depth = normal.dot(&(entry - b));
    (depth > 0.0).then_some(Penetration { depth, normal })
}

/// The swept test against an axis-aligned box (slabs), from `a` outside to `b`: the entry
/// face (module doc).
pub fn swept_box(
    min: &Vector3<f64>,
    max: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> Option<Penetration> {
    let d = b - a;
    let mut t_in = f64::NEG_INFINITY;
    let mut t_out = f64::INFINITY;
    let mut normal = Vector3::zeros();
    for axis in 0..3 {
        if d[axis] == 0.0 {
            if a[axis] < min[axis] || a[axis] > max[axis] {
                return None;
            }
            continue;
        }
        let (near, far, sign) = if d[axis] > 0.0 {
            (min[axis], max[axis], -1.0)
        } else {
            (max[axis], min[axis], 1.0)
        };
        let t_near = (near - a[axis]) / d[axis];
        let t_far = (far - a[axis]) / d[axis];
        if t_near > t_in {
            t_in = t_near;
            normal = unit(axis, sign);
        }
        t_out = t_out.min(t_far);
    }
    // `a` is outside (or on the surface), so an entry within the step has 0 ≤ t_in ≤ 1.
    if t_in > t_out || !(0.0..=1.0).contains(&t_in) || normal == Vector3::zeros() {
        return None;
    }
    let entry = a + d * t_in;
    let depth = normal.dot(&(entry - b));
    (depth > 0.0).then_some(Penetration { depth, normal })
}

/// A point off a ball: its gap |p − c| − ρ and normal (None at the exact centre).
#[inline]
pub fn off_ball(
    center: &Vector3<f64>,
    radius: f64,
    p: &Vector3<f64>,
) -> Option<(f64, Vector3<f64>)> {
    let offset = p - center;
    let distance = offset.norm();
    if distance == 0.0 {
        return None;
    }
    Some((distance - radius, offset / distance))
}

/// A point off an axis-aligned box: q = clamp(p, min, max), gap |p − q|, normal (p − q)/gap
/// (None inside).
#[inline]
pub fn off_box(
    min: &Vector3<f64>,
    max: &Vector3<f64>,
    p: &Vector3<f64>,
) -> Option<(f64, Vector3<f64>)> {
    let offset = p - p.sup(min).inf(max);
    let gap = offset.norm();
    if gap == 0.0 {
        return None;
    }
    Some((gap, offset / gap))
}

/// ±1 along one axis.
fn unit(axis: usize, sign: f64) -> Vector3<f64> {
    let mut v = Vector3::zeros();
    v[axis] = sign;
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::collision::obstacle::{AlignedBox, Ground, Sphere};
    use crate::physics::collision::Obstacle;

    fn slab() -> Obstacle {
        Obstacle::AlignedBox(AlignedBox {
            min: Vector3::new(-1.0, 0.0, -1.0),
            max: Vector3::new(1.0, 0.01, 1.0),
        })
    }

    #[test]
    fn a_vertex_that_jumped_over_a_thin_box_is_caught_on_its_top_face() {
        // From 0.3 m above the 1 cm slab to 0.2 m below it: never inside at either end.
        let a = Vector3::new(0.0, 0.3, 0.0);
        let b = Vector3::new(0.0, -0.2, 0.0);
        assert!(slab().inside(&b).is_none());
        let hit = slab().swept(&a, &b).expect("the segment crosses the slab");
        assert_eq!(hit.normal, Vector3::y());
        // b is 0.01 + 0.2 = 0.21 m below the top face.
        assert!((hit.depth - 0.21).abs() < 1e-12, "depth {}", hit.depth);
    }

    #[test]
    fn a_vertex_past_the_middle_of_a_box_is_pushed_back_out_the_face_it_entered() {
        let obstacle = Obstacle::AlignedBox(AlignedBox {
            min: Vector3::new(-1.0, 0.0, -1.0),
            max: Vector3::new(1.0, 1.0, 1.0),
        });
        let a = Vector3::new(0.0, 1.1, 0.0);
        let b = Vector3::new(0.0, 0.3, 0.0);
        // Statically the bottom face is nearer (0.3 < 0.7) ...
        assert_eq!(obstacle.inside(&b).unwrap().normal, -Vector3::y());
        // ... but the vertex came in through the top: depth 1 − 0.3 = 0.7.
        let hit = obstacle.swept(&a, &b).unwrap();
        assert_eq!(hit.normal, Vector3::y());
        assert!((hit.depth - 0.7).abs() < 1e-12, "depth {}", hit.depth);
    }

    #[test]
    fn a_vertex_that_crossed_a_sphere_gets_the_normal_at_its_entry_point() {
        let obstacle = Obstacle::Sphere(Sphere {
            center: Vector3::zeros(),
            radius: 0.5,
        });
        let a = Vector3::new(0.0, 1.0, 0.0);
        let b = Vector3::new(0.0, -1.0, 0.0);
        let hit = obstacle.swept(&a, &b).unwrap();
        // Entry at (0, 0.5, 0): n = +y, b is 1.5 m below the tangent plane there.
        assert!((hit.normal - Vector3::y()).norm() < 1e-12);
        assert!((hit.depth - 1.5).abs() < 1e-12, "depth {}", hit.depth);
    }

    #[test]
    fn a_vertex_passing_beside_an_obstacle_is_not_a_contact() {
        let a = Vector3::new(1.5, 0.3, 0.0);
        let b = Vector3::new(1.5, -0.2, 0.0);
        assert!(slab().swept(&a, &b).is_none());
        let sphere = Obstacle::Sphere(Sphere {
            center: Vector3::zeros(),
            radius: 0.5,
        });
        assert!(sphere.swept(&a, &b).is_none());
    }

    #[test]
    fn the_box_normal_is_the_face_of_least_penetration() {
        let obstacle = Obstacle::AlignedBox(AlignedBox {
            min: Vector3::zeros(),
            max: Vector3::new(2.0, 1.0, 2.0),
        });
        let hit = obstacle.inside(&Vector3::new(0.05, 0.5, 1.0)).unwrap();
        assert_eq!(hit.normal, -Vector3::x());
        assert!((hit.depth - 0.05).abs() < 1e-15);
    }

    #[test]
    fn a_vertex_just_outside_gets_the_gap_and_normal_of_the_nearest_surface_point() {
        let obstacle = Obstacle::AlignedBox(AlignedBox {
            min: Vector3::zeros(),
            max: Vector3::new(1.0, 1.0, 1.0),
        });
        // Beyond the edge x = 1, y = 1 by 3e-4 and 4e-4: gap 5e-4 along (3, 4, 0)/5.
        let (gap, normal) = obstacle
            .near(&Vector3::new(1.0003, 1.0004, 0.5), 1e-3)
            .unwrap();
        assert!((gap - 5e-4).abs() < 1e-12, "gap {gap}");
        assert!(
            (normal - Vector3::new(0.6, 0.8, 0.0)).norm() < 1e-9,
            "{normal:?}"
        );
        // Farther than the margin, or inside: not near.
        assert!(obstacle
            .near(&Vector3::new(1.0, 1.002, 0.5), 1e-3)
            .is_none());
        assert!(obstacle.near(&Vector3::new(0.5, 0.5, 0.5), 1e-3).is_none());
        let sphere = Obstacle::Sphere(Sphere {
            center: Vector3::zeros(),
            radius: 0.5,
        });
        let (gap, normal) = sphere.near(&Vector3::new(0.0, 0.0, -0.5002), 1e-3).unwrap();
        assert!(
            (gap - 2e-4).abs() < 1e-12 && normal == -Vector3::z(),
            "{gap} {normal:?}"
        );
    }

    #[test]
    fn the_ground_catches_any_vertex_below_it_however_fast() {
        let ground = Obstacle::Ground(Ground { height: 0.0 });
        let hit = ground
            .swept(
                &Vector3::new(0.0, 10.0, 0.0),
                &Vector3::new(0.0, -40.0, 0.0),
            )
            .unwrap();
        assert_eq!((hit.depth, hit.normal), (40.0, Vector3::y()));
    }
}
