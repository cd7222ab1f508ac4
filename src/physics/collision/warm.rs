//! Warm starts by contact feature: last step's impulses, found in O(1) per contact.
//!
//! A pair's contacts (body A, what it touches) come out of detection together; the cache keeps
//! each pair's range of (feature, point, impulse) entries in a hash map, so a new contact
//! looks only among its own pair's few entries for one with the same feature and a point
//! within [`MATCH_DISTANCE`] (a feature such as face–face names several points: the point
//! tells them apart).

use super::{Against, Contact, Feature};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::ops::Range;

/// A stored point matches a new one closer than this, m.
pub const MATCH_DISTANCE: f64 = 1e-3;

/// Last step's impulses by pair and feature.
#[derive(Debug, Clone, Default)]
pub struct WarmCache {
    entries: Vec<(Feature, Vector3<f64>, Vector3<f64>)>,
    pairs: FastMap<(usize, Against), Range<usize>>,
}

impl WarmCache {
    /// Forgets everything.
    pub fn clear(&mut self) {
        self.entries.clear();
        self.pairs.clear();
    }

    /// Replaces the cache with `(contact, impulse)` pairs (a pair's contacts consecutive;
    /// a pair seen again later starts a new range that replaces the first).
    pub fn store<'a>(&mut self, items: impl Iterator<Item = (&'a Contact, Vector3<f64>)>) {
        self.clear();
        let mut current: Option<((usize, Against), usize)> = None;
        for (c, j) in items {
            let key = (c.body, c.against);
            match current {
                Some((k, _)) if k == key => {}
                Some((k, start)) => {
                    self.pairs.insert(k, start..self.entries.len());
                    current = Some((key, self.entries.len()));
                }
                None => current = Some((key, self.entries.len())),
            }
            self.entries.push((c.feature, c.point, j));
        }
        if let Some((k, start)) = current {
            self.pairs.insert(k, start..self.entries.len());
        }
    }

    /// The impulse stored for the same pair and feature at a point within [`MATCH_DISTANCE`].
    pub fn find(&self, c: &Contact) -> Option<Vector3<f64>> {
        let range = self.pairs.get(&(c.body, c.against))?;
        self.entries[range.clone()]
            .iter()
            .find(|(f, p, _)| {
                *f == c.feature && (p - c.point).norm_squared() < MATCH_DISTANCE * MATCH_DISTANCE
            })
            .map(|(_, _, j)| *j)
    }
}

/// A hash map with [`FastHasher`]: the solver's keys are a few small integers, looked up once
/// per contact per step, where the standard SipHash cost more than the lookup it served.
pub type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// The multiply–rotate hash of rustc's `FxHasher`: `h ← (rotl(h, 5) ⊕ word) · K` per 64-bit
/// word. Not resistant to chosen keys (none here: body indices and normals' bits), and
/// deterministic; the maps are only looked up, never iterated, so it changes no result.
#[derive(Debug, Clone, Copy, Default)]
pub struct FastHasher {
    hash: u64,
}

impl FastHasher {
    const K: u64 = 0x517c_c1b7_2722_0a95;

    fn add(&mut self, word: u64) {
        self.hash = (self.hash.rotate_left(5) ^ word).wrapping_mul(Self::K);
    }
}

impl Hasher for FastHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(word));
        }
    }

    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }

    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }

    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }

    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }

    fn finish(&self) -> u64 {
        self.hash
    }
}
