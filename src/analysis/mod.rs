//! Analyses of a beam that are not time integration: static equilibrium and natural modes.

pub mod discretisation;
pub mod modes;
pub mod moving_load;
pub mod statics;
