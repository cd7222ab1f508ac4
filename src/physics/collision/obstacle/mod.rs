//! Obstacles: the scene's fixed things (`[[obstacle]]`), each a static body of the one shape
//! table — one file per kind under `kinds/`, and nothing else to touch.
//!
//! An obstacle is a shape of the contact geometry's table at a fixed pose ([`Obstacle::shape`]):
//! it never moves, takes no impulse, and enters the solvers as a static solver body
//! (`constraints::solver_body`: inverse mass and inertia zero). Detection and `seed` reach it
//! as a fixed thing (`collision::fixed`), the same entry a fixed body has. Everything the engine asks of an
//! obstacle goes through the methods below, which ask the kind it holds ([`Kind`]):
//!
//! | method | who asks | what |
//! |---|---|---|
//! | [`kind`](Obstacle::kind) | panels, labels | the scene-file name |
//! | [`shape`](Obstacle::shape) | the contact geometry, sweeps (`fixed`) | its shape and pose in the shape table |
//! | [`contact`](Obstacle::contact) | bodies' detection (`fixed`), measured penetration | contact points of a body's shape against it |
//! | [`inside`](Obstacle::inside), [`near`](Obstacle::near), [`swept`](Obstacle::swept), [`depth`](Obstacle::depth) | vertices (`seed` and detection, through `fixed`), cloth particles | the report's point tests (`detect`) |
//! | [`outline`](Obstacle::outline), [`bounds`](Obstacle::bounds) | front ends, through the snapshot | what to draw, the region to show |
//! | [`written::build`] | the scene reader (`scene`) | the obstacle from its `type` and keys |
//!
//! | file | idea |
//! |---|---|
//! | `kind` | what every kind answers ([`Kind`]), and the shape table's answers a kind may leave to it |
//! | `written` | how a kind is written in a scene file, in words that know no file format: its `type` word, its keys, the key lookup ([`Keys`]) |
//! | `kinds/*.rs` | one kind each: its struct, its formulas, its scene words and how it builds itself |
//!
//! **A new kind is one file in `kinds/`**: a struct named as its file (`kinds/ground.rs` holds
//! `Ground`) implementing [`Kind`]. The build script (`build.rs`) lists the folder: each file
//! becomes a module, a variant of [`Obstacle`] and an entry of the scene reader's list
//! (`obstacle_kinds!` below). Its keys need nothing else either: the scene reader reads any key a
//! kind declares ([`Key`]: a number, three numbers or a rotation).
//!
//! The shape table answers for any kind whose shape is in it: the contact falls through to
//! `shape_shape`, and the point tests to `point_shape` ([`table_gap`]). The kinds written so far
//! answer the point tests and some contacts with their own exact formulas (`detect`'s; the
//! ground's and the aligned box's contact without a pose): those are what the lessons'
//! numbers were computed with, and they keep a box's faces at its written `min` and `max` to
//! the last bit (its pose, centre ± half, is off by round-off), and the swept test's entry
//! face. A test checks that the two answers agree to round-off.

pub mod kind;
pub mod written;

pub use kind::{table_gap, Kind};
pub use written::{Key, Keys, Value, Written};

use super::detect::Penetration;
use super::geometry::{ContactPoint, Pose, Shape};
use nalgebra::Vector3;

/// Builds, from the list of kinds (`module::Kind`, one per file of `kinds/`): the [`Obstacle`]
/// enum with a variant per kind, its methods (each asks the kind held), and the scene reader's
/// list ([`written`]).
macro_rules! obstacle_kinds {
    ($($module:ident :: $kind:ident),* $(,)?) => {
        pub use kinds::{$($module::$kind),*};

        /// A fixed obstacle: one of the kinds of `kinds/`, each variant named as its kind.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum Obstacle {
            $(
                #[doc = concat!("A [`", stringify!($kind), "`].")]
                $kind($kind),
            )*
        }

        $(
            impl From<$kind> for Obstacle {
                fn from(kind: $kind) -> Obstacle {
                    Obstacle::$kind(kind)
                }
            }
        )*

        impl Obstacle {
            /// The scene-file name of this obstacle's type.
            pub fn kind(&self) -> &'static str {
                match self {
                    $(Obstacle::$kind(_) => <$kind as Kind>::WORD,)*
                }
            }

            /// Whether the obstacle is a half-space (ground, plane): a vertex below it is
            /// inside however fast it came, so it needs no swept test.
            pub fn is_half_space(&self) -> bool {
                match self {
                    $(Obstacle::$kind(k) => k.is_half_space(),)*
                }
            }

            /// The obstacle as a static body of the shape table: its shape and where it is.
            pub fn shape(&self) -> (Shape, Pose) {
                match self {
                    $(Obstacle::$kind(k) => k.shape(),)*
                }
            }

            /// Appends the contact points of shape A at `pa` against the obstacle (B) to
            /// `out`: the shape table's pair (`geometry::shape_shape`), or the kind's own.
            pub fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
                match self {
                    $(Obstacle::$kind(k) => k.contact(a, pa, margin, out),)*
                }
            }

            /// How deep a point lies inside the obstacle (0 when outside), m.
            pub fn depth(&self, p: &Vector3<f64>) -> f64 {
                match self {
                    $(Obstacle::$kind(k) => k.depth(p),)*
                }
            }

            /// Static test (`detect`): is `p` inside? Depth > 0 and the outward normal.
            #[inline]
            pub fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
                match self {
                    $(Obstacle::$kind(k) => k.inside(p),)*
                }
            }

            /// Swept test (`detect`): the point moved from `a` (start of the step) to `b`
            /// (now). The contact through the entry face if the segment entered within the
            /// step and `b` lies beyond the entry plane; the static test at `b` if it was
            /// already inside at `a`.
            pub fn swept(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Penetration> {
                match self {
                    $(Obstacle::$kind(k) => k.swept(a, b),)*
                }
            }

            /// A point just *outside* (`detect`), less than `margin` from the surface: the
            /// gap ≥ 0 (m) and the outward normal of the nearest surface point. None inside
            /// or farther.
            #[inline]
            pub fn near(&self, p: &Vector3<f64>, margin: f64) -> Option<(f64, Vector3<f64>)> {
                let (gap, normal) = match self {
                    $(Obstacle::$kind(k) => k.gap(p)?,)*
                };
                (gap >= 0.0 && gap < margin).then_some((gap, normal))
            }

            /// The signed gap (< 0 inside) and the outward normal at the nearest surface
            /// point by the shape table (`geometry::point_shape`): what a kind without its
            /// own point formulas uses; the others agree with it to round-off (tests).
            pub fn table_gap(&self, p: &Vector3<f64>) -> (f64, Vector3<f64>) {
                match self {
                    $(Obstacle::$kind(k) => table_gap(k, p),)*
                }
            }

            /// What a front end draws (world coordinates; read through the snapshot).
            pub fn outline(&self) -> Outline {
                match self {
                    $(Obstacle::$kind(k) => k.outline(),)*
                }
            }

            /// The corners (low, high) of a box the view must hold to show the obstacle;
            /// `centre` is where the bodies are (an unbounded obstacle is shown where they
            /// are).
            pub fn bounds(&self, centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
                match self {
                    $(Obstacle::$kind(k) => k.bounds(centre),)*
                }
            }
        }

        /// Every kind the scene file writes by its own `type`, in file order.
        fn written_kinds() -> Vec<(&'static str, Written)> {
            let mut kinds = Vec::new();
            $(
                if let Some(w) = <$kind as Kind>::WRITTEN {
                    kinds.push((<$kind as Kind>::WORD, w));
                }
            )*
            kinds
        }

        /// The kind written with `type = word`, built from its keys.
        fn build_kind<K: Keys>(word: &str, keys: &K) -> Option<Result<Obstacle, K::Error>> {
            $(
                if <$kind as Kind>::WRITTEN.is_some() && <$kind as Kind>::WORD == word {
                    return Some(<$kind as Kind>::build(keys));
                }
            )*
            None
        }
    };
}

// `pub mod kinds { … }` (a module per file of `kinds/`) and `obstacle_kinds!(…)` over them,
// written by `build.rs` from the folder's listing.
include!(concat!(env!("OUT_DIR"), "/obstacle_kinds.rs"));

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
    /// A fixed body (no obstacle kind's outline; see `snapshot::FixedView`): its wire, the
    /// vertices of a polyhedron or the circles of a round body (`physics::wire`), and the
    /// edges between them; its barycenter `center` and the radius of its bounding sphere
    /// (which edges are hidden behind it depends on them); a ball's `silhouette` radius.
    Body {
        corners: Vec<Vector3<f64>>,
        edges: Vec<(usize, usize)>,
        center: Vector3<f64>,
        radius: f64,
        silhouette: Option<f64>,
    },
}

impl Obstacle {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    fn all_kinds() -> Vec<Obstacle> {
        vec![
            Obstacle::Ground(Ground { height: 0.25 }),
            Obstacle::Sphere(Sphere {
                center: Vector3::new(0.1, 0.2, -0.3),
                radius: 0.7,
            }),
            Obstacle::AlignedBox(AlignedBox {
                min: Vector3::new(-0.5, -0.25, -1.0),
                max: Vector3::new(0.75, 0.5, 0.3),
            }),
            Obstacle::Plane(Plane {
                point: Vector3::new(0.0, 0.1, 0.0),
                normal: Vector3::new(-0.3, 1.0, 0.2).normalize(),
            }),
            Obstacle::RotatedBox(RotatedBox {
                center: Vector3::new(0.2, 0.1, 0.0),
                half: Vector3::new(0.5, 0.2, 0.4),
                rotation: Rotation3::from_axis_angle(&Vector3::z_axis(), 0.4).into_inner(),
            }),
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
        for o in all_kinds() {
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
        let half: Vec<bool> = all_kinds().iter().map(Obstacle::is_half_space).collect();
        assert_eq!(half, [true, false, false, true, false]);
    }

    /// A key lookup from plain values, as a reader of another format would give.
    struct Plain(Vec<(&'static str, Vec<f64>)>);

    impl Keys for Plain {
        type Error = String;
        fn finite(&self, key: &str) -> Result<f64, String> {
            let v = self
                .0
                .iter()
                .find(|(k, _)| *k == key)
                .ok_or(key.to_string())?;
            Ok(v.1[0])
        }
        fn positive(&self, key: &str) -> Result<f64, String> {
            self.finite(key)
                .and_then(|v| (v > 0.0).then_some(v).ok_or(format!("{key} ≤ 0")))
        }
        fn vector(&self, key: &str) -> Result<Vector3<f64>, String> {
            let v = self
                .0
                .iter()
                .find(|(k, _)| *k == key)
                .ok_or(key.to_string())?;
            Ok(Vector3::from_column_slice(&v.1))
        }
        fn rotation(&self, key: &str) -> Result<Option<nalgebra::UnitQuaternion<f64>>, String> {
            Ok(self
                .0
                .iter()
                .find(|(k, _)| *k == key)
                .map(|(_, v)| nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), v[0])))
        }
        fn wrong(&self, key: &str, message: String) -> String {
            format!("{key}: {message}")
        }
    }

    #[test]
    fn the_kinds_are_written_as_the_scene_file_contract_says() {
        // design.md's `[[obstacle]]` types, in the order messages list them, and their keys.
        let kinds: Vec<(&str, Vec<&str>)> = written::written()
            .iter()
            .map(|(word, w)| (*word, w.keys.iter().map(|k| k.name).collect()))
            .collect();
        assert_eq!(
            kinds,
            [
                ("ground", vec!["height"]),
                ("sphere", vec!["center", "radius"]),
                ("box", vec!["min", "max", "orientation"]),
                ("plane", vec!["point", "normal"]),
            ]
        );
        // A key holds one sort of value whichever kind names it; the unknown-key message lists
        // every key once, a rotation last.
        for key in written::all_keys() {
            for (_, w) in written::written() {
                if let Some(k) = w.keys.iter().find(|k| k.name == key.name) {
                    assert_eq!(k.value, key.value, "{}", key.name);
                }
            }
        }
        let all: Vec<&str> = written::all_keys().iter().map(|k| k.name).collect();
        assert_eq!(
            all,
            [
                "height",
                "center",
                "radius",
                "min",
                "max",
                "point",
                "normal",
                "orientation"
            ]
        );
        // Every kind's variant answers its own word.
        for o in all_kinds() {
            let written_as = if matches!(o, Obstacle::RotatedBox(_)) {
                "box"
            } else {
                o.kind()
            };
            assert_eq!(o.kind(), written_as);
        }
    }

    #[test]
    fn a_kind_builds_itself_from_any_key_lookup() {
        let sphere = written::build(
            "sphere",
            &Plain(vec![("center", vec![1.0, 2.0, 3.0]), ("radius", vec![0.5])]),
        );
        assert_eq!(
            sphere,
            Some(Ok(Obstacle::Sphere(Sphere {
                center: Vector3::new(1.0, 2.0, 3.0),
                radius: 0.5
            })))
        );
        let (min, max) = (vec![0.0, 0.0, 0.0], vec![2.0, 1.0, 1.0]);
        let turned = Plain(vec![
            ("min", min.clone()),
            ("max", max.clone()),
            ("orientation", vec![0.3]),
        ]);
        match written::build("box", &turned) {
            Some(Ok(Obstacle::RotatedBox(b))) => {
                assert_eq!(b.half, Vector3::new(1.0, 0.5, 0.5));
                assert!((b.rotation[(1, 0)] - 0.3f64.sin()).abs() < 1e-15);
            }
            other => panic!("{other:?}"),
        }
        let flat = Plain(vec![("min", min), ("max", vec![2.0, 0.0, 1.0])]);
        assert_eq!(
            written::build("box", &flat),
            Some(Err(
                "max: box obstacle needs min < max on every axis, found min [0.0, 0.0, 0.0] \
                      and max [2.0, 0.0, 1.0]"
                    .to_string()
            ))
        );
        let zero = Plain(vec![("point", vec![0.0; 3]), ("normal", vec![0.0; 3])]);
        assert!(written::build("plane", &zero)
            .unwrap()
            .unwrap_err()
            .starts_with("normal: "));
        assert_eq!(written::build("cone", &zero), None);
    }
}
