//! The history ring: the last frames' starts, for stepping back exactly (a saved state is
//! restored, nothing is integrated backwards). Also the source of the barycenter trail.
//!
//! Every frame start keeps its barycenter (the trail, 24 bytes). Whole checkpoints are kept
//! only at **keyframes**, every K frames; the worlds at frame n are rebuilt by restoring the
//! newest keyframe k ≤ n and stepping n − k frames again. Stepping is deterministic — the same
//! checkpoint stepped under the same settings gives the same bits — so the rebuilt state is
//! exactly the one the forward run had (`tests/app/history.rs` checks it bit for bit).
//!
//! ```text
//! bytes  = heap bytes of a keyframe (world, and compare world if on) + its own size
//! avail  = budget − capacity · size_of(Entry)                 (the ring's per-frame part)
//! room   = ⌊avail / bytes⌋                                    (checkpoints that fit)
//! K      = 1                                  without cloths (every frame whole, as before)
//!        = the least ⌈capacity / keys⌉ with   with cloths: any `capacity` frames in a row
//!          ⌈capacity / K⌉ + ⌈√K⌉ ≤ room                 hold ⌈capacity / K⌉ keyframes, and
//!                                                       stepping back adds ⌈√K⌉ marks
//! replay = n − k < K frames per step back; the first one into a segment leaves rewind marks
//!          every ⌈√(n − k)⌉ frames (at most ⌈√K⌉ checkpoints, dropped by the next frame
//!          pushed), so ← held replays at most that many frames each time after
//! ```
//!
//! A keyframe is also taken at the first frame start after anything that replay could not
//! reproduce: a switch of integrator or collision response ([`Stepping`]), the compare world
//! starting, stopping or being rebuilt ([`History::break_segment`]). Between two keyframes the
//! worlds were stepped under the settings stored with the first one, so replay uses those.
//!
//! The ring drops its oldest frames when it holds `capacity` frames or its keyframes pass the
//! byte budget; frames before the oldest keyframe cannot be rebuilt, so they go with it.

use crate::physics::{Checkpoint, Stepping, World};
use nalgebra::Vector3;
use std::collections::VecDeque;
use std::mem::size_of;

/// How many frames are kept by default.
pub const DEFAULT_CAPACITY: usize = 10_000;

/// The most bytes the ring holds by default (keyframes and per-frame entries).
pub const DEFAULT_BUDGET: usize = 64 << 20;

/// One saved frame start.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Barycenter of the first body at that moment (for the trail).
    pub position: Vector3<f64>,
    /// The worlds whole, if this frame is a keyframe.
    pub key: Option<Box<Keyframe>>,
}

/// The worlds at a keyframe and the settings they were stepped with from there.
#[derive(Debug, Clone)]
pub struct Keyframe {
    pub world: Checkpoint,
    pub stepping: Stepping,
    /// The compare world and its settings, if compare mode was on.
    pub compare: Option<(Checkpoint, Stepping)>,
    /// Heap bytes plus the keyframe's own size.
    pub bytes: usize,
}

/// What [`History::pop_into`] restored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Restored {
    /// Whether the compare world was restored too (false: it was not on at that frame, or
    /// no compare world was given).
    pub compare: bool,
}

/// A bounded ring of frame starts; the oldest are dropped when full.
#[derive(Debug, Clone)]
pub struct History {
    entries: VecDeque<Entry>,
    capacity: usize,
    budget: usize,
    /// K: frames from one keyframe to the next.
    interval: usize,
    /// Σ bytes of the keyframes held.
    key_bytes: usize,
    /// The next frame start is kept whole.
    fresh: bool,
    /// Rewind marks: checkpoints after the keyframe of the segment last stepped back into,
    /// in frame order; dropped by the next push.
    rewind: Vec<Mark>,
}

/// A frame start kept whole for a while, so that ← held through a segment replays about
/// √K frames each time, not about K/2 (see [`History::pop_frames_into`]).
#[derive(Debug, Clone)]
struct Mark {
    index: usize,
    world: Checkpoint,
    compare: Option<Checkpoint>,
}

impl History {
    /// A ring of `capacity` frames under [`DEFAULT_BUDGET`] bytes.
    pub fn new(capacity: usize) -> History {
        History::with_budget(capacity, DEFAULT_BUDGET)
    }

    /// A ring of `capacity` frames under `budget` bytes.
    pub fn with_budget(capacity: usize, budget: usize) -> History {
        History {
            entries: VecDeque::with_capacity(capacity.max(1)),
            capacity: capacity.max(1),
            budget,
            interval: 1,
            key_bytes: 0,
            fresh: true,
            rewind: Vec::new(),
        }
    }

    /// Saves a frame start: the barycenter `position`, and the worlds whole when the frame is
    /// a keyframe (module doc). `compare` is the compare world, if compare mode is on.
    pub fn push(&mut self, position: Vector3<f64>, world: &World, compare: Option<&World>) {
        self.rewind.clear();
        if self.entries.len() == self.capacity {
            self.drop_oldest();
        }
        let stepping = world.stepping();
        let compare_stepping = compare.map(World::stepping);
        let keyframe = self.fresh
            || match self.newest_key() {
                None => true,
                Some((k, key)) => {
                    self.entries.len() - k >= self.interval
                        || key.stepping != stepping
                        || key.compare.as_ref().map(|c| c.1) != compare_stepping
                }
            };
        let key = keyframe.then(|| {
            let checkpoint = world.checkpoint();
            let compare = compare.map(|w| (w.checkpoint(), w.stepping()));
            let bytes = size_of::<Keyframe>()
                + checkpoint.heap_bytes()
                + compare.as_ref().map_or(0, |c| c.0.heap_bytes());
            self.interval = if checkpoint.has_cloths() {
                let avail = self
                    .budget
                    .saturating_sub(self.capacity * size_of::<Entry>());
                interval(self.capacity, avail / bytes)
            } else {
                1
            };
            self.key_bytes += bytes;
            self.fresh = false;
            Box::new(Keyframe {
                world: checkpoint,
                stepping,
                compare,
                bytes,
            })
        });
        self.entries.push_back(Entry { position, key });
        while self.heap_bytes() > self.budget && self.keyframes() > 1 {
            self.drop_oldest();
        }
    }

    /// The next frame start pushed is kept whole (the compare world was rebuilt or replaced:
    /// replay could not reproduce it).
    pub fn break_segment(&mut self) {
        self.fresh = true;
    }

    /// The world and the compare world trade places in every frame kept (the app follows the
    /// compare world when its own diverged): frames from before the compare world was last
    /// started, which hold no compare world, are dropped.
    pub fn swap_worlds(&mut self) {
        self.rewind.clear();
        self.fresh = true;
        while let Some(last_without) = self
            .entries
            .iter()
            .rposition(|e| e.key.as_ref().is_some_and(|k| k.compare.is_none()))
        {
            for _ in 0..=last_without {
                if let Some(Entry { key: Some(key), .. }) = self.entries.pop_front() {
                    self.key_bytes -= key.bytes;
                }
            }
            while self.entries.front().is_some_and(|e| e.key.is_none()) {
                self.entries.pop_front();
            }
        }
        for entry in &mut self.entries {
            if let Some(key) = entry.key.as_deref_mut() {
                if let Some((checkpoint, stepping)) = key.compare.as_mut() {
                    std::mem::swap(&mut key.world, checkpoint);
                    std::mem::swap(&mut key.stepping, stepping);
                }
            }
        }
    }

    /// Drops the oldest frame, and the frames after it up to the next keyframe (they cannot be
    /// rebuilt without it).
    fn drop_oldest(&mut self) {
        if let Some(Entry { key: Some(key), .. }) = self.entries.pop_front() {
            self.key_bytes -= key.bytes;
        }
        while self.entries.front().is_some_and(|e| e.key.is_none()) {
            self.entries.pop_front();
        }
    }

    /// The newest keyframe and its index.
    fn newest_key(&self) -> Option<(usize, &Keyframe)> {
        self.entries
            .iter()
            .enumerate()
            .rev()
            .find_map(|(i, e)| e.key.as_deref().map(|k| (i, k)))
    }

    /// Puts `world` (and `compare`, if given and kept) at frame start `index`: the newest
    /// keyframe at or before it (or a rewind mark after that keyframe) restored, then stepped
    /// again up to it under the keyframe's settings; the worlds keep their own settings
    /// afterwards. A replay of 16 frames or more from the keyframe leaves rewind marks every
    /// ⌈√frames⌉ frames. Returns whether `compare` was restored, or None if there is no such
    /// frame.
    fn rebuild(
        &mut self,
        index: usize,
        world: &mut World,
        compare: Option<&mut World>,
    ) -> Option<Restored> {
        let History {
            entries, rewind, ..
        } = self;
        let (k, key) = entries
            .iter()
            .enumerate()
            .take(index + 1)
            .rev()
            .find_map(|(i, e)| e.key.as_deref().map(|key| (i, key)))?;
        let with_compare = compare.is_some() && key.compare.is_some();
        rewind
            .retain(|m| m.index > k && m.index <= index && (m.compare.is_some() || !with_compare));
        let own = world.stepping();
        let compare_own = compare.as_deref().map(World::stepping);
        world.set_stepping(key.stepping);
        let start = match rewind.last() {
            Some(mark) => {
                world.restore(&mark.world);
                mark.index
            }
            None => {
                world.restore(&key.world);
                k
            }
        };
        let compare = match (compare, &key.compare) {
            (Some(w), Some((checkpoint, stepping))) => {
                w.set_stepping(*stepping);
                match rewind.last().and_then(|m| m.compare.as_ref()) {
                    Some(c) => w.restore(c),
                    None => w.restore(checkpoint),
                }
                Some(w)
            }
            _ => None,
        };
        let frames = index - start;
        let stride = if start == k && frames >= 16 {
            (frames as f64).sqrt().ceil() as usize
        } else {
            0
        };
        let mut compare = compare;
        for done in 0..frames {
            if stride > 0 && done > 0 && done % stride == 0 {
                rewind.push(Mark {
                    index: start + done,
                    world: world.checkpoint(),
                    compare: compare.as_deref().map(World::checkpoint),
                });
            }
            world.step();
            // A compare world that diverged stays frozen there, as in the forward run.
            if let Some(w) = compare.as_deref_mut().filter(|w| w.divergence().is_none()) {
                w.step();
            }
        }
        world.set_stepping(own);
        let restored = compare.is_some();
        if let (Some(w), Some(own)) = (compare, compare_own) {
            w.set_stepping(own);
        }
        Some(Restored { compare: restored })
    }

    /// Puts the worlds at the newest frame start and removes it from the ring (stepping
    /// back); None when the ring is empty.
    pub fn pop_into(&mut self, world: &mut World, compare: Option<&mut World>) -> Option<Restored> {
        self.pop_frames_into(1, world, compare)
    }

    /// Puts the worlds at the `frames`-th newest frame start (at most the oldest kept) and
    /// removes it and every newer one from the ring: `frames` steps back at the cost of one
    /// (at most K − 1 frames replayed). None when the ring is empty or `frames` is 0.
    pub fn pop_frames_into(
        &mut self,
        frames: usize,
        world: &mut World,
        compare: Option<&mut World>,
    ) -> Option<Restored> {
        if frames == 0 || self.entries.is_empty() {
            return None;
        }
        let index = self.entries.len() - frames.min(self.entries.len());
        let restored = self.rebuild(index, world, compare);
        while self.entries.len() > index {
            if let Some(Entry { key: Some(key), .. }) = self.entries.pop_back() {
                self.key_bytes -= key.bytes;
            }
        }
        restored
    }

    /// Puts the worlds at the newest frame start, keeping it in the ring; None when empty.
    pub fn restore_last(
        &mut self,
        world: &mut World,
        compare: Option<&mut World>,
    ) -> Option<Restored> {
        self.rebuild(self.entries.len().checked_sub(1)?, world, compare)
    }

    pub fn clear(&mut self) {
        self.entries.clear();
        self.rewind.clear();
        self.key_bytes = 0;
        self.fresh = true;
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// K, the frames from one keyframe to the next (1: every frame is kept whole).
    pub fn interval(&self) -> usize {
        self.interval
    }

    /// How many keyframes the ring holds.
    pub fn keyframes(&self) -> usize {
        self.entries.iter().filter(|e| e.key.is_some()).count()
    }

    /// The bytes the ring holds: its entries (allocated for `capacity` frames at the start;
    /// the ring never holds more), its keyframes and its rewind marks (while stepping back).
    pub fn heap_bytes(&self) -> usize {
        self.entries.capacity() * size_of::<Entry>() + self.key_bytes + self.rewind_bytes()
    }

    /// The bytes of the rewind marks: at most ⌈√K⌉ checkpoints, held only while stepping
    /// back (the next frame pushed drops them).
    pub fn rewind_bytes(&self) -> usize {
        self.rewind
            .iter()
            .map(|m| {
                size_of::<Mark>()
                    + m.world.heap_bytes()
                    + m.compare.as_ref().map_or(0, Checkpoint::heap_bytes)
            })
            .sum()
    }

    /// The last `n` barycenter positions, oldest first.
    pub fn trail(&self, n: usize) -> impl Iterator<Item = &Vector3<f64>> {
        let skip = self.entries.len().saturating_sub(n);
        self.entries.iter().skip(skip).map(|e| &e.position)
    }
}

/// K for a ring of `capacity` frames with room for `room` checkpoints: the fewest frames
/// between keyframes such that any `capacity` frames in a row hold `keys` = ⌈capacity/K⌉
/// keyframes and the ⌈√K⌉ rewind marks fit, keys + ⌈√K⌉ ≤ room (K = capacity when not even
/// one keyframe and its marks fit).
fn interval(capacity: usize, room: usize) -> usize {
    let marks = |k: usize| (k as f64).sqrt().ceil() as usize;
    (1..=capacity)
        .rev()
        .map(|keys| capacity.div_ceil(keys))
        .find(|&k| capacity.div_ceil(k) + marks(k) <= room)
        .unwrap_or(capacity)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::{Body, Effects, Integrator, State};

    fn world() -> World {
        let body = Body::solid_box(Vector3::new(1.0, 1.0, 1.0), 1.0).unwrap();
        World::new(
            body,
            Effects::default(),
            vec![],
            None,
            Integrator::Rk4,
            0.1,
            State::at_rest(),
        )
    }

    #[test]
    fn a_full_ring_drops_its_oldest_entry() {
        let world = world();
        let mut history = History::new(3);
        for i in 0..5 {
            history.push(Vector3::new(i as f64, 0.0, 0.0), &world, None);
        }
        assert_eq!(history.len(), 3);
        assert_eq!(history.interval(), 1, "no cloth: every frame whole");
        assert_eq!(history.keyframes(), 3);
        let xs: Vec<f64> = history.trail(10).map(|p| p.x).collect();
        assert_eq!(
            xs,
            vec![2.0, 3.0, 4.0],
            "the two oldest of 0..5 are dropped"
        );
    }

    #[test]
    fn a_switch_of_integrator_starts_a_keyframe_and_replay_uses_the_old_one() {
        // The frame after a switch is a keyframe holding the new settings (with cloths, where
        // K > 1, replay depends on it: tests/app/history.rs).
        let mut w = world();
        let mut history = History::new(10);
        history.push(w.state().position, &w, None);
        w.step();
        w.set_integrator(Integrator::Euler);
        history.push(w.state().position, &w, None);
        let last = history.entries.back().unwrap().key.as_ref().unwrap();
        assert_eq!(last.stepping.integrator, Integrator::Euler);
        // Stepping back restores frame 1 and the world keeps running euler.
        let mut back = w.clone();
        back.step();
        history.pop_into(&mut back, None).unwrap();
        assert_eq!(back.checkpoint(), w.checkpoint());
        assert_eq!(back.integrator(), Integrator::Euler);
    }
}
