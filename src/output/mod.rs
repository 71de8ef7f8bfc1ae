//! What a run leaves in its output directory: `summary.yaml`, `history.csv` and SVG figures.

pub mod animation;
pub mod beam;
pub mod history;
pub mod plots;
pub mod summary;

use std::path::Path;

use crate::error::Error;
use crate::run::{Run, RunResult};

pub fn write_all(run: &Run, dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    match run {
        Run::Rolling(r) => write_rolling(r, dir),
        Run::Beam(b) => beam::write_all(b, dir),
    }
}

pub(crate) fn yaml(value: &impl serde::Serialize) -> Result<String, Error> {
    serde_saphyr::to_string(value)
        .map_err(|e| Error::Output(format!("cannot format YAML output: {e}")))
}

fn write_rolling(result: &RunResult, dir: &Path) -> Result<(), Error> {
    let summary = summary::Summary::from_run(result);
    write(&dir.join("summary.yaml"), &yaml(&summary)?)?;
    write(&dir.join("history.csv"), &history::csv(result))?;
    plots::all(result, dir)
}

pub(crate) fn write(path: &Path, text: &str) -> Result<(), Error> {
    std::fs::write(path, text).map_err(|e| io_error(path, e))
}

pub(crate) fn io_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output(format!("cannot write {}: {e}", path.display()))
}

/// A tolerance to three significant digits: 1e-5 stays 1e-5, accuracy/30 reads 3.33e-5.
pub fn tolerance(x: f64) -> String {
    let rounded: f64 = format!("{x:.2e}").parse().unwrap_or(x);
    format!("{rounded:e}")
}
