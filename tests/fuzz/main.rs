//! Fuzzing on stable Rust (docs/reliability.md, "Fuzzing"): every parser
//! that reads what a user types, drops or links is fed random,
//! structure-aware inputs, each made by [`arbitrary`] from random bytes that
//! its seed and index fix. A target runs in a child process of this binary,
//! so a crash that cannot be caught (a stack overflow) or a hang is seen
//! from outside; every failing input is saved to a file.
//!
//! `cargo test --release --test fuzz` runs the short fixed run (each
//! target's `quick` count, seed 1); `scripts/fuzz [SECONDS]` runs each
//! target for a time. Options (after `--`):
//!
//! - `--seconds S` or `--count N`: per target;
//! - `--seed N` (default 1), `--target NAME` (repeatable; default all);
//! - `--out DIR`: where failing inputs go (default `target/tmp/fuzz`);
//! - `--replay FILE --target NAME`: runs one saved input.

#[path = "../common/mod.rs"]
mod common;
mod driver;
mod inputs;
mod targets;

fn main() {
    std::process::exit(driver::main());
}
