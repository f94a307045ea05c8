//! Shared helpers for the workspace integration tests in `tests/`.

mod scratch;

pub use scratch::Scratch;
