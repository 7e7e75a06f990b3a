//! The numerics, one module per part of the library it checks (fem, contact, the pressures,
//! inf-sup, locking, the contact methods, Nitsche, stability under stress, the stresses, the
//! study, the scenarios): one test binary, so that `cargo test` links few times (the thread
//! count's test has its own, tests/threads, since it changes a process-wide setting).

#[macro_use]
#[path = "../common/mod.rs"]
mod common;

mod contact;
mod extremes;
mod fem;
mod friction;
mod grading;
mod infsup;
mod locking;
mod methods;
mod nitsche;
mod nitsche_inputs;
mod pressures;
mod round_off;
mod scenario_props;
mod scenarios;
mod sliding;
mod stresses;
mod study;
mod two_bodies;
mod verify;
