//! Face contact: clip the incident face against the reference face (Sutherland–Hodgman), keep
//! the points below the reference face, and thin the manifold to at most 4 well-spread points.
//!
//! ```text
//! reference face: plane n·p = d, loop v₀ … v_{m−1} counter-clockwise seen from outside (along n)
//! side plane of edge vᵢ → vᵢ₊₁:   outward normal sᵢ = (vᵢ₊₁ − vᵢ) × n;  inside: sᵢ·(p − vᵢ) ≤ 0
//! Sutherland–Hodgman, one side plane at a time, for each polygon edge p → q
//!     (signed distances δp, δq to the plane):
//!     δp ≤ 0  keep p;    δp, δq of opposite signs  add p + (q − p) δp/(δp − δq)
//! depth of a kept point p below the reference face: depth = d − n·p   (keep depth ≥ −margin)
//! ```
//!
//! Thinning (when more than 4 points survive, e.g. two equal boxes twisted face to face give 8):
//! keep the deepest point p₁; the point farthest from it p₂; the point making the largest
//! triangle with them (area ∝ n·((p₂ − p₁) × (p − p₁))) p₃ on one side of p₁p₂; the largest on
//! the other side p₄. Four points that span the overlap hold a resting face as well as eight.

use super::polyhedron::Polygon;
use nalgebra::Vector3;

/// Clips `input` by the half-space s·(p − o) ≤ 0 into `output` (cleared first).
pub fn clip_by_plane(input: &Polygon, output: &mut Polygon, s: &Vector3<f64>, o: &Vector3<f64>) {
    output.clear();
    let Some(&last) = input.last() else {
        return;
    };
    // Each edge p → q, starting with the closing edge (last → first).
    let (mut p, mut dp) = (last, s.dot(&(last - o)));
    for &q in input.iter() {
        let dq = s.dot(&(q - o));
        if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
            output.push(p + (q - p) * (dp / (dp - dq)));
        }
        if dq <= 0.0 {
            output.push(q);
        }
        (p, dp) = (q, dq);
    }
}

/// Clips `incident` to the prism over the `reference` loop of outward normal `n`. The two
/// buffers take turns as input and output; the result is left in `incident`.
pub fn clip_to_face(
    incident: &mut Polygon,
    scratch: &mut Polygon,
    reference: &Polygon,
    n: &Vector3<f64>,
) {
    let Some(&last) = reference.last() else {
        return;
    };
    let mut in_scratch = false;
    let mut v = last;
    for &w in reference.iter() {
        let side = (w - v).cross(n);
        let (from, to) = if in_scratch {
            (&*scratch, &mut *incident)
        } else {
            (&*incident, &mut *scratch)
        };
        // Nothing outside this side plane (a box on a larger box): nothing to cut.
        if from.iter().all(|p| side.dot(&(p - v)) <= 0.0) {
            v = w;
            continue;
        }
        clip_by_plane(from, to, &side, &v);
        in_scratch = !in_scratch;
        v = w;
        if to.is_empty() {
            break;
        }
    }
    if in_scratch {
        *incident = *scratch;
    }
}

/// Thins `points` and their `depths` (same order) to at most 4 (see the module doc); `n` is
/// the face normal.
pub fn reduce_to_four(points: &mut Polygon, depths: &mut [f64], n: &Vector3<f64>) {
    if points.len() <= 4 {
        return;
    }
    fn argmax(count: usize, score: impl Fn(usize) -> f64) -> usize {
        let mut best = (0, f64::NEG_INFINITY);
        for i in 0..count {
            let x = score(i);
            if x > best.1 {
                best = (i, x);
            }
        }
        best.0
    }
    let count = points.len();
    let first = argmax(count, |i| depths[i]);
    let p1 = points[first];
    let second = argmax(count, |i| (points[i] - p1).norm_squared());
    let p2 = points[second];
    let area = |i: usize| n.dot(&(p2 - p1).cross(&(points[i] - p1)));
    let third = argmax(count, area);
    let fourth = argmax(count, |i| -area(i));
    let mut chosen = [first, second, third, fourth];
    chosen.sort_unstable();
    // Move the chosen ones to the front, in order (each goes to a slot at or before its own).
    let mut kept = 0;
    for (k, &i) in chosen.iter().enumerate() {
        if k > 0 && chosen[k - 1] == i {
            continue;
        }
        points[kept] = points[i];
        depths[kept] = depths[i];
        kept += 1;
    }
    points.truncate(kept);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(h: f64, z: f64) -> Polygon {
        let mut p = Polygon::new();
        p.extend([
            Vector3::new(h, h, z),
            Vector3::new(-h, h, z),
            Vector3::new(-h, -h, z),
            Vector3::new(h, -h, z),
        ]);
        p
    }

    #[test]
    fn a_square_clipped_by_a_square_turned_45_degrees_is_an_octagon() {
        // Square of half-side 1 against the same square turned 45° about z: the overlap is a
        // regular octagon, its corners at distance 1/cos(22.5°) = 1.0824 from the centre.
        let reference = square(1.0, 0.0);
        let (c, s) = (0.5f64.sqrt(), 0.5f64.sqrt());
        let mut incident: Polygon = square(1.0, 0.0)
            .iter()
            .map(|p| Vector3::new(c * p.x - s * p.y, s * p.x + c * p.y, 0.0))
            .collect();
        let mut scratch = Polygon::new();
        clip_to_face(&mut incident, &mut scratch, &reference, &Vector3::z());
        assert_eq!(incident.len(), 8);
        let r = 1.0 / (std::f64::consts::PI / 8.0).cos();
        for p in &incident {
            assert!((p.norm() - r).abs() < 1e-12, "{p:?}");
        }
    }

    #[test]
    fn a_face_inside_the_reference_is_kept_whole() {
        let reference = square(1.0, 0.0);
        let mut incident = square(0.2, -0.01);
        let mut scratch = Polygon::new();
        clip_to_face(&mut incident, &mut scratch, &reference, &Vector3::z());
        assert_eq!(*incident, *square(0.2, -0.01));
    }

    #[test]
    fn eight_points_thin_to_four_spread_ones() {
        // The octagon of radius 1: the deepest point (index 0, depth 0.02) is kept, then the
        // opposite corner (farthest), then the two corners farthest from that diameter.
        let mut points: Polygon = (0..8)
            .map(|k| {
                let t = k as f64 * std::f64::consts::PI / 4.0;
                Vector3::new(t.cos(), t.sin(), 0.0)
            })
            .collect();
        let mut depths = [0.01; 8];
        depths[0] = 0.02;
        reduce_to_four(&mut points, &mut depths, &Vector3::z());
        assert_eq!(points.len(), 4);
        let expected = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
        for (p, (x, y)) in points.iter().zip(expected) {
            assert!((p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12, "{p:?}");
        }
        assert_eq!(depths[0], 0.02);
    }
}
