//! The history ring: the last frames' full checkpoints, for stepping back exactly (a saved state
//! is restored, nothing is integrated backwards). Also the source of the barycenter trail.

use crate::physics::Checkpoint;
use nalgebra::Vector3;
use std::collections::VecDeque;

/// How many frames are kept by default.
pub const DEFAULT_CAPACITY: usize = 10_000;

/// One saved frame start.
#[derive(Debug, Clone)]
pub struct Entry {
    /// The world at the start of the frame.
    pub world: Checkpoint,
    /// The compare world at the same moment, if compare mode was on.
    pub compare: Option<Checkpoint>,
    /// Barycenter at that moment (for the trail).
    pub position: Vector3<f64>,
}

/// A bounded ring of frame starts; the oldest is dropped when full.
#[derive(Debug, Clone)]
pub struct History {
    entries: VecDeque<Entry>,
    capacity: usize,
}

impl History {
    pub fn new(capacity: usize) -> History {
        History {
            entries: VecDeque::with_capacity(capacity.min(1024)),
            capacity: capacity.max(1),
        }
    }

    pub fn push(&mut self, entry: Entry) {
        if self.entries.len() == self.capacity {
            self.entries.pop_front();
        }
        self.entries.push_back(entry);
    }

    /// The most recent entry, removed.
    pub fn pop(&mut self) -> Option<Entry> {
        self.entries.pop_back()
    }

    /// The most recent entry.
    pub fn last(&self) -> Option<&Entry> {
        self.entries.back()
    }

    pub fn clear(&mut self) {
        self.entries.clear();
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The last `n` barycenter positions, oldest first.
    pub fn trail(&self, n: usize) -> impl Iterator<Item = &Vector3<f64>> {
        let skip = self.entries.len().saturating_sub(n);
        self.entries.iter().skip(skip).map(|e| &e.position)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::{Body, Effects, Integrator, State, World};

    #[test]
    fn a_full_ring_drops_its_oldest_entry() {
        let body = Body::solid_box(Vector3::new(1.0, 1.0, 1.0), 1.0).unwrap();
        let world = World::new(
            body,
            Effects::default(),
            vec![],
            None,
            Integrator::Rk4,
            0.1,
            State::at_rest(),
        );
        let mut history = History::new(3);
        for i in 0..5 {
            history.push(Entry {
                world: world.checkpoint(),
                compare: None,
                position: Vector3::new(i as f64, 0.0, 0.0),
            });
        }
        assert_eq!(history.len(), 3);
        let xs: Vec<f64> = history.trail(10).map(|p| p.x).collect();
        assert_eq!(
            xs,
            vec![2.0, 3.0, 4.0],
            "the two oldest of 0..5 are dropped"
        );
    }
}
