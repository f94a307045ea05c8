//! What the command-line tests share: the scratch directory of one test.

#[path = "../../../../tests/support/scratch.rs"]
mod scratch;

pub use scratch::Scratch;
