//! The physics: the model against the paper and against independent numerical integrations, its limits,
//! energy balances and properties, the golden corpus, the analyses, the measured presets and the shot.

#[path = "../support"]
mod support {
    pub mod bin;
    pub mod chain;
    pub mod chain_compliant_integrator;
    pub mod chain_integrator;
    pub mod compliant;
    pub mod compliant_integrator;
    pub mod cpu;
    pub mod energy;
    pub mod flight;
    pub mod frame_integrator;
    pub mod integrator;
    pub mod phases;
    pub mod prop;
    pub mod rng;
}

mod analysis;
mod chain;
mod chain_compliant;
mod chain_compliant_string;
mod chain_reference;
mod chain_string;
mod compliant;
mod compliant_string;
mod critical;
mod frame;
mod frame_chain;
mod frame_chain_compliant_string;
mod frame_chain_string;
mod frame_compliant;
mod frame_string;
mod golden;
mod numerical;
mod paper;
mod presets_measured;
mod properties;
mod racquet;
mod shot;
