//! A command line that asks for what cannot be done: a flag's value outside its range, or
//! flags that do nothing together. It exits with 2, as the argument parser's own refusals do,
//! so that a script tells a bad command from a failed render (1): `--width 16385` exited 1
//! and `--width -5` exited 2.

/// The error of such a command line; `main` gives it exit code 2.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// `bail!` for a `UsageError`.
macro_rules! usage {
    ($($arg:tt)*) => {
        return Err(anyhow::Error::new($crate::cli::usage::UsageError(format!($($arg)*))))
    };
}

pub(crate) use usage;

/// Whether `error` is (or wraps) a `UsageError`.
pub fn is_usage(error: &anyhow::Error) -> bool {
    error.downcast_ref::<UsageError>().is_some()
}
