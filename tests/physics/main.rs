//! Physics tests: mass properties, integrators, contacts, cloths, hard cases and properties (one test binary: each links the whole library once).

mod bodies;
mod body_order;
mod cloth;
mod cloth_attach;
mod cloth_world;
mod collisions;
mod common;
mod contact_scaling;
mod dominoes;
mod energy_ledger;
mod exact_splitting;
mod geometry;
mod hard_cases;
mod impacts;
mod joint_bounds;
mod joint_drives;
mod joints;
mod particle_laws;
mod physics_core;
mod properties;
mod round_bodies;
mod soft_step;
mod tunnelling;
mod walls;
