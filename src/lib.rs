//! rollbeam: a rigid disk rolling without slip on a rigid curve or a geometrically exact planar
//! beam. See README.md for the scene format and REPORT.md for what the studies show.

pub mod curve;
pub mod ode;
pub mod disk;
pub mod rolling;
