//! Integrator settings as a user names them (the command line's flags, the Python package's
//! arguments), checked against the scene.

use crate::error::{quote, Error};
use crate::ode::Method;
use crate::run::Overrides;
use crate::scene::{method_names, Scene, SceneSpec};

/// A method, rtol and atol as a user names them (the command line's flags, the Python
/// package's arguments), checked against the scene, as overrides of its own settings.
pub fn solver_overrides(
    scene: &Scene,
    method: Option<&str>,
    rtol: Option<f64>,
    atol: Option<f64>,
) -> Result<Overrides, Error> {
    Ok(Overrides {
        method: method
            .map(|m| parse_method(m, scene, "--method"))
            .transpose()?,
        rtol: rtol_flag(rtol, "--rtol")?,
        atol: atol_flag(scene, atol, "--atol")?,
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

/// An absolute tolerance given on the command line: positive, and one that holds a step of
/// the scene's beam ([`crate::scene::BeamScene::atol_problem`]).
fn atol_flag(scene: &Scene, value: Option<f64>, flag: &str) -> Result<Option<f64>, Error> {
    let atol = positive(value, flag)?;
    match atol.zip(scene.beam()).and_then(|(a, b)| b.atol_problem(a)) {
        Some(why) => Err(Error::Input(format!("{flag} {why}"))),
        None => Ok(atol),
    }
}

/// A method named on the command line (by `flag`) that can integrate this scene.
pub(crate) fn parse_method(name: &str, scene: &Scene, flag: &str) -> Result<Method, Error> {
    let m = Method::from_name(name).ok_or_else(|| {
        Error::Input(format!(
            "{flag} {} is unknown; use one of {}",
            quote(name),
            method_names()
        ))
    })?;
    if matches!(m, Method::GenAlpha | Method::ExactModal) && scene.beam().is_none() {
        return Err(Error::Input(format!(
            "{flag} {} integrates beam scenes; use dopri5, trbdf2 or esdirk4 for a rigid curve",
            m.name()
        )));
    }
    Ok(m)
}
