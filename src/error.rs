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
