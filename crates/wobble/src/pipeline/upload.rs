//! Textures into VRAM when the renderer starts: each texture page and CLUT placed
//! (`vram_alloc`), the texels of a semi-transparent material's texture marked with bit 15,
//! and both uploaded through GP0(A0h) (docs/hardware/gpu.md §1, §7, §8).

use super::vram_alloc::{Placement, VramAllocError, VramAllocator};
use crate::scene::Scene;
use gpu::encode;
use gpu::{Gpu, TextureDepth};

/// Place every texture of `scene` in VRAM beside the two display buffers and upload it:
/// the placements, in the scene's texture order.
pub(super) fn upload_textures(
    gpu: &mut Gpu,
    scene: &Scene,
) -> Result<Vec<Placement>, VramAllocError> {
    let widest_clut = scene
        .textures
        .iter()
        .map(|t| t.texture.clut.len())
        .max()
        .unwrap_or(0);
    let mut alloc = VramAllocator::new(scene.screen.width, scene.screen.height, widest_clut);
    let mut placements = Vec::with_capacity(scene.textures.len());
    for (index, t) in scene.textures.iter().enumerate() {
        let p = alloc.place(&t.name, &t.texture)?;
        let (texels, clut) = marked_halfwords(scene, index);
        upload(gpu, p.page_x, p.page_y, t.texture.row_halfwords(), &texels);
        if let Some((x, y)) = p.clut {
            upload(gpu, x, y, clut.len(), &clut);
        }
        placements.push(p);
    }
    Ok(placements)
}

/// Texture `index`'s texel halfwords and CLUT as uploaded. A textured polygon blends only
/// the texels with bit 15 set (docs/hardware/gpu.md §1): a texture worn by a
/// semi-transparent material gets bit 15 on every texel colour (the CLUT's entries, or a
/// 15-bit texture's texels) except transparent 0000h.
fn marked_halfwords(scene: &Scene, index: usize) -> (Vec<u16>, Vec<u16>) {
    let Some(t) = scene.textures.get(index) else {
        return (Vec::new(), Vec::new());
    };
    let blended = scene
        .objects
        .iter()
        .any(|o| o.texture == Some(index) && o.blend.is_some());
    let mark = |c: u16| if blended && c != 0 { c | 0x8000 } else { c };
    match t.texture.depth {
        TextureDepth::Direct15 => {
            let texels = t.texture.halfwords().into_iter().map(mark).collect();
            (texels, Vec::new())
        }
        _ => {
            let clut = t.texture.clut.iter().map(|&c| mark(c)).collect();
            (t.texture.halfwords(), clut)
        }
    }
}

/// Upload halfwords into a `width`-halfword-wide VRAM rectangle at (x, y) with GP0(A0h)
/// (docs/hardware/gpu.md §8).
fn upload(gpu: &mut Gpu, x: u16, y: u16, width: usize, halfwords: &[u16]) {
    if width == 0 || halfwords.is_empty() {
        return;
    }
    let height = halfwords.len() / width;
    gpu.gp0_words(&encode::cpu_to_vram(x, y, width as u16, height as u16));
    for word in encode::pixel_words(halfwords) {
        gpu.gp0(word);
    }
}
