//! Decoded drawing primitives: what the GP0 command processor hands to the rasterizer
//! (docs/hardware/gpu.md §2-§5). Coordinates are the sign-extended 11-bit vertex plus the drawing offset,
//! not yet wrapped; the rasterizer applies the size-drop rule and the 11-bit wrap.

use crate::state::{BlendMode, TextureDepth};

/// One vertex: screen position (offset applied), colour and texture coordinate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Vertex {
    /// X after adding the drawing offset.
    pub x: i32,
    /// Y after adding the drawing offset.
    pub y: i32,
    /// 8-bit R, G, B. Flat primitives carry the command colour in every vertex.
    pub color: [u8; 3],
    /// Texture U (0..255).
    pub u: u8,
    /// Texture V (0..255).
    pub v: u8,
}

/// Where and how a textured primitive samples: page, depth, CLUT, modulation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Texture {
    /// Texture page left edge in halfwords.
    pub page_x: u16,
    /// Texture page top line.
    pub page_y: u16,
    /// Texture depth.
    pub depth: TextureDepth,
    /// CLUT left edge in halfwords ((attr & 3Fh) * 16).
    pub clut_x: u16,
    /// CLUT line ((attr >> 6) & 1FFh).
    pub clut_y: u16,
    /// Raw texture: texels are written unmodulated (command bit 24).
    pub raw: bool,
}

/// A triangle (a quad arrives as two: (v0,v1,v2) then (v1,v2,v3)) (docs/hardware/gpu.md §3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Triangle {
    /// The three vertices in command order.
    pub vertices: [Vertex; 3],
    /// Gouraud shading: colours interpolated; otherwise `vertices[0].color` is used.
    pub gouraud: bool,
    /// Texture, when the command is textured (and texturing is not disabled).
    pub texture: Option<Texture>,
    /// Semi-transparency mode, when the command is semi-transparent.
    pub blend: Option<BlendMode>,
    /// Dithering applies (E1 bit 9 and the primitive kind allows it: Gouraud or modulated-texture primitives, docs/hardware/gpu.md §6).
    pub dither: bool,
}

/// A line segment; a polyline arrives as consecutive segments (docs/hardware/gpu.md §4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Line {
    /// Endpoints in command order.
    pub vertices: [Vertex; 2],
    /// Gouraud shading; otherwise `vertices[0].color` (command order) is used throughout.
    pub gouraud: bool,
    /// Semi-transparency mode, when semi-transparent.
    pub blend: Option<BlendMode>,
    /// Dithering applies (E1 bit 9; lines always dither when it is set).
    pub dither: bool,
}

/// A rectangle (sprite): never dithered, uses the E1 texture page (docs/hardware/gpu.md §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Rectangle {
    /// Top-left corner after the drawing offset; `u`/`v` are the top-left texel.
    pub origin: Vertex,
    /// Width in pixels (variable: W & 3FFh).
    pub width: u16,
    /// Height in pixels (variable: H & 1FFh).
    pub height: u16,
    /// Texture, when textured.
    pub texture: Option<Texture>,
    /// Semi-transparency mode, when semi-transparent.
    pub blend: Option<BlendMode>,
    /// Mirror U (E1 bit 12).
    pub flip_x: bool,
    /// Mirror V (E1 bit 13).
    pub flip_y: bool,
}

/// Whether a polygon is dithered when E1 bit 9 is set (docs/hardware/gpu.md §6): Gouraud polygons and
/// modulated textured polygons are; flat untextured and raw-textured ones are not.
pub fn dither_applies(gouraud: bool, textured: bool, raw: bool) -> bool {
    if textured { !raw } else { gouraud }
}
