//! The measuring tools of issue 38, as pure logic: a stopwatch on simulated time, a period
//! timer on a sampled quantity, a ruler between two points of the scene and a protractor
//! between a body axis and the vertical or another body's axis. Nothing here draws: the app's
//! panel (`tui/tools_panel.rs`) and a lesson page's `period`, `ruler`, `protractor` and
//! `stopwatch` tables (`scene`) only hold and show what these functions compute.
//!
//! | file | tool |
//! |---|---|
//! | `stopwatch` | start, stop, lap on simulated time |
//! | `period` | successive upward crossings of a level: mean period, spread, count |
//! | `ruler` | the distance between two points (a body's barycenter or a point of it, a joint's or spring's anchor, a fixed point) |
//! | `protractor` | the angle between a body axis and the vertical or another body's axis |

pub mod period;
pub mod protractor;
pub mod ruler;
pub mod stopwatch;

/// The tools a page sets (its `stopwatch`, `period`, `ruler` and `protractor` tables); a tool
/// the page names in `panels` without a table takes the app's own setting.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PageTools {
    pub stopwatch: Option<stopwatch::Schedule>,
    pub period: Option<period::Watch>,
    pub ruler: Option<ruler::Ruler>,
    pub protractor: Option<protractor::Protractor>,
}

/// The names of the quantities the period timer can watch, as the plot list names them
/// (`tui::plot::columns`): each moving body's `BODY.NAME`, the scene's `energy Px Py Pz`, each
/// joint's `JOINT.error`. `bodies` are (name, fixed) in file order.
pub fn quantity_names(bodies: &[(String, bool)], joints: &[String]) -> Vec<String> {
    let mut names = Vec::new();
    for (name, fixed) in bodies {
        if *fixed {
            continue;
        }
        for what in BODY_QUANTITIES {
            names.push(format!("{name}.{what}"));
        }
    }
    names.extend(["energy", "Px", "Py", "Pz"].map(String::from));
    names.extend(joints.iter().map(|j| format!("{j}.error")));
    names
}

/// A body's quantities in the plot list's order.
pub const BODY_QUANTITIES: [&str; 17] = [
    "x",
    "y",
    "z",
    "vx",
    "vy",
    "vz",
    "wx",
    "wy",
    "wz",
    "Lx",
    "Ly",
    "Lz",
    "|L|",
    "speed",
    "kinetic",
    "potential",
    "energy",
];
