//! The wobble pipeline and tools: scene rendering through GTE -> ordering table -> GPU,
//! GTE vector replay, command-stream replay and VRAM dumps.

pub mod default_scene;
pub mod gte_replay;
pub mod inspect;
pub mod mesh;
pub mod pipeline;
pub mod quantize;
pub mod reference;
pub mod render;
pub mod scene;
pub mod tessellate;
pub mod trade;
pub mod vram_alloc;
pub mod vram_image;
