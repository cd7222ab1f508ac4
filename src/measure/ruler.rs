//! The ruler: the distance between two points of the scene, each a fixed point of the world
//! or a point carried by a body (its barycenter, a point given in its frame, a joint's or a
//! spring's anchor), read from the bodies' states:
//!
//! ```text
//! a body's point:  p = x + R r        (r in the body's frame, m from the barycenter; r = 0: x)
//! reading:         d = p_to − p_from,  distance |d|
//! ```

use crate::physics::joints::Links;
use crate::physics::State;
use nalgebra::Vector3;

/// Where one end of the ruler is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Point {
    /// A fixed point of the world, m.
    World(Vector3<f64>),
    /// A point carried by body `body`: `offset` in its frame, m from its barycenter.
    Body { body: usize, offset: Vector3<f64> },
}

impl Point {
    /// Its world position for these states (None: no such body).
    pub fn position(&self, states: &[State]) -> Option<Vector3<f64>> {
        match *self {
            Point::World(p) => Some(p),
            Point::Body { body, offset } => {
                let s = states.get(body)?;
                Some(s.position + s.orientation.matrix() * offset)
            }
        }
    }
}

/// An end of the ruler and the name it is shown by (`bob`, `rod.b`, `(0, 2, 0)`).
#[derive(Debug, Clone, PartialEq)]
pub struct End {
    pub point: Point,
    pub name: String,
}

/// The ruler: from one end to the other.
#[derive(Debug, Clone, PartialEq)]
pub struct Ruler {
    pub from: End,
    pub to: End,
}

/// What the ruler reads: both ends in the world, their difference and its length, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    pub from: Vector3<f64>,
    pub to: Vector3<f64>,
    pub delta: Vector3<f64>,
    pub distance: f64,
}

impl Ruler {
    /// The reading for these states (None: an end's body is not in them).
    pub fn read(&self, states: &[State]) -> Option<Reading> {
        let from = self.from.point.position(states)?;
        let to = self.to.point.position(states)?;
        let delta = to - from;
        Some(Reading {
            from,
            to,
            delta,
            distance: delta.norm(),
        })
    }
}

/// The points of a scene that have names, in the order keys cycle through them: each body's
/// barycenter (`bob`), then each joint's and each spring's two anchors (`rod.a` on its first
/// body, `rod.b` on its second body or in the world).
pub fn named_points(bodies: &[String], links: &Links) -> Vec<End> {
    let pairs = links
        .joints
        .iter()
        .map(|j| (j.name.as_str(), j.a, j.b, j.anchor_a, j.anchor_b))
        .chain(
            links
                .springs
                .iter()
                .map(|s| (s.name.as_str(), s.a, s.b, s.anchor_a, s.anchor_b)),
        );
    named_points_of(bodies, pairs)
}

/// [`named_points`] of the bodies' names and each link's (name, first body, second body or
/// the world, anchor on the first in its frame, anchor on the second in its frame or the
/// world's), joints first, then springs.
pub fn named_points_of<'a>(
    bodies: &[String],
    links: impl IntoIterator<Item = (&'a str, usize, Option<usize>, Vector3<f64>, Vector3<f64>)>,
) -> Vec<End> {
    let mut ends: Vec<End> = bodies
        .iter()
        .enumerate()
        .map(|(body, name)| End {
            point: Point::Body {
                body,
                offset: Vector3::zeros(),
            },
            name: name.clone(),
        })
        .collect();
    for (name, a, b, anchor_a, anchor_b) in links {
        ends.push(End {
            point: Point::Body {
                body: a,
                offset: anchor_a,
            },
            name: format!("{name}.a"),
        });
        ends.push(End {
            point: match b {
                Some(body) => Point::Body {
                    body,
                    offset: anchor_b,
                },
                None => Point::World(anchor_b),
            },
            name: format!("{name}.b"),
        });
    }
    ends
}

/// The point a click at world point `p` sets: on the body whose barycenter is nearest to `p`
/// within `reach` (m) — then the point moves with the body — else the fixed point `p`.
/// `depth`: the axis the view looks along (its coordinate of `p` is unknown): distances leave
/// it out, and a body's point takes the body's own depth.
pub fn point_at(
    p: Vector3<f64>,
    states: &[State],
    movable: &[bool],
    depth: Option<usize>,
    reach: f64,
) -> Point {
    let flat = |v: Vector3<f64>| {
        let mut v = v;
        if let Some(d) = depth {
            v[d] = 0.0;
        }
        v
    };
    let nearest = states
        .iter()
        .enumerate()
        .filter(|(i, _)| movable.get(*i).copied().unwrap_or(true))
        .map(|(i, s)| (i, flat(s.position - p).norm()))
        .filter(|&(_, d)| d <= reach)
        .min_by(|a, b| a.1.total_cmp(&b.1));
    match nearest {
        Some((body, _)) => {
            let s = &states[body];
            let mut at = p;
            if let Some(d) = depth {
                at[d] = s.position[d];
            }
            Point::Body {
                body,
                offset: s.orientation.matrix().transpose() * (at - s.position),
            }
        }
        None => Point::World(p),
    }
}

/// A fixed point's name: `(0, 2, 0)`, each coordinate in the shortest form that reads back.
pub fn world_name(p: &Vector3<f64>) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::Orientation;
    use nalgebra::{UnitQuaternion, Vector3};

    fn body_at(x: [f64; 3], degrees_about_z: f64) -> State {
        State {
            position: Vector3::from(x),
            orientation: Orientation::Quaternion(UnitQuaternion::from_axis_angle(
                &Vector3::z_axis(),
                degrees_about_z.to_radians(),
            )),
            ..State::at_rest()
        }
    }

    #[test]
    fn a_corner_of_a_turned_box_is_read_where_the_rotation_puts_it() {
        // Body at (1, 2, 0) turned 90° about z: its point (0.5, 0, 0) is at (1, 2.5, 0); to
        // the fixed point (4, 6.5, 0): Δ = (3, 4, 0), 5 m (a 3-4-5 triangle).
        let states = [body_at([1.0, 2.0, 0.0], 90.0)];
        let ruler = Ruler {
            from: End {
                point: Point::Body {
                    body: 0,
                    offset: Vector3::new(0.5, 0.0, 0.0),
                },
                name: "box".into(),
            },
            to: End {
                point: Point::World(Vector3::new(4.0, 6.5, 0.0)),
                name: "(4, 6.5, 0)".into(),
            },
        };
        let r = ruler.read(&states).unwrap();
        assert!(
            (r.from - Vector3::new(1.0, 2.5, 0.0)).norm() < 1e-15,
            "{r:?}"
        );
        assert!(
            (r.delta - Vector3::new(3.0, 4.0, 0.0)).norm() < 1e-15,
            "{r:?}"
        );
        assert!((r.distance - 5.0).abs() < 1e-15, "{r:?}");
        // An end on a body the scene lacks reads nothing.
        assert_eq!(ruler.read(&[]), None);
    }

    #[test]
    fn a_click_near_a_body_sets_a_point_that_moves_with_it() {
        // Front view (depth z): a click at (1.1, 2, 7) is 0.1 m from the body at (1, 2, 0.3)
        // in the view plane: the point is the body's, at depth 0.3, offset (0.1, 0, 0)
        // turned back by −90°: (0, −0.1, 0) in the body's frame. Far from it: a fixed point.
        let states = [body_at([1.0, 2.0, 0.3], 90.0)];
        let p = point_at(Vector3::new(1.1, 2.0, 7.0), &states, &[true], Some(2), 0.2);
        let Point::Body { body: 0, offset } = p else {
            panic!("{p:?}")
        };
        assert!(
            (offset - Vector3::new(0.0, -0.1, 0.0)).norm() < 1e-15,
            "{offset}"
        );
        assert!((p.position(&states).unwrap() - Vector3::new(1.1, 2.0, 0.3)).norm() < 1e-15);
        let far = point_at(Vector3::new(3.0, 2.0, 0.0), &states, &[true], Some(2), 0.2);
        assert_eq!(far, Point::World(Vector3::new(3.0, 2.0, 0.0)));
        // A fixed body is never picked.
        let held = point_at(Vector3::new(1.1, 2.0, 0.3), &states, &[false], Some(2), 0.2);
        assert!(matches!(held, Point::World(_)));
    }
}
