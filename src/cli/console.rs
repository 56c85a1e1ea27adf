//! Lines for the user on stdout and stderr. A reader that goes away (`glint render --list |
//! head -3`, `glint render … 2>&1 | head`) ends the printing, not the command: `println!`
//! panics on a closed pipe, which made a render that had written its images exit with 101.

use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once stdout's reader has gone: nothing more is written there.
static STDOUT_GONE: AtomicBool = AtomicBool::new(false);

/// One line on stdout. A closed pipe stops further output quietly; any other failure (a full
/// disk behind a redirection) is the command's error.
pub fn out_line(args: std::fmt::Arguments) -> io::Result<()> {
    if STDOUT_GONE.load(Ordering::Relaxed) {
        return Ok(());
    }
    let mut out = io::stdout().lock();
    match out.write_fmt(args).and_then(|()| out.write_all(b"\n")).and_then(|()| out.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            STDOUT_GONE.store(true, Ordering::Relaxed);
            Ok(())
        }
        result => result,
    }
}

/// One line on stderr (warnings, notes, errors): where it cannot be written, there is nowhere
/// left to say so, and the command goes on. Messages quote input files, so their control
/// characters are written as escapes (`inert`).
pub fn err_line(args: std::fmt::Arguments) {
    let line = inert(&args.to_string()).into_owned();
    let mut err = io::stderr().lock();
    let _ignored = err.write_all(line.as_bytes()).and_then(|()| err.write_all(b"\n"));
}

/// `text` with its control characters but line breaks and tabs written as Rust escapes: an
/// OBJ line or a material name quoted in a message carried ESC sequences that cleared and
/// recoloured the terminal, and NUL bytes.
fn inert(text: &str) -> std::borrow::Cow<'_, str> {
    let live = |c: char| c.is_control() && c != '\n' && c != '\t';
    if !text.chars().any(live) {
        return std::borrow::Cow::Borrowed(text);
    }
    text.chars().map(|c| if live(c) { c.escape_default().to_string() } else { c.to_string() }).collect()
}

/// `println!` that returns an `io::Result` instead of panicking (`out_line`).
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::cli::console::out_line(format_args!($($arg)*))
    };
}

/// `eprintln!` that never panics (`err_line`).
macro_rules! tell {
    ($($arg:tt)*) => {
        $crate::cli::console::err_line(format_args!($($arg)*))
    };
}

pub(crate) use {say, tell};

#[cfg(test)]
mod tests {
    use super::inert;

    #[test]
    fn control_characters_of_a_message_are_written_as_escapes() {
        assert_eq!(
            inert("invalid OBJ (`v 1 0 \u{1b}[2J\u{1b}[31mEVIL`)"),
            "invalid OBJ (`v 1 0 \\u{1b}[2J\\u{1b}[31mEVIL`)"
        );
        assert_eq!(inert("a\0b\rc"), "a\\u{0}b\\rc");
        assert_eq!(inert("two lines\n\tand a tab, é ✓"), "two lines\n\tand a tab, é ✓");
    }
}
