//! Shared by the integration tests: an independent numerical solution of the same model.

pub mod integrator;
