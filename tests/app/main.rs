//! The terminal app: screens, panels, history, the study view (one test binary, built with the tui feature).
#![cfg(feature = "tui")]

mod against;
mod class_pages;
mod classroom;
mod common;
mod energy_bars;
mod findings;
mod forces;
mod fuzz;
mod history;
mod jobs;
mod mouse;
mod plot;
mod settings_live;
mod tools;
mod tui;
mod tui_cloth;
mod tui_screens;
mod tui_study;
