//! Texel error, the trade report's measure of texture mapping: a scene whose textures encode
//! their own texel coordinates is drawn, each pixel is decoded back to the texel the hardware
//! sampled, and the distance to the reference renderer's texel (the shorter way round a
//! repeating texture) is that pixel's error. The heat maps colour the same per-pixel error.

use crate::reference::ReferenceFrame;
use crate::scene::Scene;
use crate::scene::texture::Texture;
use gpu::TextureDepth;

/// A scene whose textures encode their own texel coordinates (15-bit: R = u & 31,
/// G = v & 31, B = u >> 5 | (v >> 5) << 2, for textures up to 128 texels a side; larger
/// textures are encoded at half resolution), lit by nothing, undithered, opaque: drawing it
/// through the pipeline shows which texel the hardware sampled at every pixel.
pub fn coordinate_scene(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    for t in &mut s.textures {
        let (w, h) = (t.texture.width, t.texture.height);
        let pixels: Vec<[u8; 4]> = (0..w as usize * h as usize)
            .map(|i| {
                let (u, v) = ((i % w as usize) as u32, (i / w as usize) as u32);
                let (u, v) = if w > 128 || h > 128 {
                    (u / 2, v / 2)
                } else {
                    (u, v)
                };
                let b = (u >> 5) | ((v >> 5) << 2);
                [
                    ((u & 31) << 3) as u8,
                    ((v & 31) << 3) as u8,
                    (b << 3) as u8,
                    255,
                ]
            })
            .collect();
        if let Ok(tex) = Texture::from_rgba(w, h, &pixels, TextureDepth::Direct15) {
            t.texture = tex;
        }
    }
    s.light = None;
    s.fog = None;
    s.screen.dither = false;
    s.screen.background = [0, 0, 0];
    for o in &mut s.objects {
        o.blend = None;
        o.color = if o.texture.is_some() {
            [128, 128, 128]
        } else {
            [0, 0, 0]
        };
    }
    s
}

/// Decode a coordinate-scene pixel: `None` for background or untextured surfaces.
pub fn decode_texel(p: u16, scale: i32) -> Option<(i32, i32)> {
    if p == 0 {
        return None;
    }
    let (r, g, b) = (
        (p & 31) as i32,
        ((p >> 5) & 31) as i32,
        ((p >> 10) & 31) as i32,
    );
    Some((
        (r | (b & 3) << 5) * scale,
        (g | ((b >> 2) & 3) << 5) * scale,
    ))
}

/// Distance between two texels of a texture that repeats every `size` texels: the shorter
/// way round, so a seam between repeats is not an error.
fn wrapped(d: i32, size: i32) -> f64 {
    let d = d.rem_euclid(size.max(1));
    d.min(size - d) as f64
}

/// The texel error at one pixel (Euclidean, in texels, repeat-aware): coordinate-scene pixel
/// `p` against the reference's texel `texel` of a texture of `size` texels there; `None` where
/// either shows no textured surface.
pub(super) fn texel_error(
    p: u16,
    texel: Option<(i32, i32)>,
    size: Option<(i32, i32)>,
    scale: i32,
) -> Option<f64> {
    let (hu, hv) = decode_texel(p, scale)?;
    let (ru, rv) = texel?;
    let (w, h) = size?;
    let (du, dv) = (wrapped(hu - ru, w), wrapped(hv - rv, h));
    Some((du * du + dv * dv).sqrt())
}

/// Texel errors over the pixels where both the hardware and the reference show a textured
/// surface.
pub fn texel_errors(hw: &[u16], reference: &ReferenceFrame, scale: i32) -> Vec<f64> {
    hw.iter()
        .zip(reference.texel.iter().zip(&reference.texture_size))
        .filter_map(|(&p, (&texel, &size))| texel_error(p, texel, size, scale))
        .collect()
}
