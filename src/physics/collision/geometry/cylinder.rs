//! A cylinder against a box, a hull or another cylinder: GJK/EPA (`gjk`) gives the normal,
//! then the manifold is built from the flat features that meet, by clipping as for two
//! polyhedra (`clip`).
//!
//! ```text
//! 1. GJK/EPA: normal n (B → A), depth; None when apart by more than the margin
//! 2. a reference face, when n lies within 0.8° (1 − n·m ≤ 1e-4) of a flat face's normal m:
//!      B's face most along +n (a box or hull face; B's cap, for a cylinder), else
//!      A's cap facing −n (a cylinder's end: the rim's regular octagon, m = ±a)
//!    the incident features of the other shape, toward the reference face:
//!      a polyhedron: its face most anti-parallel to m
//!      a cylinder (axis a, radius ρ, u = the unit part of −m across a, w = a × u):
//!        its lower rim, an octagon k + ρ (cos θⱼ u + sin θⱼ w), θⱼ = jπ/4, and
//!        its lowest generator, the segment x ± h a + ρ u
//!    each clipped to the reference face's prism; points with depth = d − m·p ≥ −margin kept,
//!    thinned to 4; point = p + (depth/2) m
//!    so: lying on a face, the generator gives 2 points; standing, the rim 4; tilted, 1
//! 3. two cylinders side by side (both axes across n, parallel within 0.8°): the two lowest
//!    generators, A's clipped to B's extent along the axis: 2 points
//! 4. otherwise one point: midway between GJK/EPA's witness points
//! ```
//!
//! The octagon stands for the round end: as a reference face it is the inscribed octagon
//! (a shape resting on an end within ρ(1 − cos 22.5°) = 0.076 ρ of its rim finds no point there).

use super::clip::{clip_to_face, reduce_to_four};
use super::gjk::{separation, CylinderView, Separation, Support};
use super::polygon::CAPACITY;
use super::polyhedron::{Polygon, Polyhedron};
use super::segments::closest_points;
use super::shape::{ContactPoint, Feature};
use nalgebra::Vector3;

type V = Vector3<f64>;

/// Flat features closer than this to the normal (1 − cos) are faces in contact: 0.8°.
const ALIGNED: f64 = 1e-4;
/// Points on a rim octagon.
const RIM: usize = 8;

/// A cylinder (A) against a box or a hull (B).
pub fn cylinder_polyhedron<P: Polyhedron + Support>(
    c: &CylinderView,
    p: &P,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    let Some(sep) = separation(c, p, margin) else {
        return;
    };
    let n = sep.normal;
    let face = p.incident_face(&-n);
    let (m, d) = p.face_plane(face);
    let along_b = m.dot(&n);
    let along_a = c.axis().dot(&n).abs();
    if 1.0 - along_b <= ALIGNED && along_b >= along_a {
        let mut reference = Polygon::new();
        p.face_polygon(face, &mut reference);
        let incident = lower_features(c, &m);
        if face_manifold(&m, d, &reference, &incident, true, margin, out) {
            return;
        }
    } else if 1.0 - along_a <= ALIGNED {
        let (m, d, reference) = cap(c, &-n);
        let mut incident = Polygon::new();
        p.face_polygon(p.incident_face(&m), &mut incident);
        if face_manifold(&m, d, &reference, &[incident], false, margin, out) {
            return;
        }
    }
    single(&sep, out);
}

/// Two cylinders.
pub fn cylinder_cylinder(
    a: &CylinderView,
    b: &CylinderView,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    let Some(sep) = separation(a, b, margin) else {
        return;
    };
    let n = sep.normal;
    let along_a = a.axis().dot(&n).abs();
    let along_b = b.axis().dot(&n).abs();
    if 1.0 - along_b <= ALIGNED && along_b >= along_a {
        let (m, d, reference) = cap(b, &n);
        if face_manifold(&m, d, &reference, &lower_features(a, &m), true, margin, out) {
            return;
        }
    } else if 1.0 - along_a <= ALIGNED {
        let (m, d, reference) = cap(a, &-n);
        if face_manifold(
            &m,
            d,
            &reference,
            &lower_features(b, &m),
            false,
            margin,
            out,
        ) {
            return;
        }
    } else if along_a <= ALIGNED.sqrt()
        && along_b <= ALIGNED.sqrt()
        && 1.0 - a.axis().dot(&b.axis()).abs() <= ALIGNED
        && side_by_side(a, b, &n, margin, out)
    {
        return;
    }
    single(&sep, out);
}

/// The one-point contact from the witness points.
fn single(sep: &Separation, out: &mut Vec<ContactPoint>) {
    out.push(ContactPoint {
        point: (sep.on_a + sep.on_b) / 2.0,
        normal: sep.normal,
        depth: sep.depth,
        feature: Feature::Round,
    });
}

/// The end of `c` facing `toward`: outward normal m = ±a, offset d (the cap lies in m·p = d)
/// and its rim octagon, counter-clockwise seen from outside.
fn cap(c: &CylinderView, toward: &V) -> (V, f64, Polygon) {
    let a = c.axis();
    let (x, z) = (c.rotation.column(0).into_owned(), c.rotation.column(2));
    let (m, e1, e2) = if a.dot(toward) >= 0.0 {
        (a, z.into_owned(), x)
    } else {
        (-a, x, z.into_owned())
    };
    let k = c.center + m * c.half;
    (m, m.dot(&k), octagon(&k, &e1, &e2, c.radius))
}

/// k + ρ (cos θⱼ e₁ + sin θⱼ e₂), θⱼ = jπ/4.
fn octagon(k: &V, e1: &V, e2: &V, radius: f64) -> Polygon {
    (0..RIM)
        .map(|j| {
            let t = j as f64 * std::f64::consts::TAU / RIM as f64;
            k + (e1 * t.cos() + e2 * t.sin()) * radius
        })
        .collect()
}

/// The features of `c` facing a reference face of outward normal `m` (pointing at `c`): its
/// lower rim octagon and its lowest generator.
fn lower_features(c: &CylinderView, m: &V) -> [Polygon; 2] {
    let a = c.axis();
    let sign = if a.dot(m) < 0.0 { 1.0 } else { -1.0 };
    let u = c.across(&-m).unwrap_or(c.rotation.column(0).into_owned());
    let w = a.cross(&u);
    let rim = octagon(&(c.center + a * (sign * c.half)), &u, &w, c.radius);
    let foot = c.center + u * c.radius;
    let mut generator = Polygon::new();
    generator.extend([foot - a * c.half, foot + a * c.half]);
    [rim, generator]
}

/// Clips the incident polygons to the reference face (normal `m`, offset `d`, loop
/// `reference`) and appends the points within the margin, thinned to 4. False when none.
fn face_manifold(
    m: &V,
    d: f64,
    reference: &Polygon,
    incident: &[Polygon],
    reference_is_b: bool,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) -> bool {
    let mut points = Polygon::new();
    let mut depths = [0.0; CAPACITY];
    let mut scratch = Polygon::new();
    for polygon in incident {
        let mut clipped = *polygon;
        clip_to_face(&mut clipped, &mut scratch, reference, m);
        for q in clipped.iter() {
            let depth = d - m.dot(q);
            // A segment clipped as a polygon repeats its cut point: keep each point once.
            let seen = points.iter().any(|p| (p - q).norm_squared() < 1e-24);
            if depth >= -margin && !seen && points.len() < CAPACITY {
                depths[points.len()] = depth;
                points.push(*q);
            }
        }
    }
    if points.is_empty() {
        return false;
    }
    let count = points.len();
    reduce_to_four(&mut points, &mut depths[..count], m);
    let normal = if reference_is_b { *m } else { -m };
    out.extend(points.iter().zip(&depths).map(|(p, &depth)| ContactPoint {
        point: p + m * (depth / 2.0),
        normal,
        depth,
        feature: Feature::Round,
    }));
    true
}

/// Two parallel cylinders touching along their sides: A's lowest generator (toward −n)
/// clipped to the extent of B's highest (toward +n), a point at each end of the overlap.
fn side_by_side(
    a: &CylinderView,
    b: &CylinderView,
    n: &V,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) -> bool {
    let t = a.axis();
    let (Some(ua), Some(ub)) = (a.across(&-n), b.across(n)) else {
        return false;
    };
    let a0 = a.center - t * a.half + ua * a.radius;
    let bb = b.center + ub * b.radius;
    let (b0, b1) = (bb - b.axis() * b.half, bb + b.axis() * b.half);
    let (s0, s1) = ((b0 - a0).dot(&t), (b1 - a0).dot(&t));
    let lo = s0.min(s1).max(0.0);
    let hi = s0.max(s1).min(2.0 * a.half);
    if hi - lo <= 1e-9 * (1.0 + a.half) {
        return false;
    }
    let first = out.len();
    for s in [lo, hi] {
        let pa = a0 + t * s;
        let pb = closest_points(&b0, &b1, &pa, &pa).0;
        let depth = n.dot(&(pb - pa));
        if depth >= -margin {
            out.push(ContactPoint {
                point: (pa + pb) / 2.0,
                normal: *n,
                depth,
                feature: Feature::Round,
            });
        }
    }
    out.len() > first
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::collision::geometry::polyhedron::BoxView;
    use crate::physics::collision::geometry::shape::Pose;
    use nalgebra::{Matrix3, Rotation3};

    fn unit_cube() -> BoxView {
        BoxView::new(&V::new(0.5, 0.5, 0.5), &Pose::at(V::zeros()))
    }

    fn lying(center: V) -> CylinderView {
        // Axis along x (body y turned −90° about z... any turn taking y to ±x).
        let r = Rotation3::from_axis_angle(&V::z_axis(), std::f64::consts::FRAC_PI_2);
        CylinderView {
            center,
            rotation: *r.matrix(),
            radius: 0.2,
            half: 0.3,
        }
    }

    #[test]
    fn a_cylinder_lying_on_a_box_touches_along_a_line_of_two_points() {
        // Radius 0.2, centre 0.199 above the top face y = 0.5: depth 0.001 at the two ends
        // x = ±0.3 of the lowest generator.
        let c = lying(V::new(0.0, 0.699, 0.1));
        let mut out = Vec::new();
        cylinder_polyhedron(&c, &unit_cube(), 0.01, &mut out);
        assert_eq!(out.len(), 2, "{out:?}");
        let mut xs: Vec<f64> = out.iter().map(|p| p.point.x).collect();
        xs.sort_by(f64::total_cmp);
        assert!(
            (xs[0] + 0.3).abs() < 1e-9 && (xs[1] - 0.3).abs() < 1e-9,
            "{out:?}"
        );
        for p in &out {
            assert!((p.depth - 0.001).abs() < 1e-9, "{p:?}");
            assert!((p.normal - V::y()).norm() < 1e-12);
            assert!((p.point.z - 0.1).abs() < 1e-9 && (p.point.y - 0.4995).abs() < 1e-9);
        }
    }

    #[test]
    fn a_cylinder_overhanging_the_edge_touches_up_to_the_edge() {
        // Centre at x = 0.4: the generator runs over x ∈ [0.1, 0.7], the face ends at 0.5.
        let c = lying(V::new(0.4, 0.699, 0.0));
        let mut out = Vec::new();
        cylinder_polyhedron(&c, &unit_cube(), 0.01, &mut out);
        let mut xs: Vec<f64> = out.iter().map(|p| p.point.x).collect();
        xs.sort_by(f64::total_cmp);
        assert_eq!(xs.len(), 2, "{out:?}");
        assert!(
            (xs[0] - 0.1).abs() < 1e-9 && (xs[1] - 0.5).abs() < 1e-9,
            "{xs:?}"
        );
    }

    #[test]
    fn a_cylinder_standing_on_a_box_touches_along_its_rim() {
        // Axis along y, bottom cap 0.001 below the top face: 4 rim points at radius 0.2.
        let c = CylinderView {
            center: V::new(0.0, 0.799, 0.0),
            rotation: Matrix3::identity(),
            radius: 0.2,
            half: 0.3,
        };
        let mut out = Vec::new();
        cylinder_polyhedron(&c, &unit_cube(), 0.01, &mut out);
        assert_eq!(out.len(), 4, "{out:?}");
        for p in &out {
            assert!((p.depth - 0.001).abs() < 1e-9, "{p:?}");
            assert!((p.point.x.hypot(p.point.z) - 0.2).abs() < 1e-9, "{p:?}");
            assert!((p.normal - V::y()).norm() < 1e-12);
        }
    }

    #[test]
    fn a_box_on_a_standing_cylinder_rests_on_its_end() {
        // A cube of side 0.2 whose bottom is 0.001 into the top cap y = 0.3 of a cylinder of
        // radius 0.5: reference the box's face? No: B is the box, A the cylinder below it, the
        // normal −y (B → A); the box's bottom face is the reference, 4 corners of depth 0.001.
        let c = CylinderView {
            center: V::zeros(),
            rotation: Matrix3::identity(),
            radius: 0.5,
            half: 0.3,
        };
        let cube = BoxView::new(&V::new(0.1, 0.1, 0.1), &Pose::at(V::new(0.0, 0.399, 0.0)));
        let mut out = Vec::new();
        cylinder_polyhedron(&c, &cube, 0.01, &mut out);
        assert_eq!(out.len(), 4, "{out:?}");
        for p in &out {
            assert!((p.depth - 0.001).abs() < 1e-9, "{p:?}");
            assert!((p.normal + V::y()).norm() < 1e-12);
            assert!((p.point.x.abs() - 0.1).abs() < 1e-9, "{p:?}");
        }
    }

    #[test]
    fn two_logs_side_by_side_touch_along_a_line_and_crossed_at_a_point() {
        // Two lying cylinders of radius 0.2, one 0.399 above the other: depth 0.001.
        let below = lying(V::zeros());
        let above = lying(V::new(0.1, 0.399, 0.0));
        let mut out = Vec::new();
        cylinder_cylinder(&above, &below, 0.01, &mut out);
        assert_eq!(out.len(), 2, "{out:?}");
        let mut xs: Vec<f64> = out.iter().map(|p| p.point.x).collect();
        xs.sort_by(f64::total_cmp);
        // Overlap of x ∈ [−0.2, 0.4] and [−0.3, 0.3]: [−0.2, 0.3].
        assert!(
            (xs[0] + 0.2).abs() < 1e-6 && (xs[1] - 0.3).abs() < 1e-6,
            "{xs:?}"
        );
        for p in &out {
            assert!((p.depth - 0.001).abs() < 1e-6, "{p:?}");
        }
        // Crossed: the upper one along z touches at one point, depth 0.001.
        let r = Rotation3::from_axis_angle(&V::x_axis(), std::f64::consts::FRAC_PI_2);
        let crossed = CylinderView {
            rotation: *r.matrix(),
            center: V::new(0.0, 0.399, 0.0),
            ..below
        };
        out.clear();
        cylinder_cylinder(&crossed, &below, 0.01, &mut out);
        assert_eq!(out.len(), 1, "{out:?}");
        assert!((out[0].depth - 0.001).abs() < 1e-6, "{out:?}");
        assert!((out[0].normal - V::y()).norm() < 1e-3, "{out:?}");
    }

    #[test]
    fn a_cylinder_standing_on_another_rests_on_its_rim() {
        let below = CylinderView {
            center: V::zeros(),
            rotation: Matrix3::identity(),
            radius: 0.5,
            half: 0.3,
        };
        let above = CylinderView {
            center: V::new(0.0, 0.599, 0.0),
            radius: 0.2,
            ..below
        };
        let mut out = Vec::new();
        cylinder_cylinder(&above, &below, 0.01, &mut out);
        assert_eq!(out.len(), 4, "{out:?}");
        for p in &out {
            assert!((p.depth - 0.001).abs() < 1e-9, "{p:?}");
            assert!((p.point.x.hypot(p.point.z) - 0.2).abs() < 1e-9, "{p:?}");
        }
    }
}
