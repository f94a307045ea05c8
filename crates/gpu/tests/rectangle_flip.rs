//! Rectangle X flip (E1 bit 12, docs/hardware/gpu.md §5): the origin column samples
//! `u0 | 1` and U counts down by one per pixel, wrapping at 256; the texture window applies
//! to the stepped U; clipping on the left keeps the unclipped mapping. Every texture depth,
//! every U0 (even and odd), with and without a texture window, with and without a left clip.
//! Expected texels come from the texture written below and the rule, not from the crate.

use gpu::Gpu;

const PAGE_X: u32 = 512;
const ROW: u32 = 100;
const WIDTH: u32 = 40;
const X0: u32 = 32;

/// 4-bit index of texel u in the test texture.
fn index4(u: u32) -> u16 {
    ((u * 5 + 1) & 15) as u16
}

/// 8-bit index of texel u.
fn index8(u: u32) -> u16 {
    ((u * 7 + 3) & 0xFF) as u16
}

/// Depth 0 (4-bit), 1 (8-bit), 2 (15-bit): the colour texel u of row 0 must produce.
fn texel(depth: u32, u: u32) -> u16 {
    match depth {
        0 => 0x2000 + index4(u),
        1 => 0x1000 + index8(u),
        _ => 0x0400 + u as u16,
    }
}

fn upload(g: &mut Gpu, x: u32, y: u32, pixels: &[u16]) {
    g.gp0_words(&[0xA000_0000, y << 16 | x, 1 << 16 | pixels.len() as u32]);
    for pair in pixels.chunks(2) {
        let hi = pair.get(1).copied().unwrap_or(0) as u32;
        g.gp0(hi << 16 | pair[0] as u32);
    }
}

/// A GPU with row 0 of the page at x = 512 holding the texture in the given depth, and the
/// 4-bit CLUT at (0, 301), the 8-bit CLUT at (0, 300).
fn textured_gpu(depth: u32) -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
    let row: Vec<u16> = match depth {
        0 => (0..64)
            .map(|k| (0..4).map(|j| index4(4 * k + j) << (4 * j)).sum())
            .collect(),
        1 => (0..128)
            .map(|k| index8(2 * k) | index8(2 * k + 1) << 8)
            .collect(),
        _ => (0..256).map(|u| 0x0400 + u as u16).collect(),
    };
    upload(&mut g, PAGE_X, 0, &row);
    let clut8: Vec<u16> = (0..256).map(|i| 0x1000 + i).collect();
    upload(&mut g, 0, 300, &clut8);
    let clut4: Vec<u16> = (0..16).map(|i| 0x2000 + i).collect();
    upload(&mut g, 0, 301, &clut4);
    g
}

#[test]
fn x_flip_every_depth_u0_window_and_clip() {
    for depth in 0..3u32 {
        let mut g = textured_gpu(depth);
        let clut_y = if depth == 0 { 301 } else { 300 };
        for flip in [false, true] {
            for window in [false, true] {
                // Window: mask X 6 (U bits 4-5), offset X 4 -> u' = (u & !30h) | 20h.
                let (e2, apply) = if window {
                    (
                        0xE200_0000 | 4 << 10 | 6,
                        (|u: u32| (u & !0x30) | 0x20) as fn(u32) -> u32,
                    )
                } else {
                    (0xE200_0000, (|u: u32| u) as fn(u32) -> u32)
                };
                for clip in [0u32, 3] {
                    for u0 in 0..256u32 {
                        g.gp0_words(&[0x0200_0000, ROW << 16, 1 << 16 | 128]); // clear the row
                        g.gp0(0xE300_0000 | (X0 + clip)); // left edge
                        g.gp0(e2);
                        g.gp0(0xE100_0000 | (flip as u32) << 12 | depth << 7 | (PAGE_X / 64));
                        g.gp0_words(&[
                            0x6500_0000,
                            ROW << 16 | X0,
                            clut_y << 22 | u0,
                            1 << 16 | WIDTH,
                        ]);
                        for x in X0..X0 + WIDTH + 2 {
                            let got = g.vram().pixel(x as usize, ROW as usize);
                            let dx = x.wrapping_sub(X0);
                            let want = if x < X0 + clip || dx >= WIDTH {
                                0
                            } else if flip {
                                texel(depth, apply(((u0 | 1) + 256 - dx % 256) % 256))
                            } else {
                                texel(depth, apply((u0 + dx) % 256))
                            };
                            assert_eq!(
                                got, want,
                                "depth {depth} flip {flip} window {window} clip {clip} u0 {u0} x {x}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// The first texel of an X-flipped rectangle for even U0 is U0 + 1: from U0 = 4 the row
/// reads texels 5, 4, 3, 2 (15-bit texel u = 400h + u).
#[test]
fn x_flip_even_u0_starts_one_higher() {
    let mut g = textured_gpu(2);
    g.gp0(0xE100_1000 | 2 << 7 | (PAGE_X / 64));
    g.gp0_words(&[0x6500_0000, ROW << 16, 4, 1 << 16 | 4]);
    let got: Vec<u16> = (0..4).map(|x| g.vram().pixel(x, ROW as usize)).collect();
    assert_eq!(got, [0x405, 0x404, 0x403, 0x402]);
}
