//! The numerics, one module per part of the library it checks (fem, contact, the pressures,
//! inf-sup, locking, the contact methods, Nitsche, stability under stress, the stresses, the
//! study, threads, the scenarios): one test binary, so that `cargo test` links once.

#[macro_use]
#[path = "../common/mod.rs"]
mod common;

mod contact;
mod fem;
mod infsup;
mod locking;
mod methods;
mod nitsche;
mod pressures;
mod round_off;
mod scenario_props;
mod scenarios;
mod stress;
mod stresses;
mod study;
mod threads;
mod verify;
