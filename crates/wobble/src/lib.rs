//! The wobble pipeline and tools: scene rendering through GTE -> ordering table -> GPU,
//! GTE vector replay, command-stream replay and VRAM dumps.

pub mod gte_replay;
pub mod render;
pub mod vram_image;
