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
            Failure::Usage(error) | Failure::Data(error) => write!(f, "{}", chain_text(error)),
        }
    }
}

/// A setting the library refused (out of its range) is bad usage, said in the command line's
/// words: `--rate-hz 0: expected a positive number`.
impl From<thermonav::setting::SettingError> for Failure {
    fn from(e: thermonav::setting::SettingError) -> Self {
        Failure::Usage(anyhow::anyhow!("{}", e.as_flag()))
    }
}

/// The error and its causes joined by ": " (anyhow's `{:#}`), leaving out a cause whose text
/// the message already holds (an error that prints its source, as a write error prints the
/// system's reason, would otherwise say it twice).
fn chain_text(error: &anyhow::Error) -> String {
    let mut text = error.to_string();
    for cause in error.chain().skip(1).map(ToString::to_string) {
        if !text.contains(&cause) {
            text.push_str(": ");
            text.push_str(&cause);
        }
    }
    text
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

#[cfg(test)]
mod tests {
    use super::*;

    // Issue 38 row 8: a write error that prints the system's reason said it twice through
    // anyhow's chain ("(os error 2): ... (os error 2)").
    #[test]
    fn a_cause_the_message_already_holds_is_said_once() {
        let reason = std::io::Error::from(std::io::ErrorKind::NotFound);
        let error = thermonav_io::WriteError::CreateTemporary {
            path: "missing/bank.json".into(),
            source: reason,
        };
        let text = Failure::Data(error.into()).to_string();
        let said = std::io::Error::from(std::io::ErrorKind::NotFound).to_string();
        assert_eq!(text.matches(&said).count(), 1, "{text}");
        let wrapped = anyhow::anyhow!("outer").context("context");
        assert_eq!(Failure::Usage(wrapped).to_string(), "context: outer");
    }
}
