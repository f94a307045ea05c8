//! The wobble pipeline and tools, stage by stage:
//!
//! - [`scene`]: scene files and validation, meshes, textures and their palettes, VRAM
//!   placement, the built-in scene;
//! - [`pipeline`]: the PS1 renderer, GTE stage -> ordering-table stage -> GPU submission;
//! - [`reference`](mod@reference): the f64 reference renderer the PS1 output is measured against;
//! - [`trade`]: the accuracy/cost trade report;
//! - [`gte_vectors`]: replay of GTE test vectors;
//! - [`gpu_dump`]: GPU dumps (`.psxgpu`) and command streams replayed frame by frame;
//! - [`vram_image`]: VRAM to images and the raw VRAM file format;
//! - [`inspect`]: the draw-by-draw report of a command stream or a rendered frame.

#![forbid(unsafe_code)]
#![deny(missing_docs, rustdoc::broken_intra_doc_links)]

pub mod gpu_dump;
pub mod gte_vectors;
pub mod inspect;
pub mod pipeline;
pub mod reference;
pub mod scene;
pub mod trade;
pub mod vram_image;
