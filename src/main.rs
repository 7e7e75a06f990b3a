//! riplab's binary: a thin shell over the library's command line.

use clap::Parser;

/// The system allocator with huge pages for the large blocks of a solve (BENCHMARKS.md, "Huge
/// pages").
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

/// Parse the command line; a parse error is printed plain and sanitised (clap echoes the
/// values it refuses, which may hold escape sequences), with clap's exit code (2).
fn main() -> std::process::ExitCode {
    match riplab::cli::Cli::try_parse() {
        Ok(cli) => riplab::cli::run(cli),
        Err(e) if e.use_stderr() => {
            use std::io::Write as _;
            let text = riplab::text::sanitize_lines(&e.render().to_string());
            // A closed stderr cannot be told about itself: the exit code stands.
            let _ = write!(std::io::stderr().lock(), "{text}");
            std::process::ExitCode::from(e.exit_code().clamp(0, 255) as u8)
        }
        Err(e) => e.exit(),
    }
}
