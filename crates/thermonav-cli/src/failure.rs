//! How a run fails: bad usage (exit 2) or bad data (exit 1).

use std::fmt;
use std::process::ExitCode;

/// Exit code for a command line that cannot be carried out as written.
pub const USAGE_EXIT_CODE: u8 = 2;
/// Exit code for input data that cannot be processed.
pub const DATA_EXIT_CODE: u8 = 1;

/// Why a subcommand failed; decides the exit code.
#[derive(Debug)]
pub enum Failure {
    /// The arguments are invalid (cutoff above Nyquist, ripple <= 0, ...).
    Usage(anyhow::Error),
    /// The input data is missing, malformed or unusable, or an output cannot be written.
    Data(anyhow::Error),
}

impl Failure {
    /// The process exit code for this failure.
    pub fn exit_code(&self) -> ExitCode {
        match self {
            Failure::Usage(_) => ExitCode::from(USAGE_EXIT_CODE),
            Failure::Data(_) => ExitCode::from(DATA_EXIT_CODE),
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Usage(error) | Failure::Data(error) => write!(f, "{error:#}"),
        }
    }
}

/// Classifies a library error as a usage or a data failure at the call site.
pub trait Classify<T> {
    /// The error means the arguments were wrong.
    fn usage(self) -> Result<T, Failure>;
    /// The error means the data (or the file system) was wrong.
    fn data(self) -> Result<T, Failure>;
}

impl<T, E> Classify<T> for Result<T, E>
where
    E: Into<anyhow::Error>,
{
    fn usage(self) -> Result<T, Failure> {
        self.map_err(|e| Failure::Usage(e.into()))
    }

    fn data(self) -> Result<T, Failure> {
        self.map_err(|e| Failure::Data(e.into()))
    }
}
