//! rollbeam: a rigid disk rolling without slip on a rigid curve or a geometrically exact planar
//! beam. See README.md for the scene format and REPORT.md for what the studies show.

pub mod analysis;
pub mod beam;
pub mod commands;
pub mod coupling;
pub mod curve;
pub mod disk;
pub mod error;
pub mod files;
pub mod linalg;
pub mod ode;
pub mod output;
pub mod plan;
pub mod recent;
pub mod rolling;
pub mod run;
pub mod scene;
pub mod vehicle;
pub mod workflows;

/// println! that does not panic when stdout is closed (`rollbeam run … | head -1`): what a
/// reader stopped reading is not an error of the run.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}
