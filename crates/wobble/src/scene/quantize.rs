//! Palette choice for CLUT textures: the CLUT and the per-texel indices.
//!
//! An image that already has few enough colours keeps them exactly (after the 8-to-5-bit
//! reduction): NeuQuant learns its palette from a sample of the pixels and moves every entry
//! towards its neighbours, so even an image with only 16 colours would come back with
//! slightly different ones (and its network is not tuned below about 26 entries); pixel art
//! and textures already drawn to a palette, the usual PS1 material, must survive unchanged.
//! Otherwise the palette is chosen by NeuQuant from the `color_quant` crate (maintained by
//! the image-rs project, no dependencies, good palettes for photographic input at small
//! sizes; it is also what `image`'s GIF encoder uses).

use super::texel::to_1555;

/// The CLUT (at most `size` entries, before padding) and per-pixel indices for `pixels`
/// whose 1555 colours are `colors`: the distinct colours themselves when they fit, otherwise
/// a NeuQuant palette.
pub fn palette(pixels: &[[u8; 4]], colors: &[u16], size: usize) -> (Vec<u16>, Vec<u16>) {
    let mut distinct: Vec<u16> = colors.to_vec();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() <= size {
        let texels = colors
            .iter()
            .map(|c| distinct.binary_search(c).unwrap_or(0) as u16)
            .collect();
        (distinct, texels)
    } else {
        neuquant(pixels, colors, size)
    }
}

/// NeuQuant palette for the opaque pixels; transparent pixels keep entry 0 = 0000h.
fn neuquant(pixels: &[[u8; 4]], colors: &[u16], size: usize) -> (Vec<u16>, Vec<u16>) {
    let has_transparent = colors.contains(&0);
    let slots = if has_transparent { size - 1 } else { size };
    let rgba: Vec<u8> = pixels
        .iter()
        .filter(|p| p[3] >= 128)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    let nq = color_quant::NeuQuant::new(10, slots, &rgba);
    let offset = usize::from(has_transparent);
    let mut clut = vec![0u16; offset];
    for chunk in nq.color_map_rgba().chunks_exact(4) {
        clut.push(to_1555([chunk[0], chunk[1], chunk[2], 255]));
    }
    let texels = pixels
        .iter()
        .map(|p| {
            if p[3] < 128 {
                0
            } else {
                (nq.index_of(&[p[0], p[1], p[2], 255]) + offset) as u16
            }
        })
        .collect();
    (clut, texels)
}
