//! The `splitsum` binary: parse, call the library, print errors, map them to exit codes:
//! 0 success, 1 a job (or, for `bake`, any input) failed, 2 a usage error (clap's, or an
//! option the library refuses, before any input is read), 130 interrupted.

mod cli;

use std::process::ExitCode;

use clap::Parser;

use cli::args::{Cli, Command};
use cli::Usage;

/// Exit code after Ctrl-C or SIGTERM (128 + SIGINT, the shell convention).
const INTERRUPTED: i32 = 130;

fn main() -> ExitCode {
    if let Some(message) = cli::misplaced_option(std::env::args()) {
        eprintln!("error: {message}");
        return ExitCode::from(2);
    }
    let cli = Cli::parse();
    cli::quiet_vulkan_loader();
    // Interrupted mid-write: remove the temporaries being written (the destinations keep
    // their previous contents) and exit.
    let _ = ctrlc::set_handler(|| {
        splitsum::remove_in_flight_temporaries();
        eprintln!("interrupted");
        std::process::exit(INTERRUPTED);
    });
    let result = match cli.command {
        Command::Lut(args) => cli::commands::lut(args),
        Command::Cubemap(args) => cli::commands::cubemap(args),
        Command::Bake(args) => cli::commands::bake(args),
        Command::Preview(args) => cli::preview::preview(args),
        Command::Verify(args) => cli::commands::verify(args),
        Command::Inspect(args) => cli::inspect::inspect(args),
        Command::View(args) => cli::commands::view(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(if e.downcast_ref::<Usage>().is_some() {
                2
            } else {
                1
            })
        }
    }
}
