//! A rigid body as a set of mass points, and its mass properties.
//!
//! As in the original practical, a body is a cloud of points `pᵢ` with masses `mᵢ`:
//!
//! ```text
//! M        = Σ mᵢ                                  total mass
//! c        = Σ mᵢ pᵢ / M                           barycenter (BaryCentre)
//! r₀ᵢ      = pᵢ − c                                body points about the barycenter (_ROi)
//! I_body   = Σ mᵢ ((r₀ᵢ·r₀ᵢ) 𝟙 − r₀ᵢ r₀ᵢᵀ)         body-space inertia tensor (_Ibody)
//! ```
//!
//! A solid box of sides (a, b, c) and mass M uses the closed form of the uniform solid instead:
//! `I_body = M/12 · diag(b² + c², a² + c², a² + b²)`; its 8 corners are still its points (for
//! drawing and collisions). The inertia tensor must be invertible: points on one line (or a single
//! point) cannot resist rotation about that line, so `from_points` refuses them.

use super::collision::geometry::{ConvexHull, Shape};
use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion, Vector3};

/// How the inertia of a body is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InertiaModel {
    /// The mass points themselves carry all the mass (the original report's model).
    Points,
    /// A uniform solid (closed-form tensor); the points only describe the shape.
    Solid,
}

/// A rigid body: its mass, its points about the barycenter and its body-space inertia.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Total mass M, kg.
    pub mass: f64,
    /// 1 / M.
    pub inv_mass: f64,
    /// Body points about the barycenter, r₀ᵢ (the report's `_ROi`), m.
    pub points_body: Vec<Vector3<f64>>,
    /// Where the barycenter lies in the coordinates the points were given in, m.
    pub barycenter: Vector3<f64>,
    /// Edges between points, for drawing (box edges, mesh edges; empty for a bare point set).
    pub edges: Vec<(usize, usize)>,
    /// Body-space inertia tensor about the barycenter (the report's `_Ibody`), kg·m².
    pub inertia_body: Matrix3<f64>,
    /// Its inverse (the report's `_IbodyInv`).
    pub inv_inertia_body: Matrix3<f64>,
    /// Principal moments I₁ ≤ I₂ ≤ I₃, kg·m².
    pub principal_moments: Vector3<f64>,
    /// Rotation from the principal frame to the body frame: `I_body = E diag(I₁,I₂,I₃) Eᵀ`.
    pub principal_axes: UnitQuaternion<f64>,
    /// Largest distance of a point from the barycenter, m (a length scale for views and guards).
    pub radius: f64,
    /// The convex shape contacts are computed on: the box itself, or the convex hull of the
    /// points (None when the points have no volume: then only the report's vertex test sees
    /// them).
    pub shape: Option<Shape>,
    /// Whether the body never moves (infinite mass: `inv_mass` and `inv_inertia_body` are 0).
    pub fixed: bool,
}

/// Why a body could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BodyError {
    #[error("a body needs at least one mass point")]
    NoPoints,
    #[error("mass must be positive and finite, found {0}")]
    BadMass(f64),
    #[error("{count} masses given for {points} points: give one mass per point")]
    MassCount { count: usize, points: usize },
    #[error("{0} must be positive and finite, found {1}")]
    BadLength(&'static str, f64),
    #[error("box sides must be positive and finite, found {0:?}")]
    BadSize([f64; 3]),
    #[error("a point coordinate is not finite")]
    NonFinite,
    #[error(
        "the {0} overflows (a number beyond ±1.8e308): the coordinates, sizes or masses are \
         too large to compute with"
    )]
    Overflow(&'static str),
    #[error(
        "the inertia tensor underflows (largest principal moment {0:.3e} kg·m², below the \
         smallest normal number 2.2e-308): the masses or sizes are too small to compute with"
    )]
    Underflow(f64),
    #[error(
        "the inertia tensor is singular (principal moments {0:.3e}, {1:.3e}, {2:.3e} kg·m²): \
         the points lie on one line or at one spot, so nothing resists rotation about that line; \
         add a point off the line or use a box"
    )]
    SingularInertia(f64, f64, f64),
}

impl Body {
    /// A body made of mass points. `masses` is either empty (the total `mass` shared equally) or
    /// one mass per point (then `mass` is ignored and their sum is the total).
    pub fn from_points(
        points: &[Vector3<f64>],
        masses: &[f64],
        mass: f64,
        edges: Vec<(usize, usize)>,
    ) -> Result<Body, BodyError> {
        if points.is_empty() {
            return Err(BodyError::NoPoints);
        }
        if points.iter().any(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(BodyError::NonFinite);
        }
        let masses: Vec<f64> = if masses.is_empty() {
            check_mass(mass)?;
            vec![mass / points.len() as f64; points.len()]
        } else if masses.len() != points.len() {
            return Err(BodyError::MassCount {
                count: masses.len(),
                points: points.len(),
            });
        } else {
            for &m in masses {
                check_mass(m)?;
            }
            masses.to_vec()
        };
        let total: f64 = masses.iter().sum();
        if !total.is_finite() {
            return Err(BodyError::Overflow("total mass"));
        }
        let barycenter = points
            .iter()
            .zip(&masses)
            .fold(Vector3::zeros(), |acc, (p, m)| acc + p * *m)
            / total;
        if !barycenter.iter().all(|c| c.is_finite()) {
            return Err(BodyError::Overflow("barycenter"));
        }
        let points_body: Vec<Vector3<f64>> = points.iter().map(|p| p - barycenter).collect();
        let inertia = point_inertia(&points_body, &masses);
        let shape = ConvexHull::from_points(&points_body).ok().map(Shape::Hull);
        Body::assemble(total, points_body, barycenter, edges, inertia, shape)
    }

    /// A uniform solid box of full side lengths `size` and mass `mass`, centred on the origin.
    pub fn solid_box(size: Vector3<f64>, mass: f64) -> Result<Body, BodyError> {
        check_size(size)?;
        check_mass(mass)?;
        let [a, b, c] = [size.x, size.y, size.z];
        let inertia =
            Matrix3::from_diagonal(&Vector3::new(b * b + c * c, a * a + c * c, a * a + b * b))
                * (mass / 12.0);
        Body::assemble(
            mass,
            box_corners(size),
            Vector3::zeros(),
            box_edges(),
            inertia,
            Some(Shape::Box { half: size / 2.0 }),
        )
    }

    /// A box whose 8 corners are equal mass points (`inertia = "points"`).
    pub fn box_of_corners(size: Vector3<f64>, mass: f64) -> Result<Body, BodyError> {
        check_size(size)?;
        let body = Body::from_points(&box_corners(size), &[], mass, box_edges())?;
        Ok(Body {
            shape: Some(Shape::Box { half: size / 2.0 }),
            ..body
        })
    }

    /// A uniform ball (`shell`: a thin spherical shell) of radius `radius` and mass `mass`.
    pub fn sphere(radius: f64, mass: f64, shell: bool) -> Result<Body, BodyError> {
        check_length("radius", radius)?;
        check_mass(mass)?;
        let factor = if shell { 2.0 / 3.0 } else { 2.0 / 5.0 };
        let inertia = Matrix3::identity() * (factor * mass * radius * radius);
        Body::round(mass, inertia, Shape::Ball { radius })
    }

    /// A uniform cylinder (`shell`: a thin tube without end caps) of radius `radius` and length
    /// `length` along the body y axis.
    pub fn cylinder(radius: f64, length: f64, mass: f64, shell: bool) -> Result<Body, BodyError> {
        check_length("radius", radius)?;
        check_length("length", length)?;
        check_mass(mass)?;
        let (r2, l2) = (radius * radius, length * length);
        let (axial, across) = if shell {
            (mass * r2, mass * (r2 / 2.0 + l2 / 12.0))
        } else {
            (mass * r2 / 2.0, mass * (r2 / 4.0 + l2 / 12.0))
        };
        let inertia = Matrix3::from_diagonal(&Vector3::new(across, axial, across));
        let shape = Shape::Cylinder {
            radius,
            half_length: length / 2.0,
        };
        Body::round(mass, inertia, shape)
    }

    /// A uniform solid capsule: a cylinder of radius `radius` and length `length` along the
    /// body y axis with a hemisphere on each end (module doc).
    pub fn capsule(radius: f64, length: f64, mass: f64) -> Result<Body, BodyError> {
        check_length("radius", radius)?;
        check_length("length", length)?;
        check_mass(mass)?;
        let (r, l) = (radius, length);
        // Volumes π r² L and 4/3 π r³ share the mass.
        let cylinder = mass * l / (l + 4.0 * r / 3.0);
        let spheres = mass - cylinder;
        let axial = cylinder * r * r / 2.0 + spheres * 2.0 * r * r / 5.0;
        let across = cylinder * (r * r / 4.0 + l * l / 12.0)
            + spheres * (2.0 * r * r / 5.0 + l * l / 4.0 + 3.0 * l * r / 8.0);
        let inertia = Matrix3::from_diagonal(&Vector3::new(across, axial, across));
        let shape = Shape::Capsule {
            radius,
            half_length: length / 2.0,
        };
        Body::round(mass, inertia, shape)
    }

    /// A round body: no points, its radius the shape's bounding radius.
    fn round(mass: f64, inertia: Matrix3<f64>, shape: Shape) -> Result<Body, BodyError> {
        Body::assemble(
            mass,
            Vec::new(),
            Vector3::zeros(),
            Vec::new(),
            inertia,
            Some(shape),
        )
    }

    /// The same body held fixed: it never moves (mass, inertia and their inverses all 0).
    pub fn fixed(self) -> Body {
        Body {
            mass: 0.0,
            inv_mass: 0.0,
            inertia_body: Matrix3::zeros(),
            inv_inertia_body: Matrix3::zeros(),
            principal_moments: Vector3::zeros(),
            fixed: true,
            ..self
        }
    }

    /// The same body with total mass `mass`: every point mass (or the uniform solid's density)
    /// scaled by `mass / M`, so the points and the barycenter stay where they are and the
    /// inertia tensor scales by the same ratio, `I_body' = (mass / M) I_body`.
    pub fn with_mass(&self, mass: f64) -> Result<Body, BodyError> {
        check_mass(mass)?;
        if self.fixed {
            // A fixed body has no mass to scale: it stays the world.
            return Ok(self.clone());
        }
        Body::assemble(
            mass,
            self.points_body.clone(),
            self.barycenter,
            self.edges.clone(),
            self.inertia_body * (mass / self.mass),
            self.shape.clone(),
        )
    }

    /// Finishes a body from its mass, points about the barycenter and inertia tensor.
    fn assemble(
        mass: f64,
        points_body: Vec<Vector3<f64>>,
        barycenter: Vector3<f64>,
        edges: Vec<(usize, usize)>,
        inertia_body: Matrix3<f64>,
        shape: Option<Shape>,
    ) -> Result<Body, BodyError> {
        // Overflow and underflow are named before the shape is blamed for a singular tensor.
        if !inertia_body.iter().all(|c| c.is_finite()) {
            return Err(BodyError::Overflow("inertia tensor"));
        }
        let (principal_moments, principal_axes) = principal_frame(&inertia_body);
        // All zero is a point or a line (singular, below); nonzero but subnormal underflowed.
        if principal_moments.z != 0.0 && !principal_moments.z.is_normal() {
            return Err(BodyError::Underflow(principal_moments.z));
        }
        let largest = principal_moments.z;
        // Written so that a NaN moment also counts as singular.
        let invertible = principal_moments.x.partial_cmp(&(1e-12 * largest))
            == Some(std::cmp::Ordering::Greater);
        if !invertible || !largest.is_finite() {
            return Err(BodyError::SingularInertia(
                principal_moments.x,
                principal_moments.y,
                principal_moments.z,
            ));
        }
        let inv_inertia_body = inertia_body
            .try_inverse()
            .ok_or(BodyError::SingularInertia(
                principal_moments.x,
                principal_moments.y,
                principal_moments.z,
            ))?;
        // Symmetrise: the inverse of a symmetric matrix is symmetric, round-off aside.
        let mut inv_inertia_body = (inv_inertia_body + inv_inertia_body.transpose()) * 0.5;
        if !inv_inertia_body.iter().all(|c| c.is_finite()) {
            // The determinant overflowed (moments near 1e103 and above: I₁I₂I₃ > 1.8e308)
            // although each moment is finite: invert in the principal frame instead,
            // I⁻¹ = E diag(1/I₁, 1/I₂, 1/I₃) Eᵀ.
            let e = principal_axes.to_rotation_matrix().into_inner();
            inv_inertia_body =
                e * Matrix3::from_diagonal(&principal_moments.map(|m| 1.0 / m)) * e.transpose();
            if !inv_inertia_body.iter().all(|c| c.is_finite()) {
                return Err(BodyError::Overflow("inverse inertia tensor"));
            }
        }
        let radius = match (&shape, points_body.is_empty()) {
            (Some(shape), true) => shape.bounding_radius(),
            _ => points_body.iter().map(|p| p.norm()).fold(0.0, f64::max),
        };
        Ok(Body {
            mass,
            inv_mass: 1.0 / mass,
            points_body,
            barycenter,
            edges,
            inertia_body,
            inv_inertia_body,
            principal_moments,
            principal_axes,
            radius,
            shape,
            fixed: false,
        })
    }
}

fn check_length(what: &'static str, value: f64) -> Result<(), BodyError> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(BodyError::BadLength(what, value))
    }
}

/// A mass must be > 0, finite and a normal number (a subnormal mass such as 5e-324 kg has
/// lost its precision and makes the inertia tensor vanish).
fn check_mass(mass: f64) -> Result<(), BodyError> {
    if mass > 0.0 && mass.is_normal() {
        Ok(())
    } else {
        Err(BodyError::BadMass(mass))
    }
}

fn check_size(size: Vector3<f64>) -> Result<(), BodyError> {
    if size.iter().all(|s| *s > 0.0 && s.is_finite()) {
        Ok(())
    } else {
        Err(BodyError::BadSize([size.x, size.y, size.z]))
    }
}

/// `I = Σ mᵢ ((rᵢ·rᵢ) 𝟙 − rᵢ rᵢᵀ)` for points `rᵢ` about the barycenter.
pub fn point_inertia(points: &[Vector3<f64>], masses: &[f64]) -> Matrix3<f64> {
    points
        .iter()
        .zip(masses)
        .fold(Matrix3::zeros(), |acc, (r, m)| {
            acc + (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * *m
        })
}

/// The 8 corners of a box of full sides `size` centred on the origin, in binary order
/// (bit 0: x, bit 1: y, bit 2: z; a set bit is the + side).
pub fn box_corners(size: Vector3<f64>) -> Vec<Vector3<f64>> {
    let h = size * 0.5;
    (0..8)
        .map(|i| {
            let s = |bit: usize| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
            Vector3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
        })
        .collect()
}

/// The 12 edges of a box whose corners are numbered as in [`box_corners`]: corners that differ
/// in exactly one bit.
pub fn box_edges() -> Vec<(usize, usize)> {
    let mut edges = Vec::with_capacity(12);
    for i in 0..8usize {
        for bit in 0..3 {
            let j = i ^ (1 << bit);
            if i < j {
                edges.push((i, j));
            }
        }
    }
    edges
}

/// Principal moments (ascending) and a proper rotation E (principal → body) with
/// `I = E diag(moments) Eᵀ`. The eigenvector basis is flipped if it comes out left-handed.
fn principal_frame(inertia: &Matrix3<f64>) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let eigen = SymmetricEigen::new(*inertia);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let moments = Vector3::new(
        eigen.eigenvalues[order[0]],
        eigen.eigenvalues[order[1]],
        eigen.eigenvalues[order[2]],
    );
    let mut axes = Matrix3::from_columns(&[
        eigen.eigenvectors.column(order[0]).into_owned(),
        eigen.eigenvectors.column(order[1]).into_owned(),
        eigen.eigenvectors.column(order[2]).into_owned(),
    ]);
    if axes.determinant() < 0.0 {
        axes.set_column(2, &(-axes.column(2)));
    }
    let rotation = nalgebra::Rotation3::from_matrix_unchecked(axes);
    (moments, UnitQuaternion::from_rotation_matrix(&rotation))
}
