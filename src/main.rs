//! The `pirqa` binary: all the work is in the library; this turns its errors into messages.

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    match cli::run() {
        // Stopped by Ctrl-C after writing what it had: the shell's code for SIGINT.
        Ok(()) if cli::interrupted() => ExitCode::from(130),
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
