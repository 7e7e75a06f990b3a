//! riplab's binary: a thin shell over the library's command line.

/// The system allocator with huge pages for the large blocks of a solve (BENCHMARKS.md, "Huge
/// pages").
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

fn main() -> std::process::ExitCode {
    riplab::run_command_line()
}
