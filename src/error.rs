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
            out.push('…');
            break;
        }
        out.extend(c.escape_debug());
    }
    out.push('\'');
    out
}

/// Longest run of digits a message prints as it is.
const DIGITS: usize = 17;

/// The text with every number longer than [`DIGITS`] characters in short exponent form: Rust
/// prints 1e300 as 301 digits, 1e-300 with 300 zeros and C = m a²/2 as 5.0000000000000004e297,
/// which no reader wants in a sentence.
pub fn short_numbers(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i].is_ascii_digit()
            && (i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_'));
        if !starts {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        let digits = |mut k: usize| {
            while k < chars.len() && chars[k].is_ascii_digit() {
                k += 1;
            }
            k
        };
        let mut end = digits(i);
        if end < chars.len() && chars[end] == '.' {
            end = digits(end + 1);
        }
        if end < chars.len() && matches!(chars[end], 'e' | 'E') {
            let sign = usize::from(end + 1 < chars.len() && matches!(chars[end + 1], '-' | '+'));
            let after = digits(end + 1 + sign);
            if after > end + 1 + sign {
                end = after;
            }
        }
        let token: String = chars[i..end].iter().collect();
        match token.parse::<f64>() {
            Ok(v) if token.len() > DIGITS => {
                let e = format!("{v:.6e}");
                let (mantissa, exponent) = e.split_once('e').unwrap_or((&e, "0"));
                let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
                out.push_str(&format!("{mantissa}e{exponent}"));
            }
            _ => out.push_str(&token),
        }
        i = end;
    }
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
