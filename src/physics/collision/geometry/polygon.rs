//! A polygon's vertex loop (or any short list of points) kept on the stack: contact generation
//! runs every step for every touching pair, so it must not allocate.
//!
//! Capacity [`CAPACITY`] = 32 points: a box face clipped by a box face has at most 8, a face of
//! k corners clipped by one of m at most k + m. Points pushed past the capacity are dropped
//! (only a hull face of more than 16 corners against another can reach it); the remaining points
//! still lie inside the true overlap, so a contact stays where the shapes touch.

use nalgebra::Vector3;
use std::ops::{Deref, DerefMut};

/// How many points a [`Polygon`] holds.
pub const CAPACITY: usize = 32;

/// Up to [`CAPACITY`] points, in order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polygon {
    points: [Vector3<f64>; CAPACITY],
    len: usize,
}

impl Default for Polygon {
    fn default() -> Self {
        Polygon::new()
    }
}

impl Polygon {
    /// An empty polygon.
    pub fn new() -> Polygon {
        Polygon {
            points: [Vector3::zeros(); CAPACITY],
            len: 0,
        }
    }

    /// Removes every point.
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// Appends `p` (dropped when full).
    #[inline]
    pub fn push(&mut self, p: Vector3<f64>) {
        if self.len < CAPACITY {
            self.points[self.len] = p;
            self.len += 1;
        }
    }

    /// Keeps the first `len` points.
    pub fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }
}

impl Deref for Polygon {
    type Target = [Vector3<f64>];
    fn deref(&self) -> &[Vector3<f64>] {
        &self.points[..self.len]
    }
}

impl DerefMut for Polygon {
    fn deref_mut(&mut self) -> &mut [Vector3<f64>] {
        &mut self.points[..self.len]
    }
}

impl Extend<Vector3<f64>> for Polygon {
    fn extend<I: IntoIterator<Item = Vector3<f64>>>(&mut self, points: I) {
        for p in points {
            self.push(p);
        }
    }
}

impl FromIterator<Vector3<f64>> for Polygon {
    fn from_iter<I: IntoIterator<Item = Vector3<f64>>>(points: I) -> Polygon {
        let mut polygon = Polygon::new();
        polygon.extend(points);
        polygon
    }
}

impl<'a> IntoIterator for &'a Polygon {
    type Item = &'a Vector3<f64>;
    type IntoIter = std::slice::Iter<'a, Vector3<f64>>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}
