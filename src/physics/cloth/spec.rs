//! The parameters of a sheet (a `[[cloth]]` table), validated.
//!
//! ```text
//! count = [nx, nz], nx, nz ≥ 1, nx·nz ≥ 2   particle (i, j), 0 ≤ i < nx, 0 ≤ j < nz, index j·nx + i
//! x(i, j) = position + (−size.x/2 + i·size.x/(nx − 1), 0, −size.z/2 + j·size.z/(nz − 1))
//!           (an axis with a count of 1 puts its one row on the centre line: offset 0)
//! m = mass / (nx·nz)                     every particle, pinned ones included
//! ```
//!
//! A count of 1 along one axis makes a **rope**: one line of particles, its stretch springs
//! between neighbours and its bend springs to the second neighbour (a line has no cells, so no
//! shear springs). The side along an axis of count 1 is unused and may be 0. On a rope,
//! `corners` pins its two ends and `edges` every particle (each lies on a border).
//!
//! Stiffnesses are per spring (N/m): `stretch` > 0 along x and z, `shear` ≥ 0 on both
//! diagonals of every cell, `bend` ≥ 0 to the second neighbour; 0 means no spring of that kind.
//! `damping` ≥ 0 (N·s/m) acts along every spring.

use super::integrator::ClothIntegrator;
use nalgebra::Vector3;
use std::fmt;

/// Which particles are held fixed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Pinning {
    /// The four corners.
    Corners,
    /// Every particle on the border (i = 0, i = nx − 1, j = 0 or j = nz − 1).
    Edges,
    /// None: the sheet is free.
    None,
    /// These particles (i, j).
    List(Vec<[usize; 2]>),
}

impl Pinning {
    /// The keywords a scene file may use (the list form is an array of [i, j]).
    pub const KEYWORDS: [&'static str; 3] = ["corners", "edges", "none"];

    /// The pinning named by a keyword.
    pub fn from_keyword(word: &str) -> Option<Pinning> {
        match word {
            "corners" => Some(Pinning::Corners),
            "edges" => Some(Pinning::Edges),
            "none" => Some(Pinning::None),
            _ => None,
        }
    }

    /// Whether particle (i, j) of an nx × nz sheet is pinned.
    pub fn holds(&self, i: usize, j: usize, count: [usize; 2]) -> bool {
        let [nx, nz] = count;
        let (edge_i, edge_j) = (i == 0 || i + 1 == nx, j == 0 || j + 1 == nz);
        match self {
            Pinning::Corners => edge_i && edge_j,
            Pinning::Edges => edge_i || edge_j,
            Pinning::None => false,
            Pinning::List(list) => list.contains(&[i, j]),
        }
    }

    /// A short description for tables ("corners", "edges", "none", "5 particles").
    pub fn describe(&self) -> String {
        match self {
            Pinning::Corners => "corners".into(),
            Pinning::Edges => "edges".into(),
            Pinning::None => "none".into(),
            Pinning::List(list) => format!("{} particles", list.len()),
        }
    }
}

/// A particle held to a body (`attach`): it moves with the body at its offset at t = 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Attach {
    pub particle: [usize; 2],
    /// The body's index in the scene.
    pub body: usize,
}

/// A sheet's parameters (SI units), as a scene declares them.
#[derive(Debug, Clone, PartialEq)]
pub struct ClothSpec {
    /// Unique in the scene.
    pub name: String,
    /// Side lengths along x and z, m (> 0).
    pub size: [f64; 2],
    /// Particles along x and z (each ≥ 1, at least 2 in all; 1 along an axis: a rope).
    pub count: [usize; 2],
    /// Centre of the flat sheet, m.
    pub position: Vector3<f64>,
    /// Total mass, kg (> 0), shared equally by the particles.
    pub mass: f64,
    /// Stiffness of the springs along x and z, N/m (> 0).
    pub stretch: f64,
    /// Stiffness of the diagonal springs, N/m (≥ 0; 0 = none).
    pub shear: f64,
    /// Stiffness of the second-neighbour springs, N/m (≥ 0; 0 = none).
    pub bend: f64,
    /// Damping along every spring, N·s/m (≥ 0).
    pub damping: f64,
    pub pinned: Pinning,
    /// Initial velocity of every free particle, m/s.
    pub velocity: Vector3<f64>,
    pub integrator: ClothIntegrator,
    /// Particles held to bodies (only inside the implicit solve).
    pub attach: Vec<Attach>,
}

/// Why a spec cannot build a sheet.
#[derive(Debug, Clone, PartialEq)]
pub enum ClothSpecError {
    /// A count of 0 along x (axis 0) or z (axis 1), or a single particle in all.
    Count { axis: usize, found: usize },
    /// A parameter that must be > 0 (or ≥ 0) is not, or is not finite.
    Parameter {
        what: &'static str,
        found: f64,
        rule: &'static str,
    },
    /// A pinned particle outside the grid.
    PinnedOutOfRange {
        particle: [usize; 2],
        count: [usize; 2],
    },
}

impl fmt::Display for ClothSpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ClothSpecError::Count { axis, found } if *found == 0 => write!(
                f,
                "count along {} must be ≥ 1 particle, found 0",
                ["x", "z"][*axis]
            ),
            ClothSpecError::Count { .. } => write!(
                f,
                "count must make at least 2 particles (a rope is [n, 1] or [1, n], n ≥ 2), found [1, 1]"
            ),
            ClothSpecError::Parameter { what, found, rule } => {
                write!(f, "{what} must be {rule}, found {found}")
            }
            ClothSpecError::PinnedOutOfRange { particle, count } => write!(
                f,
                "pinned particle [{}, {}] is outside the {}×{} grid: i must be < {} and j < {}",
                particle[0], particle[1], count[0], count[1], count[0], count[1]
            ),
        }
    }
}

impl std::error::Error for ClothSpecError {}

impl ClothSpec {
    /// A spec with the given grid and stretch stiffness, everything else absent: no shear, no
    /// bend, no damping, nothing pinned, at rest at the origin, `implicit-euler`.
    pub fn new(size: [f64; 2], count: [usize; 2], mass: f64, stretch: f64) -> ClothSpec {
        ClothSpec {
            name: "cloth1".into(),
            size,
            count,
            position: Vector3::zeros(),
            mass,
            stretch,
            shear: 0.0,
            bend: 0.0,
            damping: 0.0,
            pinned: Pinning::None,
            velocity: Vector3::zeros(),
            integrator: ClothIntegrator::ImplicitEuler,
            attach: Vec::new(),
        }
    }

    /// Number of particles nx·nz.
    pub fn particles(&self) -> usize {
        self.count[0] * self.count[1]
    }

    /// Checks every rule of the module doc.
    pub fn validate(&self) -> Result<(), ClothSpecError> {
        for (axis, &n) in self.count.iter().enumerate() {
            if n == 0 {
                return Err(ClothSpecError::Count { axis, found: n });
            }
        }
        if self.count == [1, 1] {
            return Err(ClothSpecError::Count { axis: 0, found: 1 });
        }
        let positive = |what, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ClothSpecError::Parameter {
                    what,
                    found: v,
                    rule: "> 0 and finite",
                })
            }
        };
        let non_negative = |what, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(ClothSpecError::Parameter {
                    what,
                    found: v,
                    rule: "≥ 0 and finite",
                })
            }
        };
        // A side along an axis with a single row (a rope) is unused: ≥ 0 is enough.
        for (axis, what) in [(0, "size.x"), (1, "size.z")] {
            if self.count[axis] > 1 {
                positive(what, self.size[axis])?;
            } else {
                non_negative(what, self.size[axis])?;
            }
        }
        positive("mass", self.mass)?;
        positive("stretch", self.stretch)?;
        non_negative("shear", self.shear)?;
        non_negative("bend", self.bend)?;
        non_negative("damping", self.damping)?;
        for (what, v) in [("position", self.position), ("velocity", self.velocity)] {
            if let Some(&bad) = v.iter().find(|c| !c.is_finite()) {
                return Err(ClothSpecError::Parameter {
                    what,
                    found: bad,
                    rule: "finite",
                });
            }
        }
        if let Pinning::List(list) = &self.pinned {
            if let Some(&particle) = list
                .iter()
                .find(|[i, j]| *i >= self.count[0] || *j >= self.count[1])
            {
                return Err(ClothSpecError::PinnedOutOfRange {
                    particle,
                    count: self.count,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_and_edges_pick_the_border() {
        let count = [4, 3];
        let corners: usize = (0..4)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .filter(|&(i, j)| Pinning::Corners.holds(i, j, count))
            .count();
        let edges: usize = (0..4)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .filter(|&(i, j)| Pinning::Edges.holds(i, j, count))
            .count();
        // 4 × 3 grid: 4 corners; border = all 12 but the 2 inner particles (1,1), (2,1).
        assert_eq!(corners, 4);
        assert_eq!(edges, 10);
    }

    #[test]
    fn validation_names_the_fault() {
        let good = ClothSpec::new([1.0, 1.0], [3, 3], 1.0, 100.0);
        assert_eq!(good.validate(), Ok(()));
        let mut bad = good.clone();
        bad.count = [3, 0];
        assert_eq!(
            bad.validate().unwrap_err().to_string(),
            "count along z must be ≥ 1 particle, found 0"
        );
        bad.count = [1, 1];
        assert_eq!(
            bad.validate().unwrap_err().to_string(),
            "count must make at least 2 particles (a rope is [n, 1] or [1, n], n ≥ 2), found [1, 1]"
        );
        // A rope: one row; its unused side may be 0.
        bad.count = [3, 1];
        bad.size = [1.0, 0.0];
        assert_eq!(bad.validate(), Ok(()));
        let mut bad = good.clone();
        bad.shear = -1.0;
        assert_eq!(
            bad.validate().unwrap_err().to_string(),
            "shear must be ≥ 0 and finite, found -1"
        );
        let mut bad = good;
        bad.pinned = Pinning::List(vec![[0, 0], [3, 1]]);
        assert_eq!(
            bad.validate().unwrap_err().to_string(),
            "pinned particle [3, 1] is outside the 3×3 grid: i must be < 3 and j < 3"
        );
    }
}
