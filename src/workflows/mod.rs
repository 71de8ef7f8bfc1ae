//! The library of workflows over runs, which the command line, the Python package and the
//! tests all call: `sweep` (a grid of cases, here or planned across machines), `tradeoff`
//! (work–precision against a converged reference, and the store of references), `analyses`
//! (static equilibrium and natural modes), `studies` (every study of the thesis and the
//! report's figures), `settings` (integrator settings as a user names them) and `parallel`,
//! the worker pool that sweeps and work–precision grids share.

pub mod analyses;
pub mod parallel;
pub mod settings;
pub mod studies;
pub mod sweep;
pub mod tradeoff;
