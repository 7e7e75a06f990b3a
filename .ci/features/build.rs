//! Nothing to build: the build dependency on syn is the point (Cargo.toml).
fn main() {}
