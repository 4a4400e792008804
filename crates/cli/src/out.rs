//! Printing to standard output with its errors returned: `println!` panics when a write
//! fails (a full disk behind `> file`), where a command should say what failed and exit 1.

use std::fmt;
use std::io::Write;

/// Write `args` to standard output, or an error naming it.
pub fn write_out(args: fmt::Arguments<'_>) -> anyhow::Result<()> {
    std::io::stdout()
        .lock()
        .write_fmt(args)
        .map_err(|e| anyhow::anyhow!("writing to standard output: {e}"))
}

/// `print!` that returns from the enclosing function with the write's error.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::out::write_out(format_args!($($arg)*))?
    };
}

/// `println!` that returns from the enclosing function with the write's error.
macro_rules! outln {
    () => {
        $crate::out::write_out(format_args!("\n"))?
    };
    ($($arg:tt)*) => {
        $crate::out::write_out(format_args!("{}\n", format_args!($($arg)*)))?
    };
}

pub(crate) use {out, outln};
