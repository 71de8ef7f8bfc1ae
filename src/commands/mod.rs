//! The subcommands, apart from the physics: each reads a scene, calls the layers below and
//! writes or prints what was asked. One function per subcommand, with its arguments:
//! `run.rs` (`rollbeam run`), `check.rs` (`check`: the model a scene builds, as `Display`),
//! `report.rs` (`static` and `modes`), `sweep.rs`, `tradeoff.rs` (work–precision),
//! `studies.rs` (every study and the report's figures), and `parallel.rs`, the worker pool
//! that sweeps and work–precision grids share.

pub mod check;
pub mod parallel;
pub mod reference;
pub mod report;
pub mod run;
pub mod studies;
pub mod sweep;
pub mod tradeoff;

use std::path::Path;

use crate::error::{quote, Error};
use crate::ode::Method;
use crate::run::Overrides;
use crate::scene::{method_names, BeamScene, Scene, SceneSpec};

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

/// A method, rtol and atol as a user names them (the command line's flags, the Python
/// package's arguments), checked against the scene, as overrides of its own settings.
pub fn solver_overrides(
    scene: &Scene,
    method: Option<&str>,
    rtol: Option<f64>,
    atol: Option<f64>,
) -> Result<Overrides, Error> {
    Ok(Overrides {
        method: method.map(|m| parse_method(m, scene)).transpose()?,
        rtol: rtol_flag(rtol, "--rtol")?,
        atol: positive(atol, "--atol")?,
        ..Default::default()
    })
}

/// The integrator settings of the command line written into a scene, so that the scene
/// alone runs as the command would (a planned sweep's case files).
pub(crate) fn write_solver(over: &Overrides, spec: &mut SceneSpec) -> Result<(), Error> {
    if let Some(m) = over.method {
        spec.set_name("solver.method", m.name())?;
    }
    if let Some(r) = over.rtol {
        spec.set("solver.rtol", r)?;
    }
    if let Some(a) = over.atol {
        spec.set("solver.atol", a)?;
    }
    Ok(())
}

/// A tolerance given on the command line: positive and finite.
pub(crate) fn positive(value: Option<f64>, flag: &str) -> Result<Option<f64>, Error> {
    match value {
        Some(v) if !(v > 0.0 && v.is_finite()) => Err(Error::Input(format!(
            "{flag} must be a positive number (got {v})"
        ))),
        v => Ok(v),
    }
}

/// A relative tolerance given on the command line: positive, and one an integrator can honour.
pub(crate) fn rtol_flag(value: Option<f64>, flag: &str) -> Result<Option<f64>, Error> {
    match positive(value, flag)? {
        Some(r) => match crate::ode::rtol_problem(r) {
            Some(why) => Err(Error::Input(format!("{flag} {why}"))),
            None => Ok(Some(r)),
        },
        None => Ok(None),
    }
}

/// A method named on the command line that can integrate this scene.
pub(crate) fn parse_method(name: &str, scene: &Scene) -> Result<Method, Error> {
    let m = Method::from_name(name).ok_or_else(|| {
        Error::Input(format!(
            "--method {} is unknown; use one of {}",
            quote(name),
            method_names()
        ))
    })?;
    if m == Method::GenAlpha && scene.beam().is_none() {
        return Err(Error::Input("--method genalpha integrates beam scenes; use dopri5, trbdf2 or esdirk4 for a rigid curve".into()));
    }
    Ok(m)
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
