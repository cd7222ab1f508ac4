//! Contacts kept across steps (`soft-step`): while the bodies have barely moved since the last
//! detection, its rows are carried to the current poses instead of being found again — the
//! contact recycling of Box2D v3 and Rapier, with a far tighter bound.
//!
//! A row found at poses (x_A, R_A), (x_B, R_B) at point p with normal n and depth d₀ is kept
//! as the point on each body, `a = R_Aᵀ(p − x_A)`, `b = R_Bᵀ(p − x_B)`, and the normal in B's
//! frame. B is found by its solver body entry (`Contact::other`): a body's own pose, or, for
//! an obstacle's static entry after the bodies, the world frame (x_B = 0, R_B = 𝟙: b = p). At new poses the two points are
//! `p_A = x_A' + R_A' a`, `p_B = x_B' + R_B' b`, the normal `n' = R_B' n_B`, and
//!
//! ```text
//! depth = d₀ − n'·(p_A − p_B)
//! ```
//!
//! (A moving out along n by δ takes δ off the depth); the row's point is p_A and its levers
//! `p_A − x_A'`, `p_A − x_B'`. Exact for a translation or rotation of the pair together; the
//! error is what the contact geometry would have changed: of the order of the relative motion.
//!
//! The rows are carried only while every body's motion since the detection,
//! `|x − x₀| + r·θ` (r its bounding radius, θ the angle it turned), stays below
//! [`KEEP_DISTANCE`], a tenth of the 1 mm speculative margin: a point that was further than the
//! margin from a surface at the detection cannot have reached it, and a kept point is off by
//! less than that. A stack or a pyramid at rest is detected again only when its slow settling
//! adds up to a tenth of a millimetre; a scene where something moves is detected every step
//! (the bound is the world's, not the pair's). The rows are carried only when the step starts
//! where the last one ended (not after a restore or an outside change of the states).

use super::Contact;
use crate::physics::body::Body;
use crate::physics::state::State;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// The most a body may have moved since the detection for its rows to be carried, m.
pub const KEEP_DISTANCE: f64 = 1e-4;

/// A row as found, and its points and normal in the frames of its bodies.
#[derive(Debug, Clone, Copy)]
struct KeptRow {
    contact: Contact,
    /// The point in A's frame.
    on_a: Vector3<f64>,
    /// The point in B's frame (world for an obstacle).
    on_b: Vector3<f64>,
    /// The normal in B's frame (world for an obstacle).
    normal_b: Vector3<f64>,
}

/// The last detection's rows and poses.
#[derive(Debug, Clone, Default)]
pub struct Kept {
    /// Each body's pose at the detection (empty: nothing kept).
    poses: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// Each body's bounding radius, m.
    radius: Vec<f64>,
    rows: Vec<KeptRow>,
    /// The margin the rows were found with.
    margin: f64,
    /// The states the last step ended at (the rows are carried only from there).
    ended: Vec<State>,
    rotations: Vec<Matrix3<f64>>,
}

impl Kept {
    /// Forgets everything: the next step detects.
    pub fn forget(&mut self) {
        self.poses.clear();
        self.rows.clear();
        self.ended.clear();
    }

    /// Keeps `contacts`, found at `states` with `margin`.
    pub fn remember(
        &mut self,
        bodies: &[Body],
        states: &[State],
        margin: f64,
        contacts: &[Contact],
    ) {
        self.poses.clear();
        self.poses.extend(
            states
                .iter()
                .map(|s| (s.position, s.orientation.quaternion())),
        );
        self.radius.clear();
        self.radius.extend(bodies.iter().map(|b| {
            let shape = b.shape.as_ref().map_or(0.0, |s| s.bounding_radius());
            b.radius.max(shape)
        }));
        self.margin = margin;
        self.rotations.clear();
        self.rotations
            .extend(states.iter().map(|s| s.orientation.matrix()));
        let rotations = &self.rotations;
        self.rows.clear();
        self.rows.extend(contacts.iter().map(|c| {
            let on_a = rotations[c.body].tr_mul(&(c.point - states[c.body].position));
            // B by its solver body entry: a body's own frame, or the world frame of an
            // obstacle's static entry (past the bodies).
            let (on_b, normal_b) = match states.get(c.other) {
                None => (c.point, c.normal),
                Some(b) => (
                    rotations[c.other].tr_mul(&(c.point - b.position)),
                    rotations[c.other].tr_mul(&c.normal),
                ),
            };
            KeptRow {
                contact: *c,
                on_a,
                on_b,
                normal_b,
            }
        }));
    }

    /// Notes the states the step ended at.
    pub fn ended_at(&mut self, states: &[State]) {
        self.ended.clear();
        self.ended.extend_from_slice(states);
    }

    /// The kept rows carried to `states` into `out`, and whether any touches (depth > 0); None
    /// when they cannot be carried (nothing kept, another margin, the step does not start where
    /// the last one ended, or a body moved more than [`KEEP_DISTANCE`]): detect again.
    pub fn carry(
        &mut self,
        bodies: &[Body],
        before: &[State],
        states: &[State],
        margin: f64,
        out: &mut Vec<Contact>,
    ) -> Option<bool> {
        let continues = self.ended.len() == before.len()
            && self
                .ended
                .iter()
                .zip(before)
                .all(|(e, b)| e.position == b.position && e.orientation == b.orientation);
        if self.poses.len() != states.len() || margin != self.margin || !continues {
            return None;
        }
        for (((s, (x0, q0)), r), body) in
            states.iter().zip(&self.poses).zip(&self.radius).zip(bodies)
        {
            if body.fixed {
                continue;
            }
            let turned = (s.orientation.quaternion() * q0.inverse()).angle();
            if (s.position - x0).norm() + r * turned > KEEP_DISTANCE {
                return None;
            }
        }
        self.rotations.clear();
        self.rotations
            .extend(states.iter().map(|s| s.orientation.matrix()));
        let rotations = &self.rotations;
        out.clear();
        out.extend(self.rows.iter().map(|k| {
            let c = &k.contact;
            let a = &states[c.body];
            let lever = rotations[c.body] * k.on_a;
            let on_a = a.position + lever;
            let (on_b, normal, lever_other) = match states.get(c.other) {
                None => (k.on_b, k.normal_b, Vector3::zeros()),
                Some(s) => (
                    s.position + rotations[c.other] * k.on_b,
                    rotations[c.other] * k.normal_b,
                    on_a - s.position,
                ),
            };
            Contact {
                point: on_a,
                depth: c.depth - normal.dot(&(on_a - on_b)),
                normal,
                lever,
                lever_other,
                ..*c
            }
        }));
        Some(out.iter().any(|c| c.depth > 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::collision::{Against, Feature};
    use crate::physics::state::Orientation;

    fn cube_at(position: Vector3<f64>, q: UnitQuaternion<f64>) -> State {
        State {
            position,
            orientation: Orientation::Quaternion(q),
            ..State::at_rest()
        }
    }

    /// A cube's corner 0.1 mm inside the ground, carried as the cube sinks 20 µm and turns:
    /// the depth, the point and the lever follow the corner exactly (a half-space's rows are
    /// the corners themselves).
    #[test]
    fn a_kept_ground_row_follows_its_corner() {
        let cube = Body::solid_box(Vector3::repeat(0.2), 1.0).unwrap();
        let start = cube_at(
            Vector3::new(0.0, 0.1 - 1e-4, 0.0),
            UnitQuaternion::identity(),
        );
        let corner = Vector3::new(0.1, -0.1, 0.1);
        let found = Contact {
            lever: corner,
            // The ground's static entry, after the one body.
            other: 1,
            ..Contact::new(
                0,
                Against::Obstacle(0),
                Feature::Vertex(0),
                start.position + corner,
                1e-4,
                Vector3::y(),
            )
        };
        let mut kept = Kept::default();
        let bodies = [cube];
        kept.remember(&bodies, &[start], 1e-3, &[found]);
        kept.ended_at(&[start]);
        let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 1e-4);
        let now = cube_at(start.position - Vector3::new(0.0, 2e-5, 0.0), q);
        let mut out = Vec::new();
        assert_eq!(
            kept.carry(&bodies, &[start], &[now], 1e-3, &mut out),
            Some(true)
        );
        let p = now.position + q * corner;
        assert!((out[0].point - p).norm() < 1e-15);
        assert!((out[0].lever - q * corner).norm() < 1e-15);
        assert!(
            (out[0].depth - (-p.y)).abs() < 1e-15,
            "{} vs {}",
            out[0].depth,
            -p.y
        );
        // Moved too far, another margin, or not where the last step ended: detect again.
        let far = cube_at(start.position + Vector3::new(2e-4, 0.0, 0.0), q);
        assert_eq!(kept.carry(&bodies, &[start], &[far], 1e-3, &mut out), None);
        assert_eq!(kept.carry(&bodies, &[start], &[now], 2e-3, &mut out), None);
        assert_eq!(kept.carry(&bodies, &[now], &[now], 1e-3, &mut out), None);
    }

    /// Two cubes that move together keep their rows' depth and normal (turned with them).
    #[test]
    fn a_pair_moving_together_keeps_its_depth() {
        let cube = Body::solid_box(Vector3::repeat(0.2), 1.0).unwrap();
        let a = cube_at(Vector3::new(0.0, 0.3, 0.0), UnitQuaternion::identity());
        let b = cube_at(Vector3::new(0.0, 0.1, 0.0), UnitQuaternion::identity());
        let point = Vector3::new(0.1, 0.2, 0.1);
        let found = Contact {
            lever: point - a.position,
            lever_other: point - b.position,
            ..Contact::new(
                0,
                Against::Body(1),
                Feature::Vertex(0),
                point,
                3e-5,
                Vector3::y(),
            )
        };
        let bodies = [cube.clone(), cube];
        let mut kept = Kept::default();
        kept.remember(&bodies, &[a, b], 1e-3, &[found]);
        kept.ended_at(&[a, b]);
        // Both turned by the same small rotation about the origin and shifted alike.
        let q = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1e-4);
        let shift = Vector3::new(1e-5, -2e-5, 0.0);
        let moved = |s: &State| cube_at(q * s.position + shift, q);
        let mut out = Vec::new();
        let now = [moved(&a), moved(&b)];
        assert_eq!(
            kept.carry(&bodies, &[a, b], &now, 1e-3, &mut out),
            Some(true)
        );
        assert!((out[0].depth - 3e-5).abs() < 1e-15);
        assert!((out[0].normal - q * Vector3::y()).norm() < 1e-15);
        assert!((out[0].point - (q * point + shift)).norm() < 1e-15);
    }
}
