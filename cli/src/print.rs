//! Printing to standard output without a panic: `say!` and `say_raw!`, `println!` and `print!`
//! that stop quietly when standard output is a closed pipe (`orthtree mesh | head -3`: the
//! reader wanted no more) and end the program with exit code 1 and an `error:` line on any
//! other failure to write (a full disk), so that no output is lost in silence. Shared by the
//! command-line program, the examples and the comparison programs (each includes this file).

/// `print!` that stops quietly on a closed pipe and exits with code 1 on any other write error.
#[macro_export]
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if let Err(e) = write!(std::io::stdout().lock(), $($arg)*)
            && e.kind() != std::io::ErrorKind::BrokenPipe
        {
            eprintln!("error: cannot write to standard output: {e}");
            std::process::exit(1);
        }
    }};
}

/// `println!` as [`say_raw!`] prints.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::say_raw!("{}\n", format_args!($($arg)*))
    };
}
