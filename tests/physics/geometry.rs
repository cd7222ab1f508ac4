//! Contact geometry against hand-computed truth: boxes face to face, edge on face, edge across
//! edge, the plate on a pillar and on a sphere, a bar across a ridge, the ground, particles,
//! hulls that must answer as the boxes they are, and random box pairs.

use nalgebra::{Rotation3, Vector3};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_4, SQRT_2};
use tumble::physics::collision::geometry::{
    deepest, point_shape, shape_shape, ContactPoint, ConvexHull, Feature, Pose, Shape,
};
use tumble::physics::collision::obstacle::{AlignedBox, Ground, Sphere};
use tumble::physics::Obstacle;

const TOL: f64 = 1e-12;

fn cube(side: f64) -> Shape {
    Shape::Box {
        half: Vector3::repeat(side / 2.0),
    }
}

fn cuboid(x: f64, y: f64, z: f64) -> Shape {
    Shape::Box {
        half: Vector3::new(x, y, z) / 2.0,
    }
}

/// The same box as a hull of its 8 corners.
fn as_hull(shape: &Shape) -> Shape {
    match shape {
        Shape::Box { half } => Shape::Hull(ConvexHull::cuboid(half)),
        hull => hull.clone(),
    }
}

fn rotated(axis: Vector3<f64>, angle: f64, position: Vector3<f64>) -> Pose {
    Pose {
        position,
        rotation: Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle)
            .into_inner(),
    }
}

fn pair(a: &Shape, pa: &Pose, b: &Shape, pb: &Pose, margin: f64) -> Vec<ContactPoint> {
    let mut out = Vec::new();
    shape_shape(a, pa, b, pb, margin, &mut out);
    out
}

fn obstacle(a: &Shape, pa: &Pose, o: &Obstacle, margin: f64) -> Vec<ContactPoint> {
    let mut out = Vec::new();
    o.contact(a, pa, margin, &mut out);
    out
}

/// Points sorted by x, then z, then y (to compare manifolds regardless of order).
fn sorted_points(contacts: &[ContactPoint]) -> Vec<Vector3<f64>> {
    let mut points: Vec<Vector3<f64>> = contacts.iter().map(|c| c.point).collect();
    points.sort_by(|p, q| {
        (p.x, p.z, p.y)
            .partial_cmp(&(q.x, q.z, q.y))
            .expect("finite points")
    });
    points
}

/// Asserts every contact has `normal` and `depth`, and the points are `expected` (any order).
fn assert_manifold(
    contacts: &[ContactPoint],
    normal: Vector3<f64>,
    depth: f64,
    expected: &[Vector3<f64>],
    tol: f64,
) {
    assert_eq!(contacts.len(), expected.len(), "{contacts:#?}");
    for c in contacts {
        assert!((c.normal - normal).norm() < tol, "normal {:?}", c.normal);
        assert!((c.depth - depth).abs() < tol, "depth {}", c.depth);
    }
    let mut expected = expected.to_vec();
    expected.sort_by(|p, q| (p.x, p.z, p.y).partial_cmp(&(q.x, q.z, q.y)).unwrap());
    for (p, q) in sorted_points(contacts).iter().zip(&expected) {
        assert!((p - q).norm() < tol, "point {p:?}, expected {q:?}");
    }
}

fn corners_xz(h: f64, y: f64) -> Vec<Vector3<f64>> {
    [(-h, -h), (-h, h), (h, -h), (h, h)]
        .iter()
        .map(|&(x, z)| Vector3::new(x, y, z))
        .collect()
}

/// Unit cube A resting 0.01 m into unit cube B at the origin.
fn face_to_face() -> (Shape, Pose, Shape, Pose) {
    (
        cube(1.0),
        Pose::at(Vector3::new(0.0, 0.99, 0.0)),
        cube(1.0),
        Pose::at(Vector3::zeros()),
    )
}

/// Unit cube A turned 45° about z, bottom edge (along z) 0.01 m into unit cube B's top face.
fn edge_on_face() -> (Shape, Pose, Shape, Pose) {
    // A's bottom edge lies √2/2 below its centre: centre y = 0.5 + √2/2 − 0.01.
    let y = 0.5 + SQRT_2 / 2.0 - 0.01;
    (
        cube(1.0),
        rotated(Vector3::z(), FRAC_PI_4, Vector3::new(0.0, y, 0.0)),
        cube(1.0),
        Pose::at(Vector3::zeros()),
    )
}

/// Depth of the crossed-edges case.
const CROSS_DEPTH: f64 = 0.02;

/// Unit cube A turned 45° about x (bottom edge along x) over unit cube B turned 45° about z (top
/// edge along z), the edges crossing 0.02 m deep.
fn crossed_edges() -> (Shape, Pose, Shape, Pose) {
    // B's top edge at y = √2/2; A's bottom edge √2/2 below its centre: centre y = √2 − δ.
    (
        cube(1.0),
        rotated(
            Vector3::x(),
            FRAC_PI_4,
            Vector3::new(0.0, SQRT_2 - CROSS_DEPTH, 0.0),
        ),
        cube(1.0),
        rotated(Vector3::z(), FRAC_PI_4, Vector3::zeros()),
    )
}

#[test]
fn two_cubes_face_to_face_touch_at_four_corners() {
    // Overlap 0.01 along y: the four corners of the shared square, midway between A's bottom
    // (y = 0.49) and B's top (y = 0.5): y = 0.495; normal +y (B → A).
    let (a, pa, b, pb) = face_to_face();
    let contacts = pair(&a, &pa, &b, &pb, 0.0);
    assert_manifold(&contacts, Vector3::y(), 0.01, &corners_xz(0.5, 0.495), TOL);
    assert!(contacts.iter().all(|c| c.feature == Feature::FaceFace));
    assert!((deepest(&contacts) - 0.01).abs() < TOL);
}

#[test]
fn a_cube_edge_down_on_a_cube_touches_at_the_two_ends_of_its_edge() {
    // A's bottom edge x = 0, y = 0.49, z ∈ [−0.5, 0.5] is 0.01 inside B's top face: its ends,
    // midway at y = 0.495.
    let (a, pa, b, pb) = edge_on_face();
    let contacts = pair(&a, &pa, &b, &pb, 0.0);
    let expected = [
        Vector3::new(0.0, 0.495, -0.5),
        Vector3::new(0.0, 0.495, 0.5),
    ];
    assert_manifold(&contacts, Vector3::y(), 0.01, &expected, 1e-12);
    assert!(contacts.iter().all(|c| c.feature == Feature::EdgeFace));
}

#[test]
fn two_cubes_crossed_edge_to_edge_touch_at_one_point() {
    // A's edge (along x) at y = √2/2 − δ crosses B's edge (along z) at y = √2/2 over x = z = 0:
    // one point midway, y = √2/2 − δ/2, depth δ, normal +y.
    let (a, pa, b, pb) = crossed_edges();
    let contacts = pair(&a, &pa, &b, &pb, 0.0);
    let expected = [Vector3::new(0.0, SQRT_2 / 2.0 - CROSS_DEPTH / 2.0, 0.0)];
    assert_manifold(&contacts, Vector3::y(), CROSS_DEPTH, &expected, 1e-12);
    assert_eq!(contacts[0].feature, Feature::EdgeEdge);
}

#[test]
fn swapping_a_and_b_flips_the_normals_and_keeps_points_and_depths() {
    for (a, pa, b, pb) in [face_to_face(), edge_on_face(), crossed_edges()] {
        let ab = pair(&a, &pa, &b, &pb, 0.0);
        let ba = pair(&b, &pb, &a, &pa, 0.0);
        assert_eq!(ab.len(), ba.len());
        for (p, q) in sorted_points(&ab).iter().zip(sorted_points(&ba)) {
            assert!((p - q).norm() < 1e-12, "{p:?} vs {q:?}");
        }
        for (c, d) in ab.iter().zip(&ba) {
            assert!((c.normal + d.normal).norm() < 1e-12);
            assert!((c.depth - d.depth).abs() < 1e-12);
        }
    }
}

#[test]
fn hulls_of_the_cubes_corners_give_the_boxes_answers() {
    for (a, pa, b, pb) in [face_to_face(), edge_on_face(), crossed_edges()] {
        let boxes = pair(&a, &pa, &b, &pb, 0.0);
        for (ha, hb) in [
            (as_hull(&a), b.clone()),
            (a.clone(), as_hull(&b)),
            (as_hull(&a), as_hull(&b)),
        ] {
            let hulls = pair(&ha, &pa, &hb, &pb, 0.0);
            assert_eq!(hulls.len(), boxes.len(), "{hulls:#?}");
            for (p, q) in sorted_points(&hulls).iter().zip(sorted_points(&boxes)) {
                assert!((p - q).norm() < 1e-12, "{p:?} vs {q:?}");
            }
            for (h, c) in hulls.iter().zip(&boxes) {
                assert!((h.normal - c.normal).norm() < 1e-12);
                assert!((h.depth - c.depth).abs() < 1e-12);
                assert_eq!(h.feature, c.feature);
            }
        }
    }
}

#[test]
fn separated_cubes_have_no_contact_unless_within_the_margin() {
    // A at y = 1.1: gap 0.1 between A's bottom (y = 0.6) and B's top (y = 0.5).
    let a = cube(1.0);
    let pa = Pose::at(Vector3::new(0.0, 1.1, 0.0));
    let b = cube(1.0);
    let pb = Pose::at(Vector3::zeros());
    assert!(pair(&a, &pa, &b, &pb, 0.05).is_empty());
    // Within a 0.2 margin: the four corners at depth −0.1, midway y = 0.55.
    let near = pair(&a, &pa, &b, &pb, 0.2);
    assert_manifold(&near, Vector3::y(), -0.1, &corners_xz(0.5, 0.55), 1e-12);
    assert_eq!(deepest(&near), 0.0, "near points do not penetrate");
    // Apart sideways (along x) with the edges crossed: nothing.
    let (a, mut pa, b, pb) = crossed_edges();
    pa.position.x += 2.0;
    assert!(pair(&a, &pa, &b, &pb, 0.01).is_empty());
}

#[test]
fn a_plate_on_a_pillar_touches_at_the_pillars_four_corners() {
    // Plate 1.0 × 0.1 × 1.0 centred over a 0.2 × 1 × 0.2 pillar (top y = 1), 0.01 into it:
    // the plate's bottom face covers the pillar's top, so the manifold is the pillar's four
    // top corners (±0.1, ·, ±0.1), midway y = 0.995. No plate vertex is inside the pillar: this
    // is the contact that a vertex test misses.
    let plate = cuboid(1.0, 0.1, 1.0);
    let pose = Pose::at(Vector3::new(0.0, 1.0 + 0.05 - 0.01, 0.0));
    let pillar = Obstacle::AlignedBox(AlignedBox {
        min: Vector3::new(-0.1, 0.0, -0.1),
        max: Vector3::new(0.1, 1.0, 0.1),
    });
    for shape in [plate.clone(), as_hull(&plate)] {
        let contacts = obstacle(&shape, &pose, &pillar, 0.0);
        assert_manifold(
            &contacts,
            Vector3::y(),
            0.01,
            &corners_xz(0.1, 0.995),
            1e-12,
        );
        assert!(contacts.iter().all(|c| c.feature == Feature::FaceFace));
    }
}

#[test]
fn a_plate_on_a_sphere_touches_at_one_point_of_its_face() {
    // Sphere radius 0.5 at the origin, plate bottom at y = 0.49: depth 0.01 at the top of the
    // sphere, point midway (0, 0.495, 0), normal +y.
    let plate = cuboid(1.0, 0.1, 1.0);
    let pose = Pose::at(Vector3::new(0.0, 0.54, 0.0));
    let sphere = Obstacle::Sphere(Sphere {
        center: Vector3::zeros(),
        radius: 0.5,
    });
    for shape in [plate.clone(), as_hull(&plate)] {
        let contacts = obstacle(&shape, &pose, &sphere, 0.0);
        assert_manifold(
            &contacts,
            Vector3::y(),
            0.01,
            &[Vector3::new(0.0, 0.495, 0.0)],
            1e-12,
        );
    }
}

#[test]
fn a_sphere_centre_inside_a_plate_pushes_it_out_through_the_nearest_face() {
    // Plate half-thickness 0.05 at the origin, sphere centre (0, −0.04, 0), radius 0.1: the
    // nearest face is the bottom one (0.01 away, outward m = −y); the plate must rise until its
    // bottom meets the sphere's top, from −0.05 to −0.04 + 0.1 = 0.06: depth 0.11, normal +y.
    // Point midway between the face point q = (0, −0.05, 0) and the sphere point facing it,
    // c − ρ m = (0, 0.06, 0): (0, 0.005, 0).
    let plate = cuboid(1.0, 0.1, 1.0);
    let pose = Pose::at(Vector3::zeros());
    let sphere = Obstacle::Sphere(Sphere {
        center: Vector3::new(0.0, -0.04, 0.0),
        radius: 0.1,
    });
    for shape in [plate.clone(), as_hull(&plate)] {
        let contacts = obstacle(&shape, &pose, &sphere, 0.0);
        assert_manifold(
            &contacts,
            Vector3::y(),
            0.11,
            &[Vector3::new(0.0, 0.005, 0.0)],
            1e-12,
        );
    }
}

#[test]
fn a_cube_corner_near_a_sphere_is_a_near_point_with_the_gap_as_negative_depth() {
    // Unit cube at the origin, sphere of radius 0.1 centred on the diagonal at distance
    // 0.2 + √3/2 from the centre: its gap to the corner (0.5, 0.5, 0.5) is 0.1.
    let direction = Vector3::repeat(1.0).normalize();
    let sphere = Obstacle::Sphere(Sphere {
        center: direction * (3f64.sqrt() / 2.0 + 0.2),
        radius: 0.1,
    });
    let pose = Pose::at(Vector3::zeros());
    assert!(obstacle(&cube(1.0), &pose, &sphere, 0.05).is_empty());
    let contacts = obstacle(&cube(1.0), &pose, &sphere, 0.2);
    // Point midway between the corner and the sphere's nearest point: √3/2 + 0.05 along the
    // diagonal; normal from the sphere toward the cube: −diagonal.
    let expected = [direction * (3f64.sqrt() / 2.0 + 0.05)];
    assert_manifold(&contacts, -direction, -0.1, &expected, 1e-12);
}

#[test]
fn a_bar_across_a_thin_ridge_touches_where_its_edge_crosses_the_ridge_top() {
    // Bar 1.0 × 0.1 × 0.1 along x, turned 45° about x so an edge (along x) points down, across
    // a ridge 0.02 wide in x, 2 long in z, top y = 0.5. The edge is √2·0.05 below the bar's
    // centre; centre y = 0.5 + 0.05√2 − 0.005: depth 0.005 where the edge is over the ridge
    // top, x ∈ [−0.01, 0.01]: points (±0.01, 0.4975, 0).
    let bar = cuboid(1.0, 0.1, 0.1);
    let pose = rotated(
        Vector3::x(),
        FRAC_PI_4,
        Vector3::new(0.0, 0.5 + 0.05 * SQRT_2 - 0.005, 0.0),
    );
    let ridge = Obstacle::AlignedBox(AlignedBox {
        min: Vector3::new(-0.01, 0.0, -1.0),
        max: Vector3::new(0.01, 0.5, 1.0),
    });
    let expected = [
        Vector3::new(-0.01, 0.4975, 0.0),
        Vector3::new(0.01, 0.4975, 0.0),
    ];
    for shape in [bar.clone(), as_hull(&bar)] {
        let contacts = obstacle(&shape, &pose, &ridge, 0.0);
        assert_manifold(&contacts, Vector3::y(), 0.005, &expected, 1e-12);
        assert!(contacts.iter().all(|c| c.feature == Feature::EdgeFace));
    }
}

#[test]
fn the_ground_gives_four_corners_flat_two_edge_down_one_corner_down() {
    let ground = Obstacle::Ground(Ground { height: 0.0 });
    let flat = Pose::at(Vector3::new(0.0, 0.49, 0.0));
    let contacts = obstacle(&cube(1.0), &flat, &ground, 0.0);
    assert_manifold(
        &contacts,
        Vector3::y(),
        0.01,
        &corners_xz(0.5, -0.005),
        1e-12,
    );
    assert!(contacts.iter().all(|c| c.feature == Feature::FaceFace));

    let edge_down = rotated(
        Vector3::z(),
        FRAC_PI_4,
        Vector3::new(0.0, SQRT_2 / 2.0 - 0.01, 0.0),
    );
    let contacts = obstacle(&cube(1.0), &edge_down, &ground, 0.0);
    let expected = [
        Vector3::new(0.0, -0.005, -0.5),
        Vector3::new(0.0, -0.005, 0.5),
    ];
    assert_manifold(&contacts, Vector3::y(), 0.01, &expected, 1e-12);
    assert!(contacts.iter().all(|c| c.feature == Feature::EdgeFace));

    // Corner down: the diagonal (1,1,1) turned onto −y; the corner √3/2 below the centre.
    let diagonal = Vector3::repeat(1.0).normalize();
    let rotation = Rotation3::rotation_between(&diagonal, &-Vector3::y())
        .expect("not opposite")
        .into_inner();
    let corner_down = Pose {
        position: Vector3::new(0.0, 3f64.sqrt() / 2.0 - 0.01, 0.0),
        rotation,
    };
    for shape in [cube(1.0), as_hull(&cube(1.0))] {
        let contacts = obstacle(&shape, &corner_down, &ground, 0.0);
        assert_manifold(
            &contacts,
            Vector3::y(),
            0.01,
            &[Vector3::new(0.0, -0.005, 0.0)],
            1e-12,
        );
        assert_eq!(contacts[0].feature, Feature::VertexFace);
    }
}

#[test]
fn a_box_obstacle_is_a_box_with_identity_rotation() {
    // Unit cube A at y = 0.99 on the obstacle [−0.5, 0.5]³: the face_to_face answer.
    let (a, pa, b, pb) = face_to_face();
    let o = Obstacle::AlignedBox(AlignedBox {
        min: Vector3::repeat(-0.5),
        max: Vector3::repeat(0.5),
    });
    assert_eq!(obstacle(&a, &pa, &o, 0.0), pair(&a, &pa, &b, &pb, 0.0));
}

#[test]
fn a_particle_inside_a_box_is_pushed_out_through_the_nearest_face() {
    // Cube of side 1 turned 45° about z at (1, 0, 0): a particle 0.1 inside its face of normal
    // R·x = (√2/2, √2/2, 0): depth 0.1, normal that face's, point on the face.
    let pose = rotated(Vector3::z(), FRAC_PI_4, Vector3::new(1.0, 0.0, 0.0));
    let n = Vector3::new(SQRT_2 / 2.0, SQRT_2 / 2.0, 0.0);
    let p = pose.position + n * 0.4 + Vector3::new(0.0, 0.0, 0.1);
    for shape in [cube(1.0), as_hull(&cube(1.0))] {
        let c = point_shape(&p, &shape, &pose, 0.0).expect("inside");
        assert!((c.depth - 0.1).abs() < 1e-12, "{c:?}");
        assert!((c.normal - n).norm() < 1e-12, "{c:?}");
        assert!((c.point - (p + n * 0.1)).norm() < 1e-12, "{c:?}");
        // 0.3 outside the same face: None, or depth −0.3 within a 0.5 margin.
        let q = pose.position + n * 0.8;
        assert!(point_shape(&q, &shape, &pose, 0.1).is_none());
        let near = point_shape(&q, &shape, &pose, 0.5).expect("within margin");
        assert!((near.depth + 0.3).abs() < 1e-12, "{near:?}");
        assert!((near.normal - n).norm() < 1e-12, "{near:?}");
    }
}

/// A rotation from a vector (axis × angle), and half-extents.
fn arbitrary_box() -> impl Strategy<Value = (Vector3<f64>, Vector3<f64>, Vector3<f64>)> {
    (
        prop::array::uniform3(0.05f64..1.0),
        prop::array::uniform3(-1.0f64..1.0),
        prop::array::uniform3(-3.2f64..3.2),
    )
        .prop_map(|(h, x, r)| (h.into(), x.into(), r.into()))
}

/// Corners of a box at a pose (an independent way to project it).
fn corners(half: &Vector3<f64>, pose: &Pose) -> Vec<Vector3<f64>> {
    (0..8)
        .map(|i| {
            let s = |bit: usize| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
            pose.to_world(&Vector3::new(s(0) * half.x, s(1) * half.y, s(2) * half.z))
        })
        .collect()
}

/// Overlap of the two corner sets' shadows on `u` (negative: a gap).
fn overlap(a: &[Vector3<f64>], b: &[Vector3<f64>], u: &Vector3<f64>) -> f64 {
    let shadow = |set: &[Vector3<f64>]| {
        set.iter()
            .map(|p| p.dot(u))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let ((a_lo, a_hi), (b_lo, b_hi)) = (shadow(a), shadow(b));
    (a_hi - b_lo).min(b_hi - a_lo)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]
    #[test]
    fn random_box_pairs_give_sane_contacts(
        (ha, xa, ra) in arbitrary_box(),
        (hb, xb, rb) in arbitrary_box(),
        margin in 0.0f64..0.05,
    ) {
        let pose = |x: Vector3<f64>, r: Vector3<f64>| Pose {
            position: x,
            rotation: Rotation3::new(r).into_inner(),
        };
        let (pa, pb) = (pose(xa, ra), pose(xb, rb));
        let (a, b) = (Shape::Box { half: ha }, Shape::Box { half: hb });
        let contacts = pair(&a, &pa, &b, &pb, margin);
        let (ca, cb) = (corners(&ha, &pa), corners(&hb, &pb));
        // The true penetration depth is the least overlap over all directions, so it is at most
        // the overlap along any axis: the world axes and the centre line. (The face bias may
        // pick a face axis up to 2 % + 10 µm worse.)
        let mut axes = vec![Vector3::x(), Vector3::y(), Vector3::z()];
        if (xa - xb).norm() > 1e-9 {
            axes.push((xa - xb).normalize());
        }
        let bound = axes.iter().map(|u| overlap(&ca, &cb, u)).fold(f64::INFINITY, f64::min);
        if bound < -margin {
            // Apart by more than the margin along some axis. The separating-axis test's 15
            // axes need not include that axis (for separated boxes the best separating
            // direction can lie between them), so a near point may still be reported, its gap
            // a lower bound of the true distance: it must never claim penetration.
            prop_assert!(
                contacts.iter().all(|c| c.depth <= 0.0),
                "apart by {} > margin {margin}: {contacts:?}",
                -bound
            );
        }
        prop_assert!(contacts.len() <= 4);
        for c in &contacts {
            prop_assert!(c.point.iter().all(|x| x.is_finite()));
            prop_assert!((c.normal.norm() - 1.0).abs() < 1e-9, "{c:?}");
            prop_assert!(c.depth >= -margin - 1e-12, "{c:?}");
            prop_assert!(c.depth <= 1.03 * bound.max(0.0) + 2e-5, "depth {} > bound {bound}", c.depth);
        }
        // B's centre inside A: they must touch.
        let local = pa.rotation.transpose() * (xb - xa);
        if local.abs().iter().zip(ha.iter()).all(|(l, h)| l < h) {
            prop_assert!(deepest(&contacts) > 0.0, "{contacts:?}");
        }
        // The generic polyhedron test on the boxes as hulls agrees with the closed form.
        let hulls = pair(&as_hull(&a), &pa, &as_hull(&b), &pb, margin);
        prop_assert_eq!(hulls.is_empty(), contacts.is_empty());
        prop_assert!((deepest(&hulls) - deepest(&contacts)).abs() <= 0.03 * deepest(&contacts) + 2e-5,
            "hulls {hulls:?} boxes {contacts:?}");
        // Swapping flips the normal and keeps the deepest depth.
        let swapped = pair(&b, &pb, &a, &pa, margin);
        prop_assert_eq!(swapped.is_empty(), contacts.is_empty());
        prop_assert!((deepest(&swapped) - deepest(&contacts)).abs() <= 0.03 * deepest(&contacts) + 2e-5);
    }
}

/// The corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) as a hull.
fn corner_tetrahedron() -> Shape {
    let points = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.0, 1.0, 0.0),
        Vector3::new(0.0, 0.0, 1.0),
    ];
    Shape::Hull(ConvexHull::from_points(&points).expect("a tetrahedron has volume"))
}

#[test]
fn a_tetrahedron_on_the_ground_touches_at_its_three_base_corners() {
    // Base y = 0 lowered 0.01 into the ground: its three corners, midway y = −0.005.
    let pose = Pose::at(Vector3::new(0.0, -0.01, 0.0));
    let contacts = obstacle(
        &corner_tetrahedron(),
        &pose,
        &Obstacle::Ground(Ground { height: 0.0 }),
        0.0,
    );
    let expected = [
        Vector3::new(0.0, -0.005, 0.0),
        Vector3::new(0.0, -0.005, 1.0),
        Vector3::new(1.0, -0.005, 0.0),
    ];
    assert_manifold(&contacts, Vector3::y(), 0.01, &expected, 1e-12);
    assert!(contacts.iter().all(|c| c.feature == Feature::FaceFace));
}

#[test]
fn a_tetrahedron_apex_down_on_a_cube_touches_at_one_point() {
    // Turned 180° about x, the apex (0, 1, 0) points down, 1 below the pose's origin; origin at
    // y = 0.5 + 1 − 0.02 puts it 0.02 into the unit cube's top face: one point (0, 0.49, 0).
    let pose = rotated(
        Vector3::x(),
        std::f64::consts::PI,
        Vector3::new(0.0, 1.48, 0.0),
    );
    let contacts = pair(
        &corner_tetrahedron(),
        &pose,
        &cube(1.0),
        &Pose::at(Vector3::zeros()),
        0.0,
    );
    assert_manifold(
        &contacts,
        Vector3::y(),
        0.02,
        &[Vector3::new(0.0, 0.49, 0.0)],
        1e-12,
    );
    assert_eq!(contacts[0].feature, Feature::VertexFace);
    // Seen from the cube: the normal flips.
    let swapped = pair(
        &cube(1.0),
        &Pose::at(Vector3::zeros()),
        &corner_tetrahedron(),
        &pose,
        0.0,
    );
    assert_manifold(
        &swapped,
        -Vector3::y(),
        0.02,
        &[Vector3::new(0.0, 0.49, 0.0)],
        1e-12,
    );
}

#[test]
fn a_particle_off_a_hull_edge_is_nearest_to_that_edge() {
    // p = (0.5, −0.1, −0.1) is beside the edge (0,0,0)–(1,0,0): distance √0.02, normal
    // (0, −1, −1)/√2, nearest point (0.5, 0, 0).
    let p = Vector3::new(0.5, -0.1, -0.1);
    let pose = Pose::at(Vector3::zeros());
    assert!(point_shape(&p, &corner_tetrahedron(), &pose, 0.1).is_none());
    let c = point_shape(&p, &corner_tetrahedron(), &pose, 0.2).expect("within margin");
    assert!((c.depth + 0.02f64.sqrt()).abs() < 1e-12, "{c:?}");
    assert!((c.normal - Vector3::new(0.0, -1.0, -1.0) / SQRT_2).norm() < 1e-12);
    assert!((c.point - Vector3::new(0.5, 0.0, 0.0)).norm() < 1e-12);
}

#[test]
fn the_house_mesh_hull_is_a_pentagonal_prism_standing_on_its_floor() {
    // lessons/meshes/house.obj: a pentagon (square 0.4 × 0.3 with a roof to y = 0.45) extruded
    // 0.2 along z: 10 corners, 7 faces (2 pentagons, 5 quads), 15 edges, and 5 edge directions
    // (z; the floor's x; the walls' y; the two roof slopes).
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/lessons/meshes/house.obj"
    ))
    .expect("house mesh");
    let points: Vec<Vector3<f64>> = text
        .lines()
        .filter_map(|line| line.strip_prefix("v "))
        .map(|xyz| {
            let v: Vec<f64> = xyz.split_whitespace().map(|x| x.parse().unwrap()).collect();
            Vector3::new(v[0], v[1], v[2])
        })
        .collect();
    let hull = ConvexHull::from_points(&points).expect("the house has volume");
    assert_eq!(hull.vertices.len(), 10);
    assert_eq!(hull.faces.len(), 7);
    assert_eq!(
        hull.faces.iter().filter(|f| f.vertices.len() == 5).count(),
        2
    );
    assert_eq!(hull.edges.len(), 15);
    assert_eq!(hull.directions.len(), 5);
    // Floor y = 0 lowered 0.01 into the ground: the floor's 4 corners (±0.2, ·, ±0.1).
    let contacts = obstacle(
        &Shape::Hull(hull),
        &Pose::at(Vector3::new(0.0, -0.01, 0.0)),
        &Obstacle::Ground(Ground { height: 0.0 }),
        0.0,
    );
    let expected: Vec<Vector3<f64>> = [(-0.2, -0.1), (-0.2, 0.1), (0.2, -0.1), (0.2, 0.1)]
        .iter()
        .map(|&(x, z)| Vector3::new(x, -0.005, z))
        .collect();
    assert_manifold(&contacts, Vector3::y(), 0.01, &expected, 1e-12);
}
