//! The point of a convex polyhedron's surface closest to a point p, and on which side p lies.
//!
//! ```text
//! box (centre c, axes R, half-extents h):  local l = Rᵀ(p − c)
//!   outside (some |lₖ| > hₖ):  q = c + R clamp(l, −h, h),  distance = |p − q|,
//!                              normal = (p − q)/|p − q|
//!   inside:  the face of least depth k = argmin (hₖ − |lₖ|), normal = sign(lₖ) R eₖ,
//!            q = p + (hₖ − |lₖ|) normal,  distance = −(hₖ − |lₖ|)
//! hull: heights hᵢ = nᵢ·p − dᵢ over the faces
//!   all hᵢ ≤ 0 (inside): the face of largest hᵢ, q = p − hᵢ nᵢ, distance = hᵢ, normal = nᵢ
//!   else: over the faces with hᵢ > 0, the projection p − hᵢ nᵢ if it falls inside the face,
//!         otherwise the closest point of the face's edges; the nearest of these is q
//! ```

use super::polyhedron::{BoxView, Polygon, Polyhedron};
use super::segments::closest_points;
use super::shape::Pose;
use nalgebra::Vector3;

/// The surface point nearest to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closest {
    /// The nearest surface point, world frame.
    pub point: Vector3<f64>,
    /// Unit normal out of the shape at `point` (toward the query point when it is outside).
    pub normal: Vector3<f64>,
    /// Signed distance of the query point: > 0 outside, < 0 inside, m.
    pub distance: f64,
}

/// Closest surface point of a box (closed form).
pub fn closest_on_box(view: &BoxView, p: &Vector3<f64>) -> Closest {
    let local = view.axes.tr_mul(&(p - view.center));
    let clamped = local.zip_map(&view.half, |l, h| l.clamp(-h, h));
    if clamped != local {
        let q = view.center + view.axes * clamped;
        let distance = (p - q).norm();
        return Closest {
            point: q,
            normal: (p - q) / distance,
            distance,
        };
    }
    let room = view.half - local.abs();
    let k = room.imin();
    let sign = if local[k] >= 0.0 { 1.0 } else { -1.0 };
    let normal = view.axes.column(k) * sign;
    Closest {
        point: p + normal * room[k],
        normal,
        distance: -room[k],
    }
}

/// Closest surface point of any convex polyhedron (by faces).
pub fn closest_on_polyhedron(shape: &impl Polyhedron, p: &Vector3<f64>) -> Closest {
    let mut inside = (f64::NEG_INFINITY, Vector3::zeros());
    let mut nearest: Option<(f64, Vector3<f64>)> = None;
    let mut polygon = Polygon::new();
    for i in 0..shape.face_count() {
        let (n, d) = shape.face_plane(i);
        let h = n.dot(p) - d;
        if h > inside.0 {
            inside = (h, n);
        }
        if h <= 0.0 {
            continue;
        }
        shape.face_polygon(i, &mut polygon);
        let projection = p - n * h;
        let m = polygon.len();
        let within = (0..m).all(|j| {
            let (v, w) = (polygon[j], polygon[(j + 1) % m]);
            (w - v).cross(&n).dot(&(projection - v)) <= 0.0
        });
        let mut consider = |q: Vector3<f64>| {
            let dist = (p - q).norm();
            if nearest.is_none_or(|(best, _)| dist < best) {
                nearest = Some((dist, q));
            }
        };
        if within {
            consider(projection);
        } else {
            for j in 0..m {
                consider(closest_points(&polygon[j], &polygon[(j + 1) % m], p, p).0);
            }
        }
    }
    match nearest {
        Some((distance, q)) if inside.0 > 0.0 => Closest {
            point: q,
            normal: (p - q) / distance,
            distance,
        },
        _ => Closest {
            point: p - inside.1 * inside.0,
            normal: inside.1,
            distance: inside.0,
        },
    }
}

/// Closest surface point of a ball (centre c, radius ρ): q = c + ρ u, u = (p − c)/|p − c|,
/// distance |p − c| − ρ (at the exact centre u = +y).
pub fn closest_on_ball(center: &Vector3<f64>, radius: f64, p: &Vector3<f64>) -> Closest {
    let offset = p - center;
    let d = offset.norm();
    let normal = if d > 0.0 { offset / d } else { Vector3::y() };
    Closest {
        point: center + normal * radius,
        normal,
        distance: d - radius,
    }
}

/// Closest surface point of a capsule: the ball of radius ρ about the point s of its core
/// segment nearest to p. An exact point on the core gets the normal of the body x axis.
pub fn closest_on_capsule(
    ends: &(Vector3<f64>, Vector3<f64>),
    side: &Vector3<f64>,
    radius: f64,
    p: &Vector3<f64>,
) -> Closest {
    let s = closest_points(&ends.0, &ends.1, p, p).0;
    if (p - s).norm() == 0.0 {
        return Closest {
            point: s + side * radius,
            normal: *side,
            distance: -radius,
        };
    }
    closest_on_ball(&s, radius, p)
}

/// Closest surface point of a cylinder (radius ρ, half-length h along the body y axis) at
/// `pose`: local l = Rᵀ(p − x), radial distance ϱ = √(lx² + lz²).
///
/// ```text
/// outside (ϱ > ρ or |ly| > h):  q = (l_radial · min(1, ρ/ϱ), clamp(ly, −h, h)), normal (l − q)/|l − q|
/// inside: the nearer of the side (room ρ − ϱ, normal radial) and the end cap (room h − |ly|,
///         normal ±y)
/// ```
pub fn closest_on_cylinder(pose: &Pose, radius: f64, half: f64, p: &Vector3<f64>) -> Closest {
    let l = pose.rotation.tr_mul(&(p - pose.position));
    let rho = l.x.hypot(l.z);
    let radial = if rho > 0.0 {
        Vector3::new(l.x / rho, 0.0, l.z / rho)
    } else {
        Vector3::x()
    };
    let world = |v: Vector3<f64>| pose.rotation * v;
    if rho > radius || l.y.abs() > half {
        let q = radial * rho.min(radius) + Vector3::y() * l.y.clamp(-half, half);
        let distance = (l - q).norm();
        return Closest {
            point: pose.to_world(&q),
            normal: world((l - q) / distance),
            distance,
        };
    }
    let side = radius - rho;
    let cap = half - l.y.abs();
    if side < cap {
        Closest {
            point: pose.to_world(&(l + radial * side)),
            normal: world(radial),
            distance: -side,
        }
    } else {
        let up = Vector3::y() * l.y.signum();
        Closest {
            point: pose.to_world(&(l + up * cap)),
            normal: world(up),
            distance: -cap,
        }
    }
}

/// Closest surface point of the half-space behind the plane through `origin` with unit outward
/// normal n: height h = n·(p − origin), q = p − h n.
pub fn closest_on_plane(origin: &Vector3<f64>, normal: &Vector3<f64>, p: &Vector3<f64>) -> Closest {
    let h = normal.dot(&(p - origin));
    Closest {
        point: p - normal * h,
        normal: *normal,
        distance: h,
    }
}
