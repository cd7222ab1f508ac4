//! What one contact-geometry query costs, in ns/call (`physics::collision::geometry`).
//!
//! Cases (unit cubes unless said otherwise, the contact buffer reused):
//! - `box-box/stacked`: a cube resting 1 cm into an equal cube, aligned (a stack): SAT over the
//!   15 axes, 4 points, no cut;
//! - `box-box/face`: the same turned 0.3 rad about y (8-point overlap thinned to 4);
//! - `box-box/edge`: two cubes crossed edge to edge (one point);
//! - `box-box/apart`: two cubes 0.1 m apart (SAT stops at the first separating axis);
//! - `box-ground`: a cube resting flat on the ground (4 points);
//! - `box-sphere`: a plate on a sphere obstacle (1 point);
//! - `hull-hull/face`: the face case with both cubes as hulls of their 8 corners;
//! - round shapes (radius 0.1 m, length 0.4 m, 1 mm into what they touch): `ball-ground`,
//!   `ball-plane` (a 20° ramp), `ball-box` (on a cube's top face), `ball-ball`,
//!   `capsule-ground` and `capsule-box` (lying: 2 points), `capsule-capsule` (crossed: 1 point),
//!   `capsule-ball`, `cylinder-ground/lying` (2 points), `cylinder-ground/standing` (4 points),
//!   `cylinder-ball`; by GJK/EPA and clipping: `cylinder-box/lying` (2 points),
//!   `cylinder-box/standing` (4), `cylinder-hull/lying` (2), `cylinder-cylinder/crossed` (1),
//!   `cylinder-cylinder/stacked` (end on end, 4).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::{FRAC_PI_4, SQRT_2};
use std::hint::black_box;
use tumble::physics::collision::geometry::{shape_shape, ContactPoint, ConvexHull, Pose, Shape};
use tumble::physics::collision::obstacle::{Ground, Plane, Sphere};
use tumble::physics::Obstacle;

fn rotated(axis: Vector3<f64>, angle: f64, position: Vector3<f64>) -> Pose {
    Pose {
        position,
        rotation: Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle)
            .into_inner(),
    }
}

fn bench(c: &mut Criterion) {
    let half = Vector3::repeat(0.5);
    let cube = Shape::Box { half };
    let hull = Shape::Hull(ConvexHull::cuboid(&half));
    let base = Pose::at(Vector3::zeros());
    let stacked = Pose::at(Vector3::new(0.0, 0.99, 0.0));
    let resting = rotated(Vector3::y(), 0.3, Vector3::new(0.0, 0.99, 0.0));
    let crossed_a = rotated(
        Vector3::x(),
        FRAC_PI_4,
        Vector3::new(0.0, SQRT_2 - 0.02, 0.0),
    );
    let crossed_b = rotated(Vector3::z(), FRAC_PI_4, Vector3::zeros());
    let apart = Pose::at(Vector3::new(0.0, 1.1, 0.0));
    let mut out: Vec<ContactPoint> = Vec::with_capacity(16);

    let mut group = c.benchmark_group("geometry");
    let mut pair = |name: &str, a: &Shape, pa: &Pose, b: &Shape, pb: &Pose| {
        group.bench_function(name, |bench| {
            bench.iter(|| {
                out.clear();
                shape_shape(
                    black_box(a),
                    black_box(pa),
                    black_box(b),
                    black_box(pb),
                    0.01,
                    &mut out,
                );
                black_box(out.len())
            })
        });
    };
    pair("box-box/stacked", &cube, &stacked, &cube, &base);
    pair("box-box/face", &cube, &resting, &cube, &base);
    pair("box-box/edge", &cube, &crossed_a, &cube, &crossed_b);
    pair("box-box/apart", &cube, &apart, &cube, &base);
    pair("hull-hull/face", &hull, &resting, &hull, &base);

    let ground = Obstacle::Ground(Ground { height: 0.0 });
    let on_ground = Pose::at(Vector3::new(0.0, 0.4999, 0.0));
    let plate = Shape::Box {
        half: Vector3::new(0.5, 0.05, 0.5),
    };
    let sphere = Obstacle::Sphere(Sphere {
        center: Vector3::zeros(),
        radius: 0.5,
    });
    let on_sphere = Pose::at(Vector3::new(0.0, 0.54, 0.0));
    let mut obstacle = |name: &str, a: &Shape, pa: &Pose, o: &Obstacle| {
        group.bench_function(name, |bench| {
            bench.iter(|| {
                out.clear();
                black_box(o).contact(black_box(a), black_box(pa), 0.01, &mut out);
                black_box(out.len())
            })
        });
    };
    obstacle("box-ground", &cube, &on_ground, &ground);
    obstacle("box-sphere", &plate, &on_sphere, &sphere);

    let ball = Shape::Ball { radius: 0.1 };
    let capsule = Shape::Capsule {
        radius: 0.1,
        half_length: 0.2,
    };
    let cylinder = Shape::Cylinder {
        radius: 0.1,
        half_length: 0.2,
    };
    let theta = 20f64.to_radians();
    let ramp = Obstacle::Plane(Plane {
        point: Vector3::zeros(),
        normal: Vector3::new(theta.sin(), theta.cos(), 0.0),
    });
    let at = |y: f64| Pose::at(Vector3::new(0.0, y, 0.0));
    let lying = |y: f64| {
        rotated(
            Vector3::z(),
            std::f64::consts::FRAC_PI_2,
            Vector3::new(0.0, y, 0.0),
        )
    };
    obstacle("ball-ground", &ball, &at(0.099), &ground);
    obstacle(
        "ball-plane",
        &ball,
        &Pose::at(Vector3::new(theta.sin(), theta.cos(), 0.0) * 0.099),
        &ramp,
    );
    obstacle("capsule-ground", &capsule, &lying(0.099), &ground);
    obstacle("cylinder-ground/lying", &cylinder, &lying(0.099), &ground);
    obstacle("cylinder-ground/standing", &cylinder, &at(0.199), &ground);
    let mut pair = |name: &str, a: &Shape, pa: &Pose, b: &Shape, pb: &Pose| {
        group.bench_function(name, |bench| {
            bench.iter(|| {
                out.clear();
                shape_shape(
                    black_box(a),
                    black_box(pa),
                    black_box(b),
                    black_box(pb),
                    0.01,
                    &mut out,
                );
                black_box(out.len())
            })
        });
    };
    pair("ball-box", &ball, &at(0.599), &cube, &base);
    pair("ball-ball", &ball, &at(0.199), &ball, &base);
    pair("capsule-box", &capsule, &lying(0.599), &cube, &base);
    pair(
        "capsule-capsule",
        &capsule,
        &rotated(
            Vector3::x(),
            std::f64::consts::FRAC_PI_2,
            Vector3::new(0.0, 0.199, 0.0),
        ),
        &capsule,
        &lying(0.0),
    );
    pair("capsule-ball", &capsule, &lying(0.199), &ball, &base);
    pair("cylinder-ball", &cylinder, &lying(0.199), &ball, &base);
    pair("cylinder-box/lying", &cylinder, &lying(0.599), &cube, &base);
    pair("cylinder-box/standing", &cylinder, &at(0.699), &cube, &base);
    pair(
        "cylinder-hull/lying",
        &cylinder,
        &lying(0.599),
        &hull,
        &base,
    );
    pair(
        "cylinder-cylinder/crossed",
        &cylinder,
        &rotated(
            Vector3::x(),
            std::f64::consts::FRAC_PI_2,
            Vector3::new(0.0, 0.199, 0.0),
        ),
        &cylinder,
        &lying(0.0),
    );
    pair(
        "cylinder-cylinder/stacked",
        &cylinder,
        &at(0.399),
        &cylinder,
        &base,
    );
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
