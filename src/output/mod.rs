//! What a run leaves in its output directory: `summary.yaml`, `history.csv` and SVG figures.

pub mod history;
pub mod plots;
pub mod summary;

use std::path::Path;

use crate::error::Error;
use crate::run::RunResult;

pub fn write_all(result: &RunResult, dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    let summary = summary::Summary::from_run(result);
    let yaml = serde_saphyr::to_string(&summary)
        .map_err(|e| Error::Output(format!("cannot format the summary: {e}")))?;
    write(&dir.join("summary.yaml"), &yaml)?;
    write(&dir.join("history.csv"), &history::csv(result))?;
    plots::all(result, dir)
}

pub(crate) fn write(path: &Path, text: &str) -> Result<(), Error> {
    std::fs::write(path, text).map_err(|e| io_error(path, e))
}

pub(crate) fn io_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output(format!("cannot write {}: {e}", path.display()))
}
