//! `tumble FILE --against THEIRS.csv`: a run computed elsewhere drawn as the ghost, and the
//! first step where it parts from tumble's marked (the run pauses there, the status line names
//! it). The rows and the parting come from [`crate::diff`], exactly as `tumble diff` finds them.

use crate::diff::theirs::{Column, Theirs};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// A body's pose: barycenter x and rotation R (body → world).
pub type Pose = (Vector3<f64>, Matrix3<f64>);

/// Their run as the app shows it.
#[derive(Debug, Clone, PartialEq)]
pub struct Against {
    /// THEIRS.csv as given.
    pub name: String,
    /// Per row: its step, and the body's pose when their columns give one (x y z; R, else q,
    /// else unturned).
    pub poses: Vec<(u64, Option<Pose>)>,
    /// The first step where they part, and the column farthest apart there (None: they agree).
    pub parting: Option<(u64, String)>,
}

impl Against {
    /// Their rows' poses and the first parting step of a `tumble diff` check.
    pub fn new(name: String, theirs: &Theirs, outcome: &crate::diff::Outcome) -> Against {
        let index = |c: Column| theirs.columns.iter().position(|&k| k == c);
        let position = [0, 1, 2].map(|i| index(Column::X(i)));
        let matrix: Vec<Option<usize>> = (0..9).map(|k| index(Column::R(k / 3, k % 3))).collect();
        let quaternion = [0, 1, 2, 3].map(|i| index(Column::Q(i)));
        let poses = (theirs.rows.iter())
            .map(|row| {
                let v = |k: Option<usize>| k.map(|k| row.values[k]);
                let pose = match position.map(v) {
                    [Some(x), Some(y), Some(z)] => {
                        let rotation = if matrix.iter().all(Option::is_some) {
                            Matrix3::from_fn(|i, j| row.values[matrix[3 * i + j].unwrap_or(0)])
                        } else if let [Some(w), Some(i), Some(j), Some(k)] = quaternion.map(v) {
                            UnitQuaternion::from_quaternion(Quaternion::new(w, i, j, k))
                                .to_rotation_matrix()
                                .into_inner()
                        } else {
                            Matrix3::identity()
                        };
                        Some((Vector3::new(x, y, z), rotation))
                    }
                    _ => None,
                };
                (
                    row.step,
                    pose.filter(|(x, r)| x.iter().chain(r.iter()).all(|c| c.is_finite())),
                )
            })
            .collect();
        let parting = outcome.first_row.map(|r| {
            let column = (outcome.comparison.columns.iter())
                .zip(&outcome.comparison.apart[r])
                .max_by(|a, b| a.1.total_cmp(b.1))
                .map_or(String::new(), |(c, _)| c.column.name());
            (theirs.rows[r].step, column)
        });
        Against {
            name,
            poses,
            parting,
        }
    }

    /// Their pose at `step`: their last row at or before it.
    pub fn pose_at(&self, step: u64) -> Option<Pose> {
        let k = self.poses.partition_point(|(s, _)| *s <= step);
        k.checked_sub(1).and_then(|k| self.poses[k].1)
    }

    /// The status line's words: where they part, or that they agree.
    pub fn status(&self) -> String {
        match &self.parting {
            Some((step, column)) => format!("part at step {step} ({column})"),
            None => "agree".to_string(),
        }
    }
}
