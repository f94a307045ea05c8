//! The picture line by line as the beam scans it out (`Gpu::run_lines`, `Gpu::beam_line`):
//! display start, range and mode changed between lines, 15- and 24-bit lines, 480i fields
//! unwoven. Expected pixels are computed here from the VRAM values the tests write, with the
//! 5-to-8-bit widening `c << 3 | c >> 2` and the 24-bit byte order of psx-spx
//! "Framebuffer" (three bytes R, G, B a pixel, low byte of each halfword first).

use gpu::{EventKind, Gpu, PixelFormat};
use proptest::prelude::*;

/// A 15-bit pattern for VRAM region `r`: every pixel of lines 0..512 different in each.
fn pattern(r: u16, x: u16, y: u16) -> u16 {
    let red = (x.wrapping_mul(3) ^ y) & 31;
    let green = (y.wrapping_add(r * 11)) & 31;
    let blue = ((x >> 5) ^ (y >> 3) ^ (r * 7)) & 31;
    red | green << 5 | blue << 10
}

fn widen(c: u16) -> u8 {
    let c = (c & 31) as u8;
    c << 3 | c >> 2
}

/// The RGB bytes a 15-bit pixel shows as.
fn rgb15(p: u16) -> [u8; 3] {
    [widen(p), widen(p >> 5), widen(p >> 10)]
}

/// A GPU showing 320x240 (GP1(08h) = 1, X 608..3168, Y 16..256) with VRAM lines 0..256
/// holding pattern 0 and lines 256..512 pattern 1.
fn showing() -> Gpu {
    let mut g = Gpu::new();
    for y in 0..512u16 {
        for x in 0..1024u16 {
            g.vram_mut()
                .set_pixel(x as usize, y as usize, pattern(y / 256, x, y));
        }
    }
    g.gp1(0x0300_0000);
    g.gp1(0x0800_0001);
    g.gp1(0x0600_0000 | 3168 << 12 | 608);
    g.gp1(0x0700_0000 | 256 << 10 | 16);
    g
}

/// A line as the test keeps it: its numbers and its RGB bytes.
#[derive(Clone, Debug)]
struct Shown {
    field: u8,
    field_row: u32,
    row: u32,
    vram_y: u16,
    width: u16,
    rgb: Vec<u8>,
}

/// Run `cycles` through `run_lines`, keeping every line.
fn run(g: &mut Gpu, cycles: u32, out: &mut Vec<Shown>) -> gpu::Events {
    g.run_lines(cycles, |l| {
        let mut rgb = vec![0u8; l.bytes(PixelFormat::Rgb888)];
        let n = l.decode(&mut rgb, PixelFormat::Rgb888).unwrap();
        assert_eq!(n, l.area.width as u32);
        out.push(Shown {
            field: l.field,
            field_row: l.field_row,
            row: l.row,
            vram_y: l.vram_y,
            width: l.area.width,
            rgb,
        });
    })
}

/// Run to the next vblank start, keeping nothing.
fn to_vblank(g: &mut Gpu) {
    let n = g.cycles_until(EventKind::VblankStart);
    assert!(g.run(n).vblank_start);
}

/// Run until the beam is in `scanline`, keeping the lines finished meanwhile.
fn to_line(g: &mut Gpu, scanline: u32, out: &mut Vec<Shown>) {
    while g.beam().line != scanline {
        let n = g.cycles_until(EventKind::HblankStart);
        run(g, n, out);
    }
}

/// Run to the next vblank start, keeping the lines.
fn rest_of_field(g: &mut Gpu, out: &mut Vec<Shown>) {
    let n = g.cycles_until(EventKind::VblankStart);
    assert!(run(g, n, out).vblank_start);
}

#[test]
fn display_start_changed_mid_frame_shows_both_halves() {
    let mut g = showing();
    to_vblank(&mut g);
    let mut lines = vec![];
    to_line(&mut g, 16 + 100, &mut lines);
    // Lines 16..115 are finished; the beam is inside line 116.
    assert_eq!(lines.len(), 100);
    // GP1(05h): display start X 64, Y 256 (a game flipping to its second buffer, or a
    // split-screen effect).
    g.gp1(0x0500_0000 | 256 << 10 | 64);
    rest_of_field(&mut g, &mut lines);
    assert_eq!(lines.len(), 240);
    for (r, line) in lines.iter().enumerate() {
        let r = r as u16;
        assert_eq!(
            (line.row, line.field_row, line.field),
            (r as u32, r as u32, 0)
        );
        assert_eq!(line.width, 320);
        let (x0, y) = if r < 100 { (0, r) } else { (64, 256 + r) };
        assert_eq!(line.vram_y, y, "row {r}");
        let expected: Vec<u8> = (0..320)
            .flat_map(|x| rgb15(pattern(y / 256, x0 + x, y)))
            .collect();
        assert!(line.rgb == expected, "row {r}");
    }
    // The woven whole-frame helper shows what VRAM holds now: all from line 256 on.
    let mut frame = vec![0u8; g.frame_size().bytes(PixelFormat::Rgb888)];
    g.display_frame(&mut frame, PixelFormat::Rgb888).unwrap();
    assert_eq!(&frame[..3], &rgb15(pattern(1, 64, 256)));
}

#[test]
fn vram_written_behind_the_beam_shows_in_the_next_frame_only() {
    let mut g = showing();
    to_vblank(&mut g);
    let mut lines = vec![];
    to_line(&mut g, 16 + 50, &mut lines);
    // Fill VRAM lines 0..240 with one colour (GP0(02h)): rows 0..49 were shown before it.
    g.gp0_words(&[0x0200_00FF, 0, 240 << 16 | 1008]);
    rest_of_field(&mut g, &mut lines);
    let red = rgb15(0x001F);
    for (r, line) in lines.iter().enumerate() {
        let first: [u8; 3] = line.rgb[..3].try_into().unwrap();
        if r < 50 {
            assert_eq!(first, rgb15(pattern(0, 0, r as u16)), "row {r}");
        } else {
            assert_eq!(first, red, "row {r}");
        }
    }
}

#[test]
fn mode_and_range_changes_take_effect_at_the_next_line() {
    let mut g = showing();
    to_vblank(&mut g);
    let mut lines = vec![];
    to_line(&mut g, 16 + 60, &mut lines);
    // 24-bit colour, GP1(06h) 2560 -> 1600 cycles: 200 pixels of 3 bytes, from halfword 0.
    g.gp1(0x0800_0011);
    g.gp1(0x0600_0000 | 2208 << 12 | 608);
    to_line(&mut g, 16 + 120, &mut lines);
    // 640 wide (divider 4), 15-bit: 2560 / 4 + 2 rounded to 4 = 640.
    g.gp1(0x0800_0003);
    g.gp1(0x0600_0000 | 3168 << 12 | 608);
    rest_of_field(&mut g, &mut lines);
    assert_eq!(lines.len(), 240);
    for (r, line) in lines.iter().enumerate() {
        let y = r as u16;
        let expected: Vec<u8> = if r < 60 {
            assert_eq!(line.width, 320);
            (0..320).flat_map(|x| rgb15(pattern(0, x, y))).collect()
        } else if r < 120 {
            assert_eq!(line.width, 200);
            // Three bytes a pixel from consecutive halfwords, low byte first.
            let byte = |k: u16| {
                let h = pattern(0, k / 2, y);
                if k.is_multiple_of(2) {
                    h as u8
                } else {
                    (h >> 8) as u8
                }
            };
            (0..600).map(byte).collect()
        } else {
            assert_eq!(line.width, 640);
            (0..640).flat_map(|x| rgb15(pattern(0, x, y))).collect()
        };
        assert!(line.rgb == expected, "row {r}");
    }
}

#[test]
fn interlaced_fields_come_unwoven() {
    // 480i, 320 wide, display start Y 1: field 0 shows VRAM lines 1, 3, 5, ..., field 1
    // lines 2, 4, 6, ... (docs/gpu.md "Interlaced drawing": field 0 shows the start line).
    let mut g = showing();
    g.gp1(0x0800_0025);
    g.gp1(0x0500_0000 | 1 << 10);
    to_vblank(&mut g);
    let field = g.beam().field;
    let mut lines = vec![];
    rest_of_field(&mut g, &mut lines);
    rest_of_field(&mut g, &mut lines);
    assert_eq!(lines.len(), 480);
    // The field after a vblank start is the next one; its lines come first, all of them.
    let first = field ^ 1;
    for (i, line) in lines.iter().enumerate() {
        let f = if i < 240 { first } else { first ^ 1 };
        let field_row = (i % 240) as u32;
        assert_eq!((line.field, line.field_row), (f, field_row));
        assert_eq!(line.row, 2 * field_row + f as u32);
        assert_eq!(line.vram_y as u32, 1 + line.row);
        let y = line.vram_y;
        assert_eq!(&line.rgb[..3], &rgb15(pattern(y / 256, 0, y)));
    }
    // Woven by row, both fields are the frame the whole-frame helper shows.
    let size = g.frame_size();
    assert_eq!((size.width, size.height), (320, 480));
    let mut woven = vec![0u8; size.bytes(PixelFormat::Rgb888)];
    for line in &lines {
        let at = line.row as usize * 320 * 3;
        woven[at..at + 320 * 3].copy_from_slice(&line.rgb);
    }
    let mut frame = vec![0u8; size.bytes(PixelFormat::Rgb888)];
    g.display_frame(&mut frame, PixelFormat::Rgb888).unwrap();
    assert!(woven == frame);
}

#[test]
fn a_disabled_display_gives_black_lines_of_its_width() {
    let mut g = showing();
    g.gp1(0x0300_0001);
    let mut lines = vec![];
    to_vblank(&mut g);
    rest_of_field(&mut g, &mut lines);
    assert_eq!(lines.len(), 240);
    assert!(
        lines
            .iter()
            .all(|l| l.width == 320 && l.rgb.iter().all(|&b| b == 0))
    );
    // RGBA: alpha 255; a short buffer is an error and is left alone.
    g.gp1(0x0300_0000);
    to_line(&mut g, 20, &mut lines);
    let line = g.beam_line().expect("line 20 is displayed");
    let mut rgba = vec![7u8; line.bytes(PixelFormat::Rgba8888)];
    line.decode(&mut rgba, PixelFormat::Rgba8888).unwrap();
    let [r, gr, b] = rgb15(pattern(0, 0, 4));
    assert_eq!(&rgba[..4], &[r, gr, b, 255]);
    let mut short = vec![7u8; line.bytes(PixelFormat::Rgba8888) - 1];
    assert!(line.decode(&mut short, PixelFormat::Rgba8888).is_err());
    assert!(short.iter().all(|&b| b == 7));
}

#[test]
fn beam_line_is_the_line_being_scanned() {
    let mut g = showing();
    to_vblank(&mut g);
    // Vblank: lines 256..262 and 0..15 are not displayed.
    assert!(g.beam_line().is_none());
    let mut lines = vec![];
    to_line(&mut g, 16, &mut lines);
    assert!(lines.is_empty());
    // The beam is at the hblank start of line 16; each step runs to the next line's, past
    // the end of the line the beam was on.
    for scanline in 16..256 {
        let line = g.beam_line().expect("displayed");
        assert_eq!((line.scanline, line.row), (scanline, scanline - 16));
        let mut ended = vec![];
        g.run_lines(g.cycles_until(EventKind::HblankStart), |l| {
            ended.push(l.scanline)
        });
        assert_eq!(ended, [scanline]);
    }
    assert!(g.beam_line().is_none());
}

proptest! {
    /// `run_lines` reports the events of `run` over the same time and leaves the GPU in the
    /// same state, in any split; it gives each displayed line once, in order.
    #[test]
    fn run_lines_is_run_plus_the_lines(
        mode in 0u32..0x80,
        y1 in 0u32..400, y2 in 0u32..400,
        splits in prop::collection::vec(1u32..300_000, 1..20),
    ) {
        let mut a = Gpu::new();
        a.gp1(0x0800_0000 | mode);
        a.gp1(0x0700_0000 | y2 << 10 | y1);
        let mut b = a.clone();
        let mut seen: Vec<(u8, u32)> = vec![];
        for &s in &splits {
            let ea = a.run(s);
            let eb = b.run_lines(s, |l| seen.push((l.field, l.scanline)));
            prop_assert_eq!(ea, eb);
        }
        prop_assert!(a == b);
        // Lines of field `f` (docs/gpu.md "Video timing"): 263 NTSC / 314 PAL; interlaced,
        // field 0 is one line longer than field 1 (263/262, 313/312).
        let (pal, interlaced) = (mode & 0x08 != 0, mode & 0x20 != 0);
        let lines = |f: u8| match (pal, interlaced) {
            (false, false) => 263,
            (true, false) => 314,
            (false, true) => 263 - u32::from(f),
            (true, true) => 313 - u32::from(f),
        };
        // The GPU starts at line 0 of field 0: the first line given is Y1 of field 0.
        if let Some(&first) = seen.first() {
            prop_assert_eq!(first, (0, y1));
        }
        for w in seen.windows(2) {
            let ((f0, l0), (f1, l1)) = (w[0], w[1]);
            if f1 == f0 && l1 == l0 + 1 {
                continue;
            }
            // A new field: the last one ended on its last displayed line and this one starts
            // on Y1. Interlaced, the fields alternate, unless the other field shows no line
            // (Y1 at or past its end: line 312 of PAL, 262 of NTSC, is only in field 0).
            prop_assert_eq!(l0 + 1, y2.min(lines(f0)), "field {} ended early", f0);
            prop_assert_eq!(l1, y1);
            let next = if !interlaced || y1 >= lines(f0 ^ 1) { f0 } else { f0 ^ 1 };
            prop_assert_eq!(f1, next);
        }
        for &(_, l) in &seen {
            prop_assert!(y1 <= l && l < y2, "line {} outside {}..{}", l, y1, y2);
        }
    }
}
