//! The forces on the bodies as arrows a front end draws: where each acts and how large (world
//! frame, N). Every number is one the loop computed and the snapshot carries; nothing is
//! stepped or solved again here.
//!
//! ```text
//! gravity   F = M g                 at each free body's barycenter
//! contact   F = J / dt              at the contact point, on body A (−J / dt on B, a body)
//! joint     F = the reaction        at the first body's anchor (its opposite at the second's)
//! spring    F = k (|d| − ℓ₀) d̂     at each end, d̂ towards the other end (damping not drawn)
//! ```
//!
//! A contact's and a joint's force is the step's mean (impulse / dt), as the panels show it.

use super::snapshot::Snapshot;
use super::Against;
use nalgebra::Vector3;

/// What a force arrow stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ForceKind {
    Gravity,
    Contact,
    Joint,
    Spring,
}

impl ForceKind {
    /// One letter for a legend or a label: g, c, j, s.
    pub fn letter(self) -> &'static str {
        match self {
            ForceKind::Gravity => "g",
            ForceKind::Contact => "c",
            ForceKind::Joint => "j",
            ForceKind::Spring => "s",
        }
    }
}

/// One force: its kind, the body it acts on (index), where it acts (m) and the force (N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceArrow {
    pub kind: ForceKind,
    pub body: usize,
    pub at: Vector3<f64>,
    pub force: Vector3<f64>,
}

/// Every force on every free body of the snapshot's world; `gravity` is the scene's g (None
/// without gravity).
pub fn force_arrows(s: &Snapshot, gravity: Option<Vector3<f64>>) -> Vec<ForceArrow> {
    let mut out = Vec::new();
    let index = |name: &str| s.bodies.iter().position(|b| b.name == name);
    let free = |i: usize| s.bodies.get(i).is_some_and(|b| !b.fixed);
    if let Some(g) = gravity {
        for (i, b) in s.bodies.iter().enumerate().filter(|(i, _)| free(*i)) {
            out.push(ForceArrow {
                kind: ForceKind::Gravity,
                body: i,
                at: b.position,
                force: g * b.mass,
            });
        }
    }
    if s.dt > 0.0 {
        for c in &s.contacts {
            let f = c.impulse / s.dt;
            if f == Vector3::zeros() {
                continue;
            }
            if free(c.body) {
                out.push(ForceArrow {
                    kind: ForceKind::Contact,
                    body: c.body,
                    at: c.point,
                    force: f,
                });
            }
            if let Against::Body(other) = c.against {
                if free(other) {
                    out.push(ForceArrow {
                        kind: ForceKind::Contact,
                        body: other,
                        at: c.point,
                        force: -f,
                    });
                }
            }
        }
    }
    for j in &s.joints {
        let pairs = [
            (Some(j.bodies.0.as_str()), 0, 1.0),
            (j.bodies.1.as_deref(), 1, -1.0),
        ];
        for (name, end, sign) in pairs {
            if let Some(i) = name.and_then(index).filter(|&i| free(i)) {
                out.push(ForceArrow {
                    kind: ForceKind::Joint,
                    body: i,
                    at: j.anchors[end],
                    force: j.force * sign,
                });
            }
        }
    }
    for sp in &s.springs {
        let d = sp.ends[1] - sp.ends[0];
        let Some(unit) = d.try_normalize(1e-12) else {
            continue;
        };
        let pull = unit * sp.tension;
        let pairs = [
            (Some(sp.bodies.0.as_str()), 0, 1.0),
            (sp.bodies.1.as_deref(), 1, -1.0),
        ];
        for (name, end, sign) in pairs {
            if let Some(i) = name.and_then(index).filter(|&i| free(i)) {
                out.push(ForceArrow {
                    kind: ForceKind::Spring,
                    body: i,
                    at: sp.ends[end],
                    force: pull * sign,
                });
            }
        }
    }
    out
}
