//! Command-line tests: check, run, walk, study, the bundled lessons and their claims, bad input, hostile input (one test binary).

mod bad_input;
mod cli_lessons;
mod cli_names_and_errors;
mod cloth_cli;
mod diff;
mod divergence_cli;
mod hostile;
mod hostile_round4;
mod joint_keys;
mod lesson_claims;
mod lessons;
mod live_numbers;
mod ode;
mod page_tools;
mod read_path;
mod shot_forces;
mod shot_tools;
mod study;
mod study_cloth;
mod study_contact;
mod study_methods;
mod study_models;
mod study_table;
mod walk;
mod walk_error;
