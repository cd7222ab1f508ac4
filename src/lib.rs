//! `tumble`: a terminal teaching tool for rigid-body dynamics.
//!
//! Data flows one way: a lesson file is parsed into a scene ([`scene`]), the scene builds a
//! [`physics::World`], and every front end (the TUI, `walk`, `run`, `study`) reads the world's
//! [`physics::Snapshot`].

pub mod cli;
pub mod contact_scenes;
pub mod diff;
pub mod error_bars;
pub mod joint_scenes;
pub mod lessons;
pub mod limits;
pub mod live;
pub mod measure;
pub mod physics;
pub mod scene;
pub mod session;
pub mod study;
pub mod tables;
#[cfg(feature = "tui")]
pub mod tui;
