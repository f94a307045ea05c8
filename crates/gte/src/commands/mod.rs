//! The 22 GTE commands, grouped by what they compute (docs/hardware/gte.md §5, §7, §8).

mod depth_cue;
mod light;
mod matrix;
mod rtp;
mod screen;
