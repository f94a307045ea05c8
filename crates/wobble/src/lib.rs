//! The wobble pipeline and tools: scene rendering through GTE -> ordering table -> GPU,
//! command-stream replay and VRAM dumps.

pub mod render;
