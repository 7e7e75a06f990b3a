//! riplab's binary: a thin shell over the library's command line.

use clap::Parser;

fn main() -> std::process::ExitCode {
    riplab::cli::run(riplab::cli::Cli::parse())
}
