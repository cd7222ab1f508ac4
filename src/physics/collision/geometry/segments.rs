//! The closest points of two segments (for edge–edge contact).
//!
//! ```text
//! P(s) = p + s d₁, s ∈ [0, 1];   Q(t) = q + t d₂, t ∈ [0, 1];   r = p − q
//! a = d₁·d₁, e = d₂·d₂, b = d₁·d₂, c = d₁·r, f = d₂·r,  denominator a e − b² ≥ 0
//! unclamped minimum of |P(s) − Q(t)|²:  s = (b f − c e)/(a e − b²)    (s = 0 if parallel)
//! then clamp s to [0, 1], t = (b s + f)/e; if t leaves [0, 1] clamp it and recompute
//! s = clamp((b t − c)/a)
//! a segment of length 0 (a point): the other's parameter alone, e.g. e = 0: s = clamp(−c/a)
//! ```
//!
//! (Ericson, *Real-Time Collision Detection*, §5.1.9.)

use nalgebra::Vector3;

/// The closest points (on the first segment, on the second) of segments p₀p₁ and q₀q₁.
pub fn closest_points(
    p0: &Vector3<f64>,
    p1: &Vector3<f64>,
    q0: &Vector3<f64>,
    q1: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let r = p0 - q0;
    let a = d1.dot(&d1);
    let e = d2.dot(&d2);
    let b = d1.dot(&d2);
    let c = d1.dot(&r);
    let f = d2.dot(&r);
    let tiny = 1e-300;
    if a <= tiny && e <= tiny {
        return (*p0, *q0); // both segments are points
    }
    if e <= tiny {
        // The second segment is a point: project it on the first.
        let s = (-c / a).clamp(0.0, 1.0);
        return (p0 + d1 * s, *q0);
    }
    if a <= tiny {
        let t = (f / e).clamp(0.0, 1.0);
        return (*p0, q0 + d2 * t);
    }
    let denominator = a * e - b * b;
    let mut s = if denominator > 1e-12 * a * e {
        ((b * f - c * e) / denominator).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (p0 + d1 * s, q0 + d2 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossed_segments_meet_at_their_crossing_over_the_gap() {
        // x-axis segment at y = 0.3 and z-axis segment at y = 0: closest points (0.2, 0.3, 0)
        // and (0.2, 0, 0) when the second runs along z through x = 0.2.
        let (p, q) = closest_points(
            &Vector3::new(-1.0, 0.3, 0.0),
            &Vector3::new(1.0, 0.3, 0.0),
            &Vector3::new(0.2, 0.0, -1.0),
            &Vector3::new(0.2, 0.0, 1.0),
        );
        assert!((p - Vector3::new(0.2, 0.3, 0.0)).norm() < 1e-15, "{p:?}");
        assert!((q - Vector3::new(0.2, 0.0, 0.0)).norm() < 1e-15, "{q:?}");
    }

    #[test]
    fn a_point_projects_on_a_segment() {
        // Point (0.5, −0.1, −0.1) against the x-axis segment [0, 1]: foot (0.5, 0, 0).
        let p = Vector3::new(0.5, -0.1, -0.1);
        let (on, q) = closest_points(&Vector3::zeros(), &Vector3::x(), &p, &p);
        assert_eq!(on, Vector3::new(0.5, 0.0, 0.0));
        assert_eq!(q, p);
    }

    #[test]
    fn a_segment_past_the_end_of_the_other_clamps_to_its_end() {
        // Second segment along z at x = 3: the first's nearest point is its end (1, 0, 0).
        let (p, q) = closest_points(
            &Vector3::new(-1.0, 0.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0),
            &Vector3::new(3.0, 0.0, -1.0),
            &Vector3::new(3.0, 0.0, 1.0),
        );
        assert_eq!(p, Vector3::new(1.0, 0.0, 0.0));
        assert_eq!(q, Vector3::new(3.0, 0.0, 0.0));
    }
}
