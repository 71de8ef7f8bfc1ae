//! Analyses of a beam that are not time integration: static equilibrium, natural modes,
//! Frýba's series for a moving force, and the choice of a mesh and a beam model from the
//! accuracy asked.

pub mod discretisation;
pub mod model_choice;
pub mod modes;
pub mod moving_load;
pub mod statics;
