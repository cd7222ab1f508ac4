//! Warm starts by contact feature: last step's impulses, found in O(1) per contact.
//!
//! A pair's contacts (body A, what it touches) come out of detection together; the cache keeps
//! each pair's range of (feature, point, impulse) entries, so a new contact looks only among
//! its own pair's few entries for one with the same feature and a point within
//! [`MATCH_DISTANCE`] (a feature such as face–face names several points: the point tells them
//! apart). Up to [`SCAN_MAX`] pairs (a body on the ground, a small stack) the pairs are found
//! by a scan of their list; above it, through a hash map (the same answer either way: a pair
//! stored twice answers with its last range).

use super::{Against, Contact, Feature};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::ops::Range;

/// A stored point matches a new one closer than this, m.
pub const MATCH_DISTANCE: f64 = 1e-3;

/// Up to this many pairs a pair is found by scanning their list; above it, by hashing (a
/// scan of a few pairs costs less than hashing one key).
pub const SCAN_MAX: usize = 8;

/// A pair of surfaces: body A and what it touches.
type Pair = (usize, Against);

/// Last step's impulses by pair and feature.
#[derive(Debug, Clone, Default)]
pub struct WarmCache {
    entries: Vec<(Feature, Vector3<f64>, Vector3<f64>)>,
    /// Each pair's range of entries, in the order stored.
    list: Vec<(Pair, Range<usize>)>,
    /// The same, by pair: filled only above [`SCAN_MAX`] pairs.
    pairs: FastMap<Pair, Range<usize>>,
}

impl WarmCache {
    /// Forgets everything.
    pub fn clear(&mut self) {
        self.entries.clear();
        self.list.clear();
        self.pairs.clear();
    }

    /// Replaces the cache with `(contact, impulse)` pairs (a pair's contacts consecutive;
    /// a pair seen again later starts a new range that replaces the first).
    pub fn store<'a>(&mut self, items: impl Iterator<Item = (&'a Contact, Vector3<f64>)>) {
        self.clear();
        let mut current: Option<(Pair, usize)> = None;
        for (c, j) in items {
            let key = (c.body, c.against);
            match current {
                Some((k, _)) if k == key => {}
                Some((k, start)) => {
                    self.list.push((k, start..self.entries.len()));
                    current = Some((key, self.entries.len()));
                }
                None => current = Some((key, self.entries.len())),
            }
            self.entries.push((c.feature, c.point, j));
        }
        if let Some((k, start)) = current {
            self.list.push((k, start..self.entries.len()));
        }
        if self.list.len() > SCAN_MAX {
            // Inserted in order: a pair seen again replaces its first range.
            self.pairs.extend(self.list.iter().cloned());
        }
    }

    /// The impulse stored for the same pair and feature at a point within [`MATCH_DISTANCE`].
    pub fn find(&self, c: &Contact) -> Option<Vector3<f64>> {
        let key = (c.body, c.against);
        let range = if self.list.len() > SCAN_MAX {
            self.pairs.get(&key)?
        } else {
            // The last range stored for the pair, as the map keeps it.
            &self.list.iter().rev().find(|(k, _)| *k == key)?.1
        };
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Body `body` against obstacle `obstacle`, vertex `vertex` at x = `x`.
    fn contact(body: usize, obstacle: usize, vertex: usize, x: f64) -> Contact {
        Contact::new(
            body,
            Against::Obstacle(obstacle),
            Feature::Vertex(vertex),
            Vector3::new(x, 0.0, 0.0),
            1e-6,
            Vector3::y(),
        )
    }

    /// `pairs` pairs (body p on obstacle 0) of two vertices each, impulse (p, vertex, 0); then
    /// body 0 again with impulse (−1, vertex, 0): a pair seen twice answers with its last range.
    fn stored(pairs: usize) -> (WarmCache, Vec<Contact>) {
        let mut items = Vec::new();
        for p in 0..pairs {
            for vertex in 0..2 {
                items.push((contact(p, 0, vertex, 0.1 * vertex as f64), p as f64));
            }
        }
        for vertex in 0..2 {
            items.push((contact(0, 0, vertex, 0.1 * vertex as f64), -1.0));
        }
        let mut cache = WarmCache::default();
        cache.store(
            items
                .iter()
                .map(|(c, p)| (c, Vector3::new(*p, c.point.x * 10.0, 0.0))),
        );
        (cache, items.into_iter().map(|(c, _)| c).collect())
    }

    #[test]
    fn the_scan_and_the_map_give_each_pair_its_last_impulses() {
        // Few pairs (the scan) and many (the map): the same answers.
        for pairs in [2, 3, SCAN_MAX - 1, SCAN_MAX, SCAN_MAX + 4] {
            let (cache, contacts) = stored(pairs);
            assert_eq!(cache.pairs.is_empty(), cache.list.len() <= SCAN_MAX);
            for c in &contacts {
                let expected_pair = if c.body == 0 { -1.0 } else { c.body as f64 };
                let expected = Vector3::new(expected_pair, c.point.x * 10.0, 0.0);
                assert_eq!(cache.find(c), Some(expected), "{pairs} pairs, {c:?}");
            }
            // Same pair, a point 2 mm away, or another feature: nothing.
            let mut far = contacts[2];
            far.point.x += 2.0 * MATCH_DISTANCE;
            assert_eq!(cache.find(&far), None);
            let mut other = contacts[2];
            other.feature = Feature::Vertex(7);
            assert_eq!(cache.find(&other), None);
            // A pair never stored: nothing.
            assert_eq!(cache.find(&contact(0, 1, 0, 0.0)), None);
        }
    }
}
