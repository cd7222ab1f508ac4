//! The joint kinds, one file each, with the same verbs:
//!
//! | verb | what |
//! |---|---|
//! | `ROWS` | how many equality rows it adds |
//! | `rows` | its equality rows at two poses: C, J and J̇u (bounds (−∞, ∞)) |
//! | `error` | its position residual, m (what `--joint` and the panels show) |
//! | `coordinate` | (hinge, slider) the coordinate q its limits and motor act on, and the row J u = q̇ |
//!
//! A limit or a motor is a row on the coordinate with bounds (`Row::stop`, `Row::motor`,
//! solved by `drive`): a kind that has a `coordinate` takes both.
//!
//! Each file also says how the scene file writes its kind ([`Kind::WRITTEN`]: the `type` word
//! and keys), what its coordinate measures ([`Kind::MEASURE`]) and how it builds itself from its
//! keys ([`Kind::build`], through the format-neutral `written::Keys`), so the scene reader knows
//! no kind. A new kind is its file and one line of `joint_kinds!` below; a limit or a motor on a
//! kind is its `coordinate`, `MEASURE` and the two keys, in its file.
//!
//! | kind | file | rows |
//! |---|---|---|
//! | ball | `ball` | 3: a common point |
//! | hinge | `hinge` | 5: a common point and a common axis |
//! | fixed | `fixed` | 6: a common point and orientation |
//! | distance | `distance` | 1: a rod of fixed length |
//! | slider | `slider` | 5: a common orientation and a rail |

use super::rows::{Pose, Row};
use super::written::{Between, Keys, Measure, Written};
use super::Joint;
use crate::physics::constraints::Axis;
use nalgebra::{Matrix3, Vector3};

/// What every joint kind answers: one file per kind implements it, and [`JointKind`] asks the
/// kind a joint holds.
pub(super) trait Kind {
    /// How the scene file writes it: its `type` word and keys.
    const WRITTEN: Written;
    /// How many equality rows it adds.
    const ROWS: usize;
    /// What its coordinate measures; None for a kind without one (no limits, no motor).
    const MEASURE: Option<Measure> = None;

    /// The joint from its keys (the reader adds `limits` and `motor`).
    fn build<K: Keys>(keys: &K, on: Between) -> Result<Joint, K::Error>;

    /// Appends its equality rows at the anchors `at` to `out`.
    fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>);

    /// Its position residual at poses `a`, `b` (velocities unused), m: by default the anchors'
    /// separation.
    fn error(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
        separation(joint, a, b)
    }

    /// The coordinate its limits and motor act on, and the row of its rate (owner `index`);
    /// None for a kind without one.
    fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> Option<(Row, f64)> {
        let _ = (joint, index, a, b);
        None
    }

    /// The axis a front end draws, world frame, at poses `a`, `b`; None for a kind without one.
    fn axis(joint: &Joint, a: &Pose, b: &Pose) -> Option<Vector3<f64>> {
        let _ = (joint, a, b);
        None
    }
}

/// The kinds: `module::Struct` (the struct implements [`Kind`]), in the order scene-file
/// messages list them. Builds [`JointKind`] and the functions that ask a joint's kind.
macro_rules! joint_kinds {
    ($($(#[$doc:meta])* $module:ident::$kind:ident),* $(,)?) => {
        $(mod $module;)*

        /// What a joint holds.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum JointKind {
            $($(#[$doc])* $kind,)*
        }

        impl JointKind {
            /// Every kind, as scene files name them.
            pub const ALL: [JointKind; [$(stringify!($kind)),*].len()] =
                [$(JointKind::$kind),*];

            /// How the scene file writes each kind, in the order of [`JointKind::ALL`].
            pub const WRITTEN: [Written; [$(stringify!($kind)),*].len()] =
                [$(<$module::$kind as Kind>::WRITTEN),*];

            /// How the scene file writes it.
            pub fn written(self) -> Written {
                match self {
                    $(JointKind::$kind => <$module::$kind as Kind>::WRITTEN,)*
                }
            }

            /// What its coordinate measures; None for a kind without one.
            pub fn measure(self) -> Option<Measure> {
                match self {
                    $(JointKind::$kind => <$module::$kind as Kind>::MEASURE,)*
                }
            }

            /// How many constraint rows it adds.
            pub fn rows(self) -> usize {
                match self {
                    $(JointKind::$kind => <$module::$kind as Kind>::ROWS,)*
                }
            }

            /// The joint of this kind from its keys (the reader adds `limits` and `motor`).
            pub fn build<K: Keys>(self, keys: &K, on: Between) -> Result<Joint, K::Error> {
                match self {
                    $(JointKind::$kind => <$module::$kind as Kind>::build(keys, on),)*
                }
            }
        }

        /// Appends the joint's equality rows at the anchors `at` to `out`.
        #[inline(always)]
        pub(super) fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
            match joint.kind {
                $(JointKind::$kind => <$module::$kind as Kind>::rows(joint, at, out),)*
            }
        }

        /// The joint's position residual at poses `a`, `b` (velocities unused), m.
        pub(super) fn error(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
            match joint.kind {
                $(JointKind::$kind => <$module::$kind as Kind>::error(joint, a, b),)*
            }
        }

        /// The coordinate its limits and motor act on and the row of its rate (owner `index`);
        /// None for a kind without one.
        pub(super) fn coordinate(
            joint: &Joint,
            index: usize,
            a: &Pose,
            b: &Pose,
        ) -> Option<(Row, f64)> {
            match joint.kind {
                $(JointKind::$kind => <$module::$kind as Kind>::coordinate(joint, index, a, b),)*
            }
        }

        /// The axis a front end draws (hinge: A's axis; slider: the rail), world frame.
        pub(super) fn axis(joint: &Joint, a: &Pose, b: &Pose) -> Option<Vector3<f64>> {
            match joint.kind {
                $(JointKind::$kind => <$module::$kind as Kind>::axis(joint, a, b),)*
            }
        }
    };
}

joint_kinds!(
    /// A common point: 3 rows.
    ball::Ball,
    /// A common point and a common axis: 5 rows.
    hinge::Hinge,
    /// A common point and orientation: 6 rows.
    fixed::Fixed,
    /// A rod of fixed length between two points: 1 row.
    distance::Distance,
    /// A common orientation and a rail: the anchor moves only along the axis, 5 rows.
    slider::Slider,
);

impl JointKind {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        self.written().name
    }

    /// The kind with this name.
    pub fn from_name(name: &str) -> Option<JointKind> {
        JointKind::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// A hinge's two axis rows at poses `a`, `b`: (g on A, C, J̇u) each (`hinge::axes`).
#[inline(always)]
pub(super) fn hinge_axes(joint: &Joint, a: &Pose, b: &Pose) -> [(Vector3<f64>, f64, f64); 2] {
    hinge::axes(joint, a, b)
}

/// What every kind's rows start from, at poses A and B: the levers r = R a, the anchors'
/// separation d = p_A − p_B and ω×(ω×r) on each side (the centripetal part of the anchors'
/// accelerations), and the row builder.
pub(super) struct Anchors<'a> {
    pub a: &'a Pose,
    pub b: &'a Pose,
    pub ra: Vector3<f64>,
    pub rb: Vector3<f64>,
    pub centripetal: Vector3<f64>,
    pub separation: Vector3<f64>,
    bodies: (usize, Option<usize>),
    index: usize,
}

impl<'a> Anchors<'a> {
    #[inline(always)]
    pub fn of(joint: &Joint, index: usize, a: &'a Pose, b: &'a Pose) -> Anchors<'a> {
        let ra = a.r * joint.anchor_a;
        let rb = b.r * joint.anchor_b;
        let centripetal = a.w.cross(&a.w.cross(&ra)) - b.w.cross(&b.w.cross(&rb));
        let separation = a.x + ra - b.x - rb;
        Anchors {
            a,
            b,
            ra,
            rb,
            centripetal,
            separation,
            bodies: (joint.a, joint.b),
            index,
        }
    }

    /// The equality row (lin, g_A | −lin, g_B) with C = `c` and J̇u = `bias`.
    #[inline(always)]
    pub fn row(
        &self,
        lin: Vector3<f64>,
        g_a: Vector3<f64>,
        g_b: Vector3<f64>,
        c: f64,
        bias: f64,
    ) -> Row {
        let (a, b) = self.bodies;
        let axis = Axis::jacobian(lin, (a, g_a), b.map(|b| (b, g_b)));
        Row::equality(axis, c, bias, self.index)
    }

    /// The three point rows of ball, hinge and fixed: C = x_A + r_A − x_B − r_B,
    /// (e_k, r_A×e_k | −e_k, −r_B×e_k), J̇u = ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B).
    #[inline(always)]
    pub fn point_rows(&self, out: &mut Vec<Row>) {
        for k in 0..3 {
            let e = Vector3::ith(k, 1.0);
            out.push(self.row(
                e,
                self.ra.cross(&e),
                -self.rb.cross(&e),
                self.separation[k],
                self.centripetal[k],
            ));
        }
    }

    /// The three orientation rows of fixed and slider, (0, e_k | 0, −e_k) with C_k the k-th
    /// component of the error vector (the skew part of R_A (R_B R₀)ᵀ), J̇u = 0 (they hold
    /// ω_A − ω_B = 0).
    #[inline]
    pub fn orientation_rows(&self, rest: &Matrix3<f64>, out: &mut Vec<Row>) {
        let error = orientation_error(&self.a.r, &self.b.r, rest);
        for k in 0..3 {
            let ang = Vector3::ith(k, 1.0);
            out.push(self.row(Vector3::zeros(), ang, -ang, error[k], 0.0));
        }
    }
}

/// The anchors' separation |p_A − p_B| (ball, hinge, fixed: their position residual), m.
fn separation(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
    let [pa, pb] = anchor_points(joint, a, b);
    (pa - pb).norm()
}

/// The two anchor points at poses `a`, `b`, world frame: `x + R a` on each side.
pub(super) fn anchor_points(joint: &Joint, a: &Pose, b: &Pose) -> [Vector3<f64>; 2] {
    [a.x + a.r * joint.anchor_a, b.x + b.r * joint.anchor_b]
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
fn turned(ra: &Matrix3<f64>, rb: &Matrix3<f64>, rest: &Matrix3<f64>) -> f64 {
    let e = ra * (rb * rest).transpose();
    let sine = orientation_error(ra, rb, rest).norm();
    sine.atan2(0.5 * (e.trace() - 1.0))
}

/// A coordinate's row (lin, g_A | −lin, g_B) of joint `index` at q = `value` (its C), no
/// bias, and q.
fn coordinate_row(
    joint: &Joint,
    index: usize,
    (lin, g_a, g_b): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
    value: f64,
) -> (Row, f64) {
    let axis = Axis::jacobian(lin, (joint.a, g_a), joint.b.map(|b| (b, g_b)));
    (Row::equality(axis, value, 0.0, index), value)
}
