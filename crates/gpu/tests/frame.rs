//! The displayed frame: size from the display ranges (psx-spx "GP1(06h)", "GP1(07h)"),
//! 15/24-bit decoding (psx-spx "Framebuffer"), disabled display, 480i weave, errors.

use gpu::{FrameError, FrameSize, Gpu, PixelFormat};

fn shown(mode: u32, h: (u32, u32), v: (u32, u32)) -> Gpu {
    let mut g = Gpu::new();
    g.gp1(0x0300_0000); // display on
    g.gp1(0x0800_0000 | mode);
    g.gp1(0x0600_0000 | h.1 << 12 | h.0);
    g.gp1(0x0700_0000 | v.1 << 10 | v.0);
    g
}

fn frame(g: &Gpu, format: PixelFormat) -> (FrameSize, Vec<u8>) {
    let size = g.frame_size();
    let mut out = vec![0xAA; size.width as usize * size.height as usize * 4];
    let got = g.display_frame(&mut out, format).unwrap();
    assert_eq!(got, size);
    out.truncate(size.bytes(format));
    (size, out)
}

#[test]
fn widths_follow_the_horizontal_range_and_dot_clock() {
    // psx-spx: pixels = ((X2 - X1) / cycles_per_dot + 2) AND NOT 3, worked by hand.
    let cases = [
        (0x01, 0x260, 0x260 + 2560, 320),    // 2560 / 8 = 320 -> 322 -> 320
        (0x00, 0x260, 0x260 + 2560, 256),    // 2560 / 10 = 256 -> 258 -> 256
        (0x40, 539, 3227, 384),              // 2688 / 7 = 384 -> 386 -> 384
        (0x40, 0x260, 0x260 + 368 * 7, 368), // 368 -> 370 -> 368
        (0x02, 615, 3175, 512),              // 2560 / 5 = 512 -> 514 -> 512
        (0x03, 620, 3180, 640),              // 640 -> 642 -> 640
        (0x01, 0x260, 0x260 + 2590, 324),    // 323 -> 325 -> 324
        (0x01, 0x260, 0x260 + 800, 100),     // 100 -> 102 -> 100
        (0x01, 0x260, 0xFFF, 352),           // X2 clamped to 3413: 2805 / 8 = 350 -> 352
        (0x01, 0x500, 0x500, 0),             // empty range
        (0x01, 0x600, 0x500, 0),             // reversed range
    ];
    for (mode, x1, x2, width) in cases {
        let g = shown(mode, (x1, x2), (0x10, 0x100));
        assert_eq!(g.frame_size().width, width, "mode {mode:#x} {x1}..{x2}");
        assert_eq!(g.display_area().width as u32, width);
    }
}

#[test]
fn heights_follow_the_vertical_range() {
    let cases = [
        (0x01, 0x10, 0x100, 240),
        (0x09, 0x23, 0x123, 256), // PAL, 256 lines
        (0x09, 0x13, 0x133, 288), // PAL, 288 lines (psx-spx A3h +/- 144)
        (0x09, 0x10, 0x3FF, 298), // Y2 clamped to the 314-line PAL field
        (0x01, 0x10, 0x3FF, 247), // ... and to the 263-line NTSC field
        (0x25, 0x10, 0x100, 480), // 480i doubles
        (0x21, 0x10, 0x100, 240), // interlace without bit 2: 240
        (0x2D, 0x23, 0x123, 512), // PAL 480i-style, 256 lines per field
        (0x01, 0x100, 0x10, 0),
    ];
    for (mode, y1, y2, height) in cases {
        let g = shown(mode, (0x260, 0x260 + 2560), (y1, y2));
        assert_eq!(g.frame_size().height, height, "mode {mode:#x} {y1}..{y2}");
    }
}

#[test]
fn fifteen_bit_pixels_widen_by_replication() {
    let mut g = shown(0x01, (0x260, 0x260 + 800), (0x10, 0x12)); // 100 x 2
    g.gp1(0x0500_0000 | 7 << 10 | 1000); // start (1000, 7)
    let v = g.vram_mut();
    // (R, G, B) 5-bit = (31, 16, 1) and (0, 31, 8), mask bit set on the second.
    v.set_pixel(1000, 7, 31 | 16 << 5 | 1 << 10);
    v.set_pixel(1001, 7, 0x8000 | 31 << 5 | 8 << 10);
    // Column 24 is VRAM x 1024 -> wraps to 0.
    v.set_pixel(0, 7, 2);
    v.set_pixel(1000, 8, 31 << 10);
    let (size, rgb) = frame(&g, PixelFormat::Rgb888);
    assert_eq!(
        size,
        FrameSize {
            width: 100,
            height: 2
        }
    );
    // 5 -> 8 bits: 31 -> 255, 16 -> 132, 8 -> 66, 2 -> 16, 1 -> 8, 0 -> 0.
    assert_eq!(rgb[0..6], [255, 132, 8, 0, 255, 66]);
    assert_eq!(rgb[24 * 3..24 * 3 + 3], [16, 0, 0]);
    assert_eq!(rgb[300..303], [0, 0, 255]);
    let (_, rgba) = frame(&g, PixelFormat::Rgba8888);
    assert_eq!(rgba[0..8], [255, 132, 8, 255, 0, 255, 66, 255]);
    assert_eq!(rgba.len(), 100 * 2 * 4);
}

#[test]
fn twenty_four_bit_pixels_are_three_bytes_in_halfwords() {
    let mut g = shown(0x11, (0x260, 0x260 + 32), (0x10, 0x11)); // 24-bit 320: 4 x 1
    g.gp1(0x0500_0000 | 3 << 10 | 64);
    let v = g.vram_mut();
    for (i, h) in [0x2211u16, 0x4433, 0x6655, 0x8877, 0xAA99, 0xCCBB]
        .iter()
        .enumerate()
    {
        v.set_pixel(64 + i, 3, *h);
    }
    let (size, rgb) = frame(&g, PixelFormat::Rgb888);
    assert_eq!(
        size,
        FrameSize {
            width: 4,
            height: 1
        }
    );
    assert_eq!(
        rgb,
        [
            0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88, 0x99, 0xAA, 0xBB, 0xCC
        ]
    );
}

#[test]
fn disabled_display_is_black() {
    let mut g = shown(0x01, (0x260, 0x260 + 800), (0x10, 0x14));
    g.vram_mut().as_mut_slice().fill(0x7FFF);
    g.gp1(0x0300_0001);
    let (size, rgba) = frame(&g, PixelFormat::Rgba8888);
    assert_eq!(
        size,
        FrameSize {
            width: 100,
            height: 4
        }
    );
    assert!(rgba.chunks(4).all(|p| p == [0, 0, 0, 255]));
    let (_, rgb) = frame(&g, PixelFormat::Rgb888);
    assert!(rgb.iter().all(|&b| b == 0));
}

#[test]
fn interlaced_frame_weaves_consecutive_lines() {
    let mut g = shown(0x25, (0x260, 0x260 + 2560), (0x10, 0x100)); // 320x480i
    for y in 0..512 {
        g.vram_mut().set_pixel(0, y, (y % 32) as u16);
    }
    let (size, rgb) = frame(&g, PixelFormat::Rgb888);
    assert_eq!(
        size,
        FrameSize {
            width: 320,
            height: 480
        }
    );
    for row in 0..480usize {
        let c = (row % 32) as u8;
        assert_eq!(rgb[row * 320 * 3], c << 3 | c >> 2, "row {row}");
    }
}

#[test]
fn short_buffer_is_an_error() {
    let g = shown(0x01, (0x260, 0x260 + 2560), (0x10, 0x100));
    let mut out = vec![7u8; 320 * 240 * 3 - 1];
    assert_eq!(
        g.display_frame(&mut out, PixelFormat::Rgb888),
        Err(FrameError::BufferTooSmall {
            needed: 320 * 240 * 3,
            got: 320 * 240 * 3 - 1
        })
    );
    assert!(out.iter().all(|&b| b == 7), "nothing written");
    let mut g = g;
    g.gp1(0x0300_0001);
    assert!(g.display_frame(&mut [], PixelFormat::Rgba8888).is_err());
}

proptest::proptest! {
    /// Any area of any VRAM, 15- or 24-bit, either widening, RGB or RGBA, decodes to what the
    /// halfwords say pixel by pixel (coordinates wrapped at the VRAM edges; psx-spx
    /// "Framebuffer").
    #[test]
    fn any_area_decodes_pixel_by_pixel(
        seed in proptest::prelude::any::<u64>(),
        x in 0u16..1024, y in 0u16..512, width in 0u16..700, height in 0u16..8,
        color_24bit in proptest::prelude::any::<bool>(),
        shift in proptest::prelude::any::<bool>(),
        rgba in proptest::prelude::any::<bool>(),
    ) {
        let mut vram = vec![0u16; 1024 * 512];
        let mut s = seed | 1;
        for p in vram.iter_mut() {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            *p = s as u16;
        }
        let area = gpu::DisplayArea { x, y, width, height, color_24bit };
        let (format, bpp) = if rgba { (PixelFormat::Rgba8888, 4) } else { (PixelFormat::Rgb888, 3) };
        let expand = if shift { gpu::ChannelExpand::Shift } else { gpu::ChannelExpand::Replicate };
        let mut out = vec![0u8; width as usize * height as usize * bpp];
        area.decode(&vram, &mut out, format, expand).unwrap();
        let at = |x: usize, y: usize| vram[(y % 512) * 1024 + x % 1024];
        let widen = |c: u16| {
            let c = (c & 31) as u8;
            if shift { c << 3 } else { c << 3 | c >> 2 }
        };
        for row in 0..height as usize {
            for col in 0..width as usize {
                let (vx, vy) = (x as usize, y as usize + row);
                let rgb = if color_24bit {
                    let byte = |k: usize| (at(vx + k / 2, vy) >> (8 * (k % 2))) as u8;
                    [byte(3 * col), byte(3 * col + 1), byte(3 * col + 2)]
                } else {
                    let p = at(vx + col, vy);
                    [widen(p), widen(p >> 5), widen(p >> 10)]
                };
                let i = (row * width as usize + col) * bpp;
                proptest::prop_assert_eq!(&out[i..i + 3], &rgb[..]);
                if rgba {
                    proptest::prop_assert_eq!(out[i + 3], 255);
                }
            }
        }
    }
}
