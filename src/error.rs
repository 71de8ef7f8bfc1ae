//! Errors a user can act on, and the exit status each one maps to.

use std::fmt;

#[derive(Debug)]
pub enum Error {
    /// The scene file or the command line is invalid (exit 1).
    Input(String),
    /// The solver could not continue (exit 2).
    Solver(String),
    /// Results could not be written (exit 1).
    Output(String),
}

impl Error {
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Input(_) | Error::Output(_) => 1,
            Error::Solver(_) => 2,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input(m) | Error::Solver(m) | Error::Output(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for Error {}

/// Longest excerpt of a user's text that a message quotes.
const QUOTE_CHARS: usize = 40;

/// A user's text as a message quotes it: in single quotes, control characters and quotes
/// escaped, cut to a short excerpt, so that a message stays one short line whatever was written.
pub fn quote(text: &str) -> String {
    let mut out = String::from("'");
    for (i, c) in text.chars().enumerate() {
        if i == QUOTE_CHARS {
            out.push_str("…");
            break;
        }
        out.extend(c.escape_debug());
    }
    out.push('\'');
    out
}

/// Longest run of digits a message prints as it is.
const DIGITS: usize = 17;

/// The text with every number longer than [`DIGITS`] characters in exponent form: Rust prints
/// 1e300 as 301 digits and 1e-300 with 300 zeros, which no reader wants in a sentence.
pub fn short_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut run = String::new();
    let flush = |run: &mut String, out: &mut String| {
        match run.parse::<f64>() {
            Ok(v) if run.len() > DIGITS => out.push_str(&format!("{v:e}")),
            _ => out.push_str(run),
        }
        run.clear();
    };
    for c in text.chars() {
        if c.is_ascii_digit() || (c == '.' && !run.contains('.')) {
            run.push(c);
        } else {
            flush(&mut run, &mut out);
            out.push(c);
        }
    }
    flush(&mut run, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::{quote, short_numbers};

    #[test]
    fn long_numbers_are_printed_short() {
        let big = format!("= {} m is wider", 1e300);
        assert_eq!(short_numbers(&big), "= 1e300 m is wider");
        assert_eq!(short_numbers(&format!("{}", 1e-30)), "1e-30");
        assert_eq!(
            short_numbers("t = 0.123456 s, 12 steps"),
            "t = 0.123456 s, 12 steps"
        );
    }

    #[test]
    fn quotes_are_short_and_on_one_line() {
        assert_eq!(quote("genalpha"), "'genalpha'");
        assert_eq!(quote("a\nb"), "'a\\nb'");
        let long = quote(&"x".repeat(100_000));
        assert!(long.chars().count() < 50 && long.ends_with("…'"));
    }
}
