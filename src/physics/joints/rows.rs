//! A joint's constraint rows at a configuration: C, its gradient J and the bias J̇u (the
//! equations are in the parent module's doc).

use super::{Joint, JointKind};
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

/// Where a body is and how it moves: barycenter x, rotation R, velocity v, angular velocity ω
/// (world frame). The world is [`Pose::WORLD`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub x: Vector3<f64>,
    pub r: Matrix3<f64>,
    pub v: Vector3<f64>,
    pub w: Vector3<f64>,
}

impl Pose {
    /// The world: at the origin, unturned, at rest.
    pub const WORLD: Pose = Pose {
        x: Vector3::new(0.0, 0.0, 0.0),
        r: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        v: Vector3::new(0.0, 0.0, 0.0),
        w: Vector3::new(0.0, 0.0, 0.0),
    };

    /// A state's position and rotation, velocities left at zero (for what depends on
    /// positions only).
    pub fn of_state(state: &State) -> Pose {
        Pose {
            x: state.position,
            r: state.orientation.matrix(),
            ..Pose::WORLD
        }
    }
}

/// One scalar constraint row: `Ċ = lin_a·v_A + ang_a·ω_A + lin_b·v_B + ang_b·ω_B`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// The joint it belongs to (index in `Links::joints`).
    pub joint: usize,
    pub a: usize,
    pub b: Option<usize>,
    pub lin_a: Vector3<f64>,
    pub ang_a: Vector3<f64>,
    pub lin_b: Vector3<f64>,
    pub ang_b: Vector3<f64>,
    /// C, the position error (m or, for angular rows, dimensionless).
    pub c: f64,
    /// J̇u, the velocity-product term of C̈.
    pub bias: f64,
}

impl Row {
    /// `J u`: the rate Ċ at these velocities.
    #[inline]
    pub fn rate(&self, a: &Pose, b: &Pose) -> f64 {
        self.lin_a.dot(&a.v) + self.ang_a.dot(&a.w) + self.lin_b.dot(&b.v) + self.ang_b.dot(&b.w)
    }
}

/// Appends joint `index`'s rows at poses `a`, `b` (B the world's pose when the joint holds A
/// to the world) to `out`.
pub fn rows_of(joint: &Joint, index: usize, a: &Pose, b: &Pose, out: &mut Vec<Row>) {
    let ra = a.r * joint.anchor_a;
    let rb = b.r * joint.anchor_b;
    let row = |lin_a, ang_a, lin_b, ang_b, c, bias| Row {
        joint: index,
        a: joint.a,
        b: joint.b,
        lin_a,
        ang_a,
        lin_b,
        ang_b,
        c,
        bias,
    };
    // ω×(ω×r) on each side: the centripetal part of the anchors' accelerations.
    let centripetal = a.w.cross(&a.w.cross(&ra)) - b.w.cross(&b.w.cross(&rb));
    let separation = a.x + ra - b.x - rb;
    if joint.kind == JointKind::Distance {
        let length = separation.norm();
        let n = if length > 0.0 {
            separation / length
        } else {
            Vector3::y()
        };
        let rate = a.v + a.w.cross(&ra) - b.v - b.w.cross(&rb);
        let along = n.dot(&rate);
        let bending = if length > 0.0 {
            (rate.norm_squared() - along * along) / length
        } else {
            0.0
        };
        out.push(row(
            n,
            ra.cross(&n),
            -n,
            -rb.cross(&n),
            length - joint.length,
            n.dot(&centripetal) + bending,
        ));
        return;
    }
    if joint.kind == JointKind::Slider {
        // Two linear rows t·d = 0 for t ⊥ the rail (B's normals), d = p_A − p_B:
        // Ċ = t·ḋ + (ω_B×t)·d, C̈ − J u̇ = t·(ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)) + 2 (ω_B×t)·ḋ
        // + (ω_B×(ω_B×t))·d.
        let rate = a.v + a.w.cross(&ra) - b.v - b.w.cross(&rb);
        for normal in &joint.normals_b {
            let t = b.r * normal;
            let wt = b.w.cross(&t);
            out.push(row(
                t,
                ra.cross(&t),
                -t,
                t.cross(&separation) - rb.cross(&t),
                t.dot(&separation),
                t.dot(&centripetal) + 2.0 * wt.dot(&rate) + b.w.cross(&wt).dot(&separation),
            ));
        }
        orientation_rows(joint, a, b, |ang, c| {
            out.push(row(Vector3::zeros(), ang, Vector3::zeros(), -ang, c, 0.0));
        });
        return;
    }
    for k in 0..3 {
        let e = Vector3::ith(k, 1.0);
        out.push(row(
            e,
            ra.cross(&e),
            -e,
            -rb.cross(&e),
            separation[k],
            centripetal[k],
        ));
    }
    match joint.kind {
        JointKind::Hinge => {
            let u = a.r * joint.axis_a;
            let du = a.w.cross(&u);
            let relative = a.w - b.w;
            for normal in &joint.normals_b {
                let t = b.r * normal;
                let g = u.cross(&t);
                let dg = du.cross(&t) + u.cross(&b.w.cross(&t));
                out.push(row(
                    Vector3::zeros(),
                    g,
                    Vector3::zeros(),
                    -g,
                    u.dot(&t),
                    relative.dot(&dg),
                ));
            }
        }
        JointKind::Fixed => orientation_rows(joint, a, b, |ang, c| {
            out.push(row(Vector3::zeros(), ang, Vector3::zeros(), -ang, c, 0.0));
        }),
        JointKind::Ball | JointKind::Distance | JointKind::Slider => {}
    }
}

/// The skew part of E = R_A (R_B R₀)ᵀ, the rotation A has turned away from where B holds it:
/// (E − Eᵀ)/2 is sin θ times the axis, the error vector.
fn orientation_error(ra: &Matrix3<f64>, rb: &Matrix3<f64>, rest: &Matrix3<f64>) -> Vector3<f64> {
    let e = ra * (rb * rest).transpose();
    Vector3::new(
        0.5 * (e[(2, 1)] - e[(1, 2)]),
        0.5 * (e[(0, 2)] - e[(2, 0)]),
        0.5 * (e[(1, 0)] - e[(0, 1)]),
    )
}

/// The angle θ of E = R_A (R_B R₀)ᵀ, rad (0 when A keeps its orientation relative to B):
/// θ = atan2(|skew E|, (tr E − 1)/2).
pub(super) fn turned(ra: &Matrix3<f64>, rb: &Matrix3<f64>, rest: &Matrix3<f64>) -> f64 {
    let e = ra * (rb * rest).transpose();
    let sine = orientation_error(ra, rb, rest).norm();
    sine.atan2(0.5 * (e.trace() - 1.0))
}

/// The three orientation rows of fixed and slider, (0, e_k | 0, −e_k) with C_k the k-th
/// component of the error vector, J̇u = 0 (they hold ω_A − ω_B = 0): `push(e_k, C_k)`.
#[inline]
fn orientation_rows(joint: &Joint, a: &Pose, b: &Pose, mut push: impl FnMut(Vector3<f64>, f64)) {
    let error = orientation_error(&a.r, &b.r, &joint.rest);
    for k in 0..3 {
        push(Vector3::ith(k, 1.0), error[k]);
    }
}

/// A hinge's or a slider's coordinate at poses `a`, `b` and the row of its rate, J u = q̇
/// (`drive`'s limit and motor rows); None for other kinds.
///
/// ```text
/// hinge   θ = atan2(p·t₂, p·t₁)   p = R_A p_A (⊥ the axis, = t₁ at t = 0), t₁, t₂ = R_B n_B
///         (B's two normals, t₂ = u × t₁), wrapped to (c − π, c + π], c the limits' middle
///         θ̇ = u·(ω_A − ω_B):                     (0, u | 0, −u)
/// slider  s = a·d     a = R_B a_B the rail's axis, d = p_A − p_B
///         ṡ = a·ḋ + (ω_B×a)·d:                    (a, r_A×a | −a, −r_B×a + a×d)
/// ```
pub fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> Option<(Row, f64)> {
    let row = |lin_a, ang_a, lin_b, ang_b, c| Row {
        joint: index,
        a: joint.a,
        b: joint.b,
        lin_a,
        ang_a,
        lin_b,
        ang_b,
        c,
        bias: 0.0,
    };
    match joint.kind {
        JointKind::Hinge => {
            let u = a.r * joint.axis_a;
            let p = a.r * joint.reference_a;
            let raw = p
                .dot(&(b.r * joint.normals_b[1]))
                .atan2(p.dot(&(b.r * joint.normals_b[0])));
            let middle = joint.limits.map_or(0.0, |[lo, hi]| 0.5 * (lo + hi));
            let turn = std::f64::consts::TAU;
            let angle = middle + (raw - middle + 0.5 * turn).rem_euclid(turn) - 0.5 * turn;
            let zero = Vector3::zeros();
            Some((row(zero, u, zero, -u, angle), angle))
        }
        JointKind::Slider => {
            let ra = a.r * joint.anchor_a;
            let rb = b.r * joint.anchor_b;
            let d = a.x + ra - b.x - rb;
            let axis = b.r * joint.axis_b;
            let travel = axis.dot(&d);
            let ang_b = axis.cross(&d) - rb.cross(&axis);
            Some((row(axis, ra.cross(&axis), -axis, ang_b, travel), travel))
        }
        _ => None,
    }
}
