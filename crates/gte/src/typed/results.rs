//! What the typed operations return: the values the hardware computed, read from the
//! registers after the command (docs/hardware/gte.md §5, §8).

use crate::Flag;
use fixed::types::{I4F12, I16F16};

/// An 8-bit-per-channel colour as the colour FIFO stores it.
pub type Rgb = [u8; 3];

/// MAC1-3 and IR1-3 as a command leaves them (docs/hardware/gte.md §4): MACn the 32-bit
/// sums shifted by sf, IRn those saturated to 16 bits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct MacIr {
    /// MAC1, MAC2, MAC3.
    pub mac: [i32; 3],
    /// IR1, IR2, IR3.
    pub ir: [i16; 3],
}

/// One projected vertex (RTPS), with what the projection computed on the way
/// (docs/hardware/gte.md §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Projected {
    /// Screen X, integer-snapped and saturated to -400h..3FFh as the GPU receives it.
    pub x: i16,
    /// Screen Y.
    pub y: i16,
    /// Screen Z (SZ3), 0..FFFFh.
    pub sz: u16,
    /// Depth-cue interpolation factor IR0, 0..1.0.
    pub ir0: I4F12,
    /// FLAG after the command.
    pub flag: Flag,
    /// The vertex in camera space (RT × V + TR), in vertex units: MAC1-3 and IR1-3, IR
    /// saturated to -8000h..=7FFFh (§5.1-5.3).
    pub camera: MacIr,
    /// MAC0: the depth-cue sum quotient × DQA + DQB, its low 32 bits (§5.7).
    pub mac0: i32,
    /// The divide's quotient H / SZ3 in 16.16 (0..=1FFFFh; 1FFFFh on overflow), from the
    /// divide mode in use (§5.5, §6).
    pub quotient: u32,
}

/// One projected vertex (RTPS) with its screen position before the integer truncation.
///
/// `x`/`y` are the 16.16 values of docs/hardware/gte.md §5 step 6 (`quotient * IR1 + OFX`, resp.
/// `quotient * IR2 + OFY`, from the divide mode in use), saturated to -400h..=3FFh.FFFFh: the
/// range whose integer parts are the -400h..3FFh that SXY saturates to, with the fraction kept.
/// So `x.floor()` is always `projected.x` (and likewise for y).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SubpixelProjected {
    /// What [`Geometry::project`](super::Geometry::project) returns for the same state and
    /// vertex.
    pub projected: Projected,
    /// Screen X in 16.16, before truncation.
    pub x: I16F16,
    /// Screen Y in 16.16, before truncation.
    pub y: I16F16,
}

/// Three projected vertices (RTPT). The registers keep the camera-space MAC/IR of the last
/// vertex only; [`Geometry::project`](super::Geometry::project) on each vertex gives all
/// three (the same values, docs/typed-api.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ProjectedTriangle {
    /// Screen X, Y of each vertex (SXY0-2).
    pub xy: [(i16, i16); 3],
    /// Screen Z of each vertex (SZ1-3).
    pub sz: [u16; 3],
    /// Depth-cue IR0 from the last vertex.
    pub ir0: I4F12,
    /// FLAG after the command: the three vertices' projection bits and the last vertex's
    /// depth-cue bits (docs/typed-api.md).
    pub flag: Flag,
    /// The last vertex in camera space: MAC1-3 and IR1-3.
    pub camera: MacIr,
    /// MAC0: the last vertex's depth-cue sum, its low 32 bits.
    pub mac0: i32,
    /// The divide's quotient for each vertex (16.16).
    pub quotient: [u32; 3],
}

/// The result of an interpolation that also pushes a colour (INTPL, GPF, GPL): MAC1-3 and
/// IR1-3, and the colour pushed from MAC1-3 (each MACn SAR 4 saturated to 0..=FFh).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Interpolated {
    /// MAC1-3 and IR1-3.
    pub mac_ir: MacIr,
    /// The colour pushed.
    pub rgb: Rgb,
}
