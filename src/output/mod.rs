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

/// The text of `summary.yaml`, as `write_all` writes it.
pub fn summary_yaml(run: &Run) -> Result<String, Error> {
    match run {
        Run::Rolling(r) => yaml(&summary::Summary::from_run(r)),
        Run::Beam(b) => beam::summary_yaml(b),
    }
}

/// The text of `history.csv`, as `write_all` writes it.
pub fn history_csv(run: &Run) -> String {
    match run {
        Run::Rolling(r) => history::csv(r),
        Run::Beam(b) => beam::csv(b),
    }
}

pub fn yaml(value: &impl serde::Serialize) -> Result<String, Error> {
    serde_saphyr::to_string(value)
        .map_err(|e| Error::Output(format!("cannot format YAML output: {e}")))
}

fn write_rolling(result: &RunResult, dir: &Path) -> Result<(), Error> {
    let summary = summary::Summary::from_run(result);
    write(&dir.join("summary.yaml"), &yaml(&summary)?)?;
    write(&dir.join("history.csv"), &history::csv(result))?;
    plots::all(result, dir)
}

/// Append one CSV row of numbers and its newline. A quantity that is undefined at that time
/// (NaN: a disk's columns after it left, the friction needed where it does not press) leaves
/// its cell empty.
pub(crate) fn push_row(out: &mut String, values: &[f64]) {
    use std::fmt::Write;
    for (k, &x) in values.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        if !x.is_nan() {
            let _ = write!(out, "{x}");
        }
    }
    out.push('\n');
}

/// Every output file is written here, and no table or summary leaves with a non-finite number
/// in it: that would be a run whose numbers overflowed, reported as a solver failure.
pub(crate) fn write(path: &Path, text: &str) -> Result<(), Error> {
    let table = matches!(
        path.extension().and_then(|e| e.to_str()),
        Some("csv" | "yaml")
    );
    if let Some((line, token)) = table.then(|| non_finite(text)).flatten() {
        return Err(Error::Solver(format!(
            "{} would hold the non-finite number {token} (line {line}): the run's numbers overflowed, so it was not written",
            path.display()
        )));
    }
    std::fs::write(path, text).map_err(|e| io_error(path, e))
}

/// The first line and token of a CSV or YAML text that is an infinity or NaN as Rust or YAML
/// prints them, outside quoted text (a failed sweep case's message is quoted).
pub(crate) fn non_finite(text: &str) -> Option<(usize, String)> {
    const TOKENS: [&str; 8] = ["inf", "-inf", "NaN", "nan", ".inf", "-.inf", ".nan", ".NaN"];
    text.lines().enumerate().find_map(|(k, line)| {
        // Every token holds an n: a row of plain numbers is passed over by one byte scan.
        if !line.bytes().any(|b| b == b'n' || b == b'N') {
            return None;
        }
        line.split('"')
            .step_by(2)
            .flat_map(|unquoted| {
                unquoted.split(|c: char| c.is_whitespace() || ",:[]{}".contains(c))
            })
            .find(|t| TOKENS.contains(t))
            .map(|t| (k + 1, t.to_string()))
    })
}

pub(crate) fn io_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output(format!("cannot write {}: {e}", path.display()))
}

/// A tolerance to three significant digits: 1e-5 stays 1e-5, accuracy/30 reads 3.33e-5.
pub fn tolerance(x: f64) -> String {
    let rounded: f64 = format!("{x:.2e}").parse().unwrap_or(x);
    format!("{rounded:e}")
}

#[cfg(test)]
mod tests {
    use super::non_finite;

    #[test]
    fn non_finite_numbers_are_found_outside_quotes() {
        assert_eq!(non_finite("t,w\n0,1\n0.1,inf\n"), Some((3, "inf".into())));
        assert_eq!(
            non_finite("energy:\n  initial: .inf\n"),
            Some((2, ".inf".into()))
        );
        assert_eq!(non_finite("v,status\n1,\"failed: E is inf\"\n"), None);
        assert_eq!(non_finite("t,w\n0,1e300\n0.1,-2.5\n"), None);
    }
}
