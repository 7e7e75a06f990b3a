//! Nothing of its own: `.ci/run` builds this crate to build riplab with other features than
//! the default on the test build's dependencies (Cargo.toml says why it depends on what).
