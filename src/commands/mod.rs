//! The subcommands, thin adapters over the layers below: each takes its clap arguments, calls
//! a workflow (`crate::workflows`) or a run, and prints or writes what was asked. `run.rs`
//! (`rollbeam run`), `check.rs` (`check`: the model a scene builds, as `Display`),
//! `analyses.rs` (`static` and `modes`), `sweep.rs`, `tradeoff.rs` (work–precision) and
//! `studies.rs` (every study and the report's figures).

pub mod analyses;
pub mod check;
pub mod run;
pub mod studies;
pub mod sweep;
pub mod tradeoff;

use std::path::Path;

use crate::error::Error;
use crate::run::Overrides;
use crate::scene::{BeamScene, Scene};
use crate::workflows::settings::solver_overrides;

/// The integrator settings a run or sweep may take from the command line.
#[derive(clap::Args)]
pub struct SolverFlags {
    /// Integrator: dopri5, trbdf2, esdirk4 or genalpha (beam scenes).
    #[arg(long)]
    method: Option<String>,
    #[arg(long, allow_negative_numbers = true)]
    rtol: Option<f64>,
    #[arg(long, allow_negative_numbers = true)]
    atol: Option<f64>,
}

impl SolverFlags {
    /// Whether any flag is given.
    pub(crate) fn given(&self) -> bool {
        self.method.is_some() || self.rtol.is_some() || self.atol.is_some()
    }

    /// The flags checked against the scene, as overrides of its own settings.
    fn overrides(&self, scene: &Scene) -> Result<Overrides, Error> {
        solver_overrides(scene, self.method.as_deref(), self.rtol, self.atol)
    }
}

/// The beam of a scene, for a command that analyses beams only.
pub(crate) fn beam_only<'a>(
    scene: &'a Scene,
    path: &Path,
    command: &str,
) -> Result<&'a BeamScene, Error> {
    scene.beam().ok_or_else(|| {
        Error::Input(format!(
            "{}: `{command}` needs a beam track; this scene has a rigid curve",
            path.display()
        ))
    })
}
