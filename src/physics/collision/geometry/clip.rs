//! Face contact: clip the incident face against the reference face (Sutherland–Hodgman), keep
//! the points below the reference face, and thin the manifold to at most 4 well-spread points.
//!
//! ```text
//! reference face: plane n·p = d, loop v₀ … v_{m−1} counter-clockwise seen from outside (along n)
//! side plane of edge vᵢ → vᵢ₊₁:   outward normal sᵢ = (vᵢ₊₁ − vᵢ) × n;  inside: sᵢ·(p − vᵢ) ≤ 0
//! Sutherland–Hodgman, one side plane at a time, for each polygon edge p → q
//!     (signed distances δp, δq to the plane, and a band τ = ON_PLANE·|sᵢ|² of points taken
//!     as lying on it):
//!     δq ≤ τ  keep q;    δp < −τ < τ < δq or δq < −τ < τ < δp   add p + (q − p) δp/(δp − δq)
//! depth of a kept point p below the reference face: depth = d − n·p   (keep depth ≥ −margin)
//! ```
//!
//! The band matters when faces of equal size meet edge on edge (a cube on a cube, a cube
//! straddling two others): the incident corners lie on the side planes to round-off, and
//! without it a corner 1e-17 outside is cut at an arbitrary point of an edge parallel to the
//! plane, or dropped. The manifold then changed from step to step (2, 3 or 4 points, corners
//! moving by centimetres) while nothing moved by a nanometre, and the warm start lost those
//! contacts' impulses: a pyramid of 20 rows fell back on its direct solve 91 times in its
//! first second (3.3 ms a step), 6 times with the band (1.5 ms a step). A corner within the
//! band is kept as it is, at most τ/|sᵢ| = ON_PLANE·|edge| (0.2 µm on a 20 cm cube) outside
//! the prism.
//!
//! Thinning (when more than 4 points survive, e.g. two equal boxes twisted face to face give 8):
//! keep the deepest point p₁; the point farthest from it p₂; the point making the largest
//! triangle with them (area ∝ n·((p₂ − p₁) × (p − p₁))) p₃ on one side of p₁p₂; the largest on
//! the other side p₄. Four points that span the overlap hold a resting face as well as eight.

use super::polyhedron::Polygon;
use nalgebra::Vector3;

/// Points within this fraction of a reference edge's length of its side plane lie on it.
pub const ON_PLANE: f64 = 1e-6;

/// Clips `input` by the half-space s·(p − o) ≤ 0 into `output` (cleared first); a point with
/// s·(p − o) ≤ `band` is inside.
pub fn clip_by_plane(
    input: &Polygon,
    output: &mut Polygon,
    s: &Vector3<f64>,
    o: &Vector3<f64>,
    band: f64,
) {
    output.clear();
    let Some(&last) = input.last() else {
        return;
    };
    // Each edge p → q, starting with the closing edge (last → first).
    let (mut p, mut dp) = (last, s.dot(&(last - o)));
    for &q in input.iter() {
        let dq = s.dot(&(q - o));
        if (dp < -band && dq > band) || (dp > band && dq < -band) {
            output.push(p + (q - p) * (dp / (dp - dq)));
        }
        if dq <= band {
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
        let band = ON_PLANE * side.norm_squared();
        let (from, to) = if in_scratch {
            (&*scratch, &mut *incident)
        } else {
            (&*incident, &mut *scratch)
        };
        // Nothing outside this side plane (a box on a larger box): nothing to cut.
        if from.iter().all(|p| side.dot(&(p - v)) <= band) {
            v = w;
            continue;
        }
        clip_by_plane(from, to, &side, &v, band);
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
    fn a_face_straddling_the_reference_edge_on_edge_keeps_the_four_corners_of_the_overlap() {
        // A cube on two cubes below it: the incident square (half-side 1) is shifted by 1
        // along x, so the overlap is x ∈ [0, 1], y ∈ [−1, 1], and its edges y = ±1 lie on the
        // reference's side planes. Turned by round-off (1e-16 to 1e-10 rad) and moved by
        // 1e-15, the overlap keeps its four corners to 1e-9 (without the band, a corner
        // 1e-17 outside a side plane is cut anywhere along the edge, or lost).
        let reference = square(1.0, 0.0);
        let exact = [(1.0, 1.0), (0.0, 1.0), (0.0, -1.0), (1.0, -1.0)];
        for angle in [
            1e-16f64, -1e-16, 3e-14, -3e-14, 1e-12, -1e-12, 1e-10, -1e-10,
        ] {
            for shift in [1e-15, -1e-15] {
                let (c, s) = (angle.cos(), angle.sin());
                let mut incident: Polygon = square(1.0, -1e-12)
                    .iter()
                    .map(|p| Vector3::new(c * p.x - s * p.y + 1.0, s * p.x + c * p.y + shift, p.z))
                    .collect();
                let mut scratch = Polygon::new();
                clip_to_face(&mut incident, &mut scratch, &reference, &Vector3::z());
                assert_eq!(incident.len(), 4, "angle {angle}: {incident:?}");
                for (x, y) in exact {
                    let near = incident
                        .iter()
                        .any(|p| (p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9);
                    assert!(
                        near,
                        "angle {angle}: corner ({x}, {y}) missing in {incident:?}"
                    );
                }
            }
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
