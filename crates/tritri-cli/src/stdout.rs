//! Standard output as the commands write it: a write that fails (a full
//! disk behind `> file`, `> /dev/full`) is an error that names standard
//! output, exit status 1, never a panic. (A closed pipe ends the program
//! quietly instead: main.rs restores SIGPIPE.) `outln!` and `out!` are
//! `println!` and `print!` that return that error.

use std::io::{self, Write};

/// Standard output, whose errors say that it was standard output.
pub struct Stdout;

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        io::stdout().write(buf).map_err(named)
    }

    fn flush(&mut self) -> io::Result<()> {
        io::stdout().flush().map_err(named)
    }
}

fn named(e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("writing to standard output: {e}"))
}

/// `print!`'s text to [`Stdout`], flushed when it ends a line.
pub fn print(text: std::fmt::Arguments) -> io::Result<()> {
    Stdout.write_fmt(text)
}

/// `println!` that returns the error ([`print`]).
macro_rules! outln {
    () => { $crate::stdout::print(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::stdout::print(format_args!("{}\n", format_args!($($arg)*))) };
}

/// `print!` that returns the error ([`print`]).
macro_rules! out {
    ($($arg:tt)*) => { $crate::stdout::print(format_args!($($arg)*)) };
}

pub(crate) use {out, outln};

#[cfg(test)]
mod tests {
    #[test]
    fn an_error_names_standard_output() {
        let e = super::named(std::io::Error::from_raw_os_error(28));
        assert!(
            e.to_string()
                .starts_with("writing to standard output: No space left on device"),
            "{e}"
        );
    }
}
