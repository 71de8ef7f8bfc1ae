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

#[cfg(test)]
mod tests {
    use super::quote;

    #[test]
    fn quotes_are_short_and_on_one_line() {
        assert_eq!(quote("genalpha"), "'genalpha'");
        assert_eq!(quote("a\nb"), "'a\\nb'");
        let long = quote(&"x".repeat(100_000));
        assert!(long.chars().count() < 50 && long.ends_with("…'"));
    }
}
