//! What a run leaves in its output directory: `summary.yaml`, `history.csv` and SVG figures.
//! `beam/` (its summary and history; `beam/figures.rs`, its figures) and `animation.rs` write a
//! beam run's; `rolling_history.rs`, and the rigid curve's parts of `summary.rs` and
//! `plots.rs`, a disk on a rigid curve's; `summary.rs` and `plots.rs` also hold what both share
//! (the stop, the solver's report, the energy; the charts).

pub mod animation;
pub mod beam;
pub mod plots;
pub mod rolling_history;
pub mod summary;

use std::path::Path;

use crate::error::Error;
use crate::run::{RollingRun, Run};

/// Every output of a run into `dir`: the figures too where `figures` says so.
pub fn write_all(run: &Run, dir: &Path, figures: bool) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    // The summary says how the run ended, so it is written last, once every other file is
    // whole; one left from an earlier run goes first, so that a failed write leaves none.
    let _ = std::fs::remove_file(dir.join("summary.yaml"));
    match run {
        Run::Rolling(r) => write_rolling(r, dir, figures),
        Run::Beam(b) => beam::write_all(b, dir, figures),
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
        Run::Rolling(r) => rolling_history::csv(r),
        Run::Beam(b) => beam::csv(b),
    }
}

pub fn yaml(value: &impl serde::Serialize) -> Result<String, Error> {
    serde_saphyr::to_string(value)
        .map_err(|e| Error::Output(format!("cannot format YAML output: {e}")))
}

fn write_rolling(result: &RollingRun, dir: &Path, figures: bool) -> Result<(), Error> {
    let summary = summary::Summary::from_run(result);
    write(&dir.join("history.csv"), &rolling_history::csv(result))?;
    if figures {
        plots::all(result, dir)?;
    }
    write(&dir.join("summary.yaml"), &yaml(&summary)?)
}

/// Append one CSV row of numbers and its newline. A quantity that is undefined at that time
/// (NaN: a disk's columns after it left, the friction needed where it does not press) leaves
/// its cell empty.
pub(crate) fn push_row(out: &mut String, values: &[f64]) {
    let mut digits = zmij::Buffer::new();
    for (k, &x) in values.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        if !x.is_nan() {
            push_number(out, x, &mut digits);
        }
    }
    out.push('\n');
}

/// `x` as `{x}` prints it (the shortest digits that read back as x, never an exponent, no
/// ".0" on a whole number), with the digits found by zmij: D44's history.csv is built in 0.83
/// ms instead of 1.2. The two differ only where the shortest digits end in a tie, which std
/// rounds up and zmij to even: both read back as x, in as many digits. Among 8 million doubles
/// of every size the smallest such was 8.6·10⁸.
fn push_number(out: &mut String, x: f64, digits: &mut zmij::Buffer) {
    use std::fmt::Write;
    if !x.is_finite() {
        let _ = write!(out, "{x}");
        return;
    }
    let shortest = digits.format_finite(x);
    let Some((mantissa, exponent)) = shortest.split_once('e') else {
        out.push_str(shortest.strip_suffix(".0").unwrap_or(shortest));
        return;
    };
    let Ok(exponent) = exponent.parse::<i32>() else {
        let _ = write!(out, "{x}");
        return;
    };
    // d.ddd × 10^exponent, written out in full.
    if mantissa.starts_with('-') {
        out.push('-');
    }
    // At most 17 significant digits.
    let mut buffer = [0u8; 24];
    let mut count = 0;
    for b in mantissa.bytes().filter(u8::is_ascii_digit) {
        buffer[count] = b;
        count += 1;
    }
    let significant = std::str::from_utf8(&buffer[..count]).unwrap_or_default();
    if exponent < 0 {
        out.push_str("0.");
        out.extend(std::iter::repeat_n('0', (-exponent - 1) as usize));
        out.push_str(significant);
    } else {
        let whole = exponent as usize + 1;
        if significant.len() <= whole {
            out.push_str(significant);
            out.extend(std::iter::repeat_n('0', whole - significant.len()));
        } else {
            out.push_str(&significant[..whole]);
            out.push('.');
            out.push_str(&significant[whole..]);
        }
    }
}

/// Every output file is written here, and no table or summary leaves with a non-finite number
/// in it: that would be a run whose numbers overflowed, reported as a solver failure.
pub(crate) fn write(path: &Path, text: &str) -> Result<(), Error> {
    let table = matches!(
        path.extension().and_then(|e| e.to_str()),
        Some("csv" | "yaml")
    );
    if table {
        finite(&path.display().to_string(), text, ", so it was not written")?;
    }
    // A file from an earlier run is removed first: ext4 flushes a file that replaces another
    // by rename (or truncation) before the rename returns, which a rerun into the same folder
    // would wait for.
    let _ = std::fs::remove_file(path);
    crate::files::write_whole(path, text)
}

/// The text of a table or summary named `name`, refused where it holds a non-finite number;
/// `then` ends the sentence with what became of it.
fn finite(name: &str, text: &str, then: &str) -> Result<(), Error> {
    match non_finite(text) {
        Some((line, token)) => Err(Error::Solver(format!(
            "{name} would hold the non-finite number {token} (line {line}): the run's numbers overflowed{then}"
        ))),
        None => Ok(()),
    }
}

/// The texts of `summary.yaml` and `history.csv` for a run handed over in memory (the Python
/// package's), held to what its files would be: a summary or history that `write` would
/// refuse is the same solver failure.
pub fn finite_tables(run: &Run) -> Result<(String, String), Error> {
    let summary = summary_yaml(run)?;
    finite("summary.yaml", &summary, "")?;
    let history = history_csv(run);
    finite("history.csv", &history, "")?;
    Ok((summary, history))
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
    use super::{non_finite, push_row};

    /// The CSV's numbers are read by other programs and compared across versions: the fast
    /// path must print a double as `{x}` does. Compared over the bit patterns of a xorshift
    /// sequence (every exponent, both signs), numbers of a run's size and the edge cases.
    #[test]
    fn rows_print_numbers_as_display_does() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut values: Vec<f64> = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1e-5,
            1e-6,
            1e-7,
            123456.0,
            1e15,
            1e16,
            1e17,
            1.5e300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            3.0e-3,
            -2.5e-12,
        ];
        for _ in 0..200_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let x = f64::from_bits(seed);
            if x.is_finite() {
                values.push(x);
                // Numbers of a run's size, where the fixed and exponent forms meet.
                values.push(x.abs().log2().rem_euclid(1.0) * 10f64.powi((seed % 40) as i32 - 20));
            }
        }
        for x in values {
            let mut out = String::new();
            push_row(&mut out, &[x]);
            let display = format!("{x}\n");
            if x.abs() < 1e4 {
                assert_eq!(out, display, "the bits {:#x}", x.to_bits());
            } else {
                assert_eq!(out.trim_end().parse::<f64>(), Ok(x), "{out}");
                assert_eq!(out.len(), display.len(), "{out} against {display}");
            }
        }
    }

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
