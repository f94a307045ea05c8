//! GP0 transfers and environment, GP1, GPUSTAT, packet assembly and ordering tables, on
//! hand-worked cases (docs/hardware/gpu.md §2, §8, §9).

use gpu::{Gpu, command_stream};
use gpu::{OrderingTable, OtError, walk_ram};
use proptest::prelude::*;

fn px(g: &Gpu, x: usize, y: usize) -> u16 {
    g.vram().pixel(x, y)
}

/// Fill: x is rounded down to 16, width up to 16; w = 3F1h becomes 400h (the whole line);
/// colour channels >> 3; the drawing area and E6 do not apply.
#[test]
fn fill_alignment_and_size() {
    let mut g = Gpu::new();
    g.gp0(0xE600_0003);
    g.gp0_words(&[0x0200_00FF, 0x0001_0013, 0x0001_0001]); // x=13h -> 10h, w=1 -> 16
    for x in 0..40 {
        let want = if (16..32).contains(&x) { 0x1F } else { 0 };
        assert_eq!(px(&g, x, 1), want, "x={x}");
    }
    g.gp0_words(&[0x0200_FF00, 0x0002_0000, 0x0001_03F1]);
    assert_eq!(px(&g, 0, 2), 0x03E0);
    assert_eq!(px(&g, 1023, 2), 0x03E0);
    // Zero height draws nothing.
    g.gp0_words(&[0x0200_FFFF, 0x0003_0000, 0x0000_0010]);
    assert_eq!(px(&g, 0, 3), 0);
}

/// Fill wraps at the bottom of VRAM: y = 510, h = 4 covers lines 510, 511, 0, 1.
#[test]
fn fill_wraps() {
    let mut g = Gpu::new();
    g.gp0_words(&[0x0200_00FF, 510 << 16, 0x0004_0010]);
    for y in [510, 511, 0, 1] {
        assert_eq!(px(&g, 0, y), 0x1F, "y={y}");
    }
    assert_eq!(px(&g, 0, 2), 0);
}

/// CPU-to-VRAM wraps at the right edge; VRAM-to-CPU reads the same pixels back, two per
/// word, low half first.
#[test]
fn cpu_transfers_wrap_and_round_trip() {
    let mut g = Gpu::new();
    g.gp0_words(&[
        0xA000_0000,
        5 << 16 | 1023,
        0x0001_0003,
        0x2222_1111,
        0x0000_3333,
    ]);
    assert_eq!(px(&g, 1023, 5), 0x1111);
    assert_eq!(px(&g, 0, 5), 0x2222);
    assert_eq!(px(&g, 1, 5), 0x3333);
    g.gp0_words(&[0xC000_0000, 5 << 16 | 1023, 0x0001_0003]);
    assert_eq!(g.gpustat() >> 27 & 1, 1, "ready to send VRAM");
    assert_eq!(g.gpuread(), 0x2222_1111);
    assert_eq!(g.gpuread(), 0x0000_3333);
    assert_eq!(g.gpustat() >> 27 & 1, 0);
}

/// E6 applies to CPU-to-VRAM: set-mask writes bit 15; check-mask skips protected pixels.
#[test]
fn mask_on_transfers() {
    let mut g = Gpu::new();
    g.gp0(0xE600_0001);
    g.gp0_words(&[0xA000_0000, 0, 0x0001_0002, 0x0000_0000]);
    assert_eq!(
        px(&g, 0, 0),
        0x8000,
        "a 0 written with set-mask reads 8000h"
    );
    g.gp0(0xE600_0002);
    g.gp0_words(&[0xA000_0000, 0, 0x0001_0002, 0x5555_1234]);
    assert_eq!(px(&g, 0, 0), 0x8000, "protected");
    assert_eq!(px(&g, 1, 0), 0x8000, "protected");
}

/// VRAM-to-VRAM copy: size 0 means the maximum; rows are read before they are written, so a
/// copy one pixel to the right shifts a row without smearing.
#[test]
fn vram_copy() {
    let mut g = Gpu::new();
    g.gp0_words(&[0xA000_0000, 0, 0x0001_0004, 0x0002_0001, 0x0004_0003]);
    g.gp0_words(&[0x8000_0000, 0, 1, 0x0001_0004]);
    let row: Vec<u16> = (0..6).map(|x| px(&g, x, 0)).collect();
    assert_eq!(row, [1, 1, 2, 3, 4, 0]);
    // Copy to (1000, 100) wraps at the right edge.
    g.gp0_words(&[0x8000_0000, 0, 100 << 16 | 1022, 0x0001_0004]);
    assert_eq!(
        [
            px(&g, 1022, 100),
            px(&g, 1023, 100),
            px(&g, 0, 100),
            px(&g, 1, 100)
        ],
        [1, 1, 2, 3]
    );
}

/// A command stream gives the same VRAM however its words are split between calls.
#[test]
fn packets_split_anywhere() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/gpu/triangle.gpu"
    ))
    .unwrap();
    let commands = command_stream::parse(&text).unwrap();
    let mut whole = Gpu::new();
    command_stream::run(&mut whole, &commands);
    let words: Vec<(bool, u32)> = commands
        .iter()
        .flat_map(|c| {
            c.words
                .iter()
                .map(move |w| (c.port == command_stream::Port::Gp1, *w))
        })
        .collect();
    for chunk in [1, 2, 3, 5, 7, 13] {
        let mut g = Gpu::new();
        let mut pending = Vec::new();
        for &(gp1, w) in &words {
            if gp1 {
                g.gp0_words(&pending);
                pending.clear();
                g.gp1(w);
            } else {
                pending.push(w);
                if pending.len() == chunk {
                    g.gp0_words(&pending);
                    pending.clear();
                }
            }
        }
        g.gp0_words(&pending);
        assert!(g.vram() == whole.vram(), "chunk {chunk}");
    }
}

/// GPUSTAT mirrors E1 bits 0-10 in bits 0-10, E6 in bits 11-12, GP1(08h) in 16-22.
#[test]
fn gpustat_bits() {
    let mut g = Gpu::new();
    assert_eq!(
        g.gpustat() & 0x1FFF_FFFF,
        0x1480_2000,
        "reset: display off, ready"
    );
    g.gp0(0xE100_07FF & !0x180 | 0x100); // depth 2, every other bit set
    assert_eq!(g.gpustat() & 0x7FF, 0x7FF & !0x180 | 0x100);
    g.gp0(0xE600_0003);
    assert_eq!(g.gpustat() >> 11 & 3, 3);
    g.gp1(0x0800_003F);
    // Mode 3Fh: bits 0-5 map to GPUSTAT 17-22; bit 6 (368 wide) is clear, so bit 16 is 0.
    assert_eq!(g.gpustat() >> 16 & 0x7F, 0b111_1110);
    g.gp1(0x0300_0000);
    assert_eq!(g.gpustat() >> 23 & 1, 0);
    g.gp1(0x0400_0002);
    assert_eq!(g.gpustat() >> 29 & 3, 2);
}

/// Display area width and height from GP1(08h) and the reset display ranges (2560 video
/// cycles, 240 lines), start from GP1(05h). psx-spx "GP1(06h)": pixels = (cycles / divider
/// + 2) & !3, so 368-wide mode shows 2560 / 7 = 365 -> 364 pixels of the reset range.
#[test]
fn display_area_modes() {
    let mut g = Gpu::new();
    for (mode, w) in [(0, 256), (1, 320), (2, 512), (3, 640), (0x40, 364)] {
        g.gp1(0x0800_0000 | mode);
        assert_eq!(g.display_area().width, w);
        assert_eq!(g.display_area().height, 240);
    }
    g.gp1(0x0600_0000 | (0x200 + 368 * 7) << 12 | 0x200);
    assert_eq!(g.display_area().width, 368);
    g.gp1(0x0600_0000 | (0x200 + 2560) << 12 | 0x200);
    g.gp1(0x0800_0024 | 3);
    assert_eq!(
        (g.display_area().width, g.display_area().height),
        (640, 480)
    );
    g.gp1(0x0800_0011);
    assert!(g.display_area().color_24bit);
    g.gp1(0x0500_0000 | 256 << 10 | 320);
    assert_eq!((g.display_area().x, g.display_area().y), (320, 256));
}

/// GP1(10h) latches E2-E5 values and the version into GPUREAD.
#[test]
fn gpu_info() {
    let mut g = Gpu::new();
    g.gp0(0xE200_1234 & 0xE20F_FFFF);
    g.gp0(0xE300_0000 | 3 << 10 | 4);
    g.gp0(0xE400_0000 | 200 << 10 | 300);
    g.gp0(0xE500_0000 | 0x7FF << 11 | 5);
    g.gp1(0x1000_0002);
    assert_eq!(g.gpuread(), 0x1234);
    g.gp1(0x1000_0003);
    assert_eq!(g.gpuread(), 3 << 10 | 4);
    g.gp1(0x1000_0004);
    assert_eq!(g.gpuread(), 200 << 10 | 300);
    g.gp1(0x1000_0005);
    assert_eq!(g.gpuread(), 0x7FF << 11 | 5);
    g.gp1(0x1000_0007);
    assert_eq!(g.gpuread(), 2);
}

/// GP1(01h) abandons a partial packet: the next word starts a new command.
#[test]
fn command_buffer_reset() {
    let mut g = Gpu::new();
    g.gp0(0x2000_00FF); // start of a flat triangle
    g.gp1(0x0100_0000);
    g.gp0_words(&[0x0200_00FF, 0, 0x0001_0010]);
    assert_eq!(px(&g, 0, 0), 0x1F);
}

/// A quad is drawn as two triangles, the first as soon as its words are in and the GPU
/// reaches it (docs/gpu.md, "A quad cut short"): GP1(01h) after the first triangle's words
/// of an idle GPU leaves that triangle drawn, as the same words sent as a triangle draw it,
/// and the second triangle is not drawn.
#[test]
fn quad_cut_after_its_first_triangle() {
    // F4: command and three vertices are the first triangle (an F3's words).
    let f4 = [0x2800_00FF, pos(0, 0), pos(40, 0), pos(0, 30), pos(40, 30)];
    let mut cut = Gpu::new();
    cut.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    cut.gp0_words(&f4[..4]);
    cut.gp1(0x0100_0000);
    let mut triangle = Gpu::new();
    triangle.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    triangle.gp0_words(&[0x2000_00FF, pos(0, 0), pos(40, 0), pos(0, 30)]);
    assert!(cut.vram() == triangle.vram(), "first triangle drawn");
    assert_ne!(px(&cut, 1, 1), 0);
    assert_eq!(px(&cut, 39, 29), 0, "second triangle not drawn");
    // The cut ends the packet: the next word starts a command.
    cut.gp0_words(&[0x0200_001F, pos(0, 100), 0x0001_0010]);
    assert_ne!(px(&cut, 0, 100), 0);
    // One word fewer: nothing is drawn.
    let mut short = Gpu::new();
    short.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    short.gp0_words(&f4[..3]);
    short.gp1(0x0100_0000);
    assert!(short.vram().as_slice().iter().all(|&p| p == 0));
    // GP1(00h) cuts the same way (and then resets the drawing environment).
    let mut reset = Gpu::new();
    reset.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    reset.gp0_words(&f4[..4]);
    reset.gp1(0x0000_0000);
    assert!(reset.vram() == triangle.vram());
}

/// A textured quad cut after its first triangle applies that triangle's texpage attribute
/// (vertex 1's UV word, docs/hardware/gpu.md §2) to the draw mode, as the triangle does.
#[test]
fn quad_cut_applies_the_texpage_of_its_first_triangle() {
    // FT4 with texpage 118h (page 512,256, 15-bit): its first triangle is FT3's 7 words.
    let ft4 = [
        0x2C80_8080,
        pos(0, 0),
        0,
        pos(40, 0),
        0x0118_0010,
        pos(0, 30),
        0x0000_1000,
        pos(40, 30),
        0x0000_1010,
    ];
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    g.gp0_words(&ft4[..7]);
    g.gp1(0x0100_0000);
    // GPUSTAT bits 0-8: page X 512 / 64 = 8, Y 256 (bit 4), 15-bit (bits 7-8 = 2).
    assert_eq!(g.gpustat() & 0x1FF, 8 | 1 << 4 | 2 << 7);
}

/// A GPU still drawing has not reached the quad: its words wait in the FIFO, and GP1(01h)
/// drops them with the triangle undrawn and the draw mode unchanged.
#[test]
fn quad_cut_while_the_gpu_is_busy_draws_nothing() {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    // A 256x256 rectangle keeps the GPU busy.
    g.gp0_words(&[0x6000_00FF, pos(0, 200), 0x0100_0100]);
    let before = g.vram().clone();
    let stat = g.gpustat() & 0x1FF;
    g.gp0_words(&[
        0x2C80_8080,
        pos(300, 0),
        0,
        pos(340, 0),
        0x0118_0010,
        pos(300, 30),
        0x0000_1000,
    ]);
    g.gp1(0x0100_0000);
    assert!(*g.vram() == before);
    assert_eq!(g.gpustat() & 0x1FF, stat);
}

/// Ordering table: packets come out far (high index) first; packets at one index come out
/// most-recent-first; the walk ends at the terminator.
#[test]
fn ordering_table_order() {
    let mut ot = OrderingTable::new(8, 64).unwrap();
    ot.insert(1, &[0x11]).unwrap();
    ot.insert(6, &[0x61, 0x62]).unwrap();
    ot.insert(1, &[0x12]).unwrap();
    ot.insert(0, &[0x01]).unwrap();
    let mut seen = Vec::new();
    let stats = ot.walk(|w| seen.extend_from_slice(w)).unwrap();
    assert_eq!(seen, [0x61, 0x62, 0x12, 0x11, 0x01]);
    assert_eq!(stats.packets, 4);
    assert_eq!(stats.nodes, 8 + 4);
    ot.clear();
    let mut n = 0;
    ot.walk(|_| n += 1).unwrap();
    assert_eq!(n, 0);
    // DMA6 layout: entry 0 holds the end marker, entry i points at entry i-1.
    assert_eq!(ot.ram()[0], 0x00FF_FFFF);
    assert_eq!(ot.ram()[5], 16);
}

#[test]
fn ordering_table_errors() {
    let mut ot = OrderingTable::new(4, 4).unwrap();
    assert_eq!(
        ot.insert(4, &[0]),
        Err(OtError::IndexOutOfRange { index: 4, depth: 4 })
    );
    assert_eq!(ot.insert(0, &[0; 4]), Err(OtError::PrimitiveBufferFull));
    assert_eq!(ot.insert(0, &[0; 256]), Err(OtError::PacketTooLong(256)));
    // A link out of range, and a cycle.
    assert_eq!(
        walk_ram(&[0x0000_0040], 0, |_| {}),
        Err(OtError::BadLink(0x40))
    );
    assert_eq!(
        walk_ram(&[0x0000_0004, 0x0000_0000], 0, |_| {}),
        Err(OtError::Cycle)
    );
    // A count running past the end.
    assert_eq!(
        walk_ram(&[0x05FF_FFFF], 0, |_| {}),
        Err(OtError::BadLink(0))
    );
}

/// Walking into a GPU draws in painter's order: a far red rectangle under a near green one.
#[test]
fn ordering_table_draws_far_first() {
    let mut ot = OrderingTable::new(16, 64).unwrap();
    ot.insert(2, &[0x6000_FF00, 0, 0x0004_0004]).unwrap(); // near, green
    ot.insert(10, &[0x6000_00FF, 0, 0x0008_0008]).unwrap(); // far, red
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
    ot.walk_into(&mut g).unwrap();
    assert_eq!(px(&g, 1, 1), 0x03E0);
    assert_eq!(px(&g, 6, 6), 0x001F);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Any word stream on either port: no panic, VRAM keeps its size.
    #[test]
    fn random_streams_never_panic(words in prop::collection::vec((any::<bool>(), any::<u32>()), 0..400)) {
        let mut g = Gpu::new();
        g.gp0_words(&[0xE300_0000, 0xE407_FFFF]);
        for (gp1, w) in words {
            if gp1 && w >> 24 != 0x01 {
                g.gp1(w);
            } else {
                g.gp0(w);
            }
            let _ = g.gpustat();
        }
        let _ = g.gpuread();
        prop_assert_eq!(g.vram().as_slice().len(), 1024 * 512);
    }

    /// Random primitives built from valid command bytes with arbitrary coordinates.
    #[test]
    fn random_primitives_never_panic(op in 0x20u32..0x80, rest in prop::collection::vec(any::<u32>(), 12), e in any::<u32>()) {
        let mut g = Gpu::new();
        g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE100_0000 | (e & 0x3FFF), 0xE200_0000 | (e >> 12 & 0xFFFFF)]);
        g.gp0(op << 24 | (rest[0] & 0xFFFFFF));
        g.gp0_words(&rest[1..]);
        g.gp0(0x5555_5555);
        prop_assert_eq!(g.vram().as_slice().len(), 1024 * 512);
    }
}

/// Drawing area covering the whole VRAM, offset 0.
const FULL_AREA: [u32; 3] = [0xE300_0000, 0xE407_FFFF, 0xE500_0000];

/// A packet position word for (x, y).
fn pos(x: u32, y: u32) -> u32 {
    y << 16 | x
}

/// Polyline termination (docs/hardware/gpu.md §2): the terminator is tested where the next vertex's first
/// word would be, i.e. the position word of a flat polyline and the colour word of a Gouraud
/// one; 5000_5000h in a Gouraud position slot is a vertex at (0, 0).
#[test]
fn polyline_terminator() {
    let red = 0x001F; // 0xF8 >> 3 in the red channel
    let green = 0x03E0;
    let mut g = Gpu::new();
    g.gp0_words(&FULL_AREA);
    // Flat: (10,10)-(13,10)-(13,12), then the terminator, then a 1x1 green rectangle.
    g.gp0_words(&[
        0x4800_00F8,
        pos(10, 10),
        pos(13, 10),
        pos(13, 12),
        0x5555_5555,
    ]);
    g.gp0_words(&[0x6800_F800, pos(20, 20)]);
    for x in 10..=13 {
        assert_eq!(px(&g, x, 10), red, "({x},10)");
    }
    for y in 10..=12 {
        assert_eq!(px(&g, 13, y), red, "(13,{y})");
    }
    assert_eq!(px(&g, 14, 10), 0);
    assert_eq!(px(&g, 13, 13), 0);
    assert_eq!(
        px(&g, 20, 20),
        green,
        "the word after the terminator is a command"
    );

    // Gouraud: the terminator in the colour slot ends the polyline.
    g.gp0_words(&[
        0x5800_00F8,
        pos(30, 30),
        0x0000_00F8,
        pos(33, 30),
        0x5000_5000,
    ]);
    g.gp0_words(&[0x6800_F800, pos(40, 40)]);
    assert_eq!(px(&g, 30, 30), red);
    assert_eq!(px(&g, 33, 30), red);
    assert_eq!(px(&g, 34, 30), 0);
    assert_eq!(px(&g, 40, 40), green);

    // Gouraud: 5000_5000h as a position is the vertex (0, 0): a 45-degree line from (50,50).
    g.gp0_words(&[
        0x5800_00F8,
        pos(50, 50),
        0x0000_00F8,
        0x5000_5000,
        0x5555_5555,
    ]);
    for i in [0, 25, 50] {
        assert_eq!(px(&g, i, i), red, "({i},{i})");
    }
    assert_eq!(px(&g, 1, 0), 0);
}

/// A stream mixing every packet shape (12-word textured Gouraud quad, polylines of both
/// kinds, a rectangle, fill, copy, CPU-to-VRAM with an odd pixel count, E-commands) gives
/// the same VRAM when split into two calls at every word position, and when fed word by word.
#[test]
fn packets_split_at_every_position() {
    let mut words = FULL_AREA.to_vec();
    words.extend([0x0200_4080, pos(0, 0), pos(64, 64)]); // fill
    words.extend([
        0xA000_0000,
        pos(100, 5),
        pos(3, 1),
        0x7FFF_1234,
        0x0000_4321,
    ]);
    words.extend([
        0x3C10_2030,
        pos(5, 5),
        0x0000_0000,
        0x0040_5060,
        pos(60, 8),
        0x0010_0010,
        0x0070_8090,
        pos(8, 50),
        0x0000_1000,
        0x00A0_B0C0,
        pos(55, 58),
        0x0000_1010,
    ]);
    words.extend([
        0x4A30_4050,
        pos(70, 70),
        pos(90, 75),
        pos(80, 95),
        0x5000_5000,
    ]);
    words.extend([
        0x5820_3040,
        pos(100, 100),
        0x0040_5060,
        pos(120, 90),
        0x5555_5555,
    ]);
    words.extend([
        0xE100_0200,
        0x6480_8080,
        pos(130, 10),
        0x0000_0402,
        pos(20, 12),
    ]);
    words.extend([0x8000_0000, pos(0, 0), pos(200, 200), pos(40, 30)]); // copy
    let mut whole = Gpu::new();
    whole.gp0_words(&words);
    let mut single = Gpu::new();
    for &w in &words {
        single.gp0(w);
    }
    assert!(single.vram() == whole.vram(), "word by word");
    assert_ne!(px(&whole, 210, 210), 0, "the copy reached VRAM");
    for split in 0..=words.len() {
        let (a, b) = words.split_at(split);
        let mut g = Gpu::new();
        g.gp0_words(a);
        g.gp0_words(b);
        assert!(g.vram() == whole.vram(), "split at {split}");
    }
}

/// One random GP0 packet: environment, fills, copies, polygons, lines, polylines,
/// rectangles, a small CPU-to-VRAM transfer, IRQ requests, and stray words.
fn packet() -> impl Strategy<Value = Vec<u32>> {
    let xy = || (0u32..300, 0u32..260).prop_map(|(x, y)| x | y << 16);
    prop_oneof![
        (0xE1u32..=0xE6, any::<u32>()).prop_map(|(op, v)| vec![op << 24 | (v & 0xFF_FFFF)]),
        (any::<u32>(), xy(), xy()).prop_map(|(c, p, s)| vec![0x0200_0000 | c & 0xFF_FFFF, p, s]),
        (0x20u32..0x40, prop::collection::vec(any::<u32>(), 12)).prop_map(|(op, w)| {
            let mut v = vec![op << 24 | (w[0] & 0xFF_FFFF)];
            let n = gpu_packet_len(op << 24) - 1;
            v.extend(w[1..=n].iter().map(|&x| x & 0x00FF_00FF));
            v
        }),
        (0x40u32..0x60, prop::collection::vec(xy(), 6)).prop_map(|(op, p)| {
            let mut v = vec![op << 24 | 0x80_4020];
            if op & 0x08 != 0 {
                v.extend(&p[..4]);
                v.push(0x5555_5555);
            } else {
                v.extend(&p[..gpu_packet_len(op << 24) - 1]);
            }
            v
        }),
        (0x60u32..0x80, prop::collection::vec(xy(), 3)).prop_map(|(op, p)| {
            let mut v = vec![op << 24 | 0x40_8080];
            v.extend(&p[..gpu_packet_len(op << 24) - 1]);
            v
        }),
        (xy(), xy(), xy()).prop_map(|(a, b, s)| vec![0x8000_0000, a, b, s & 0x003F_003F]),
        (xy(), any::<[u32; 4]>())
            .prop_map(|(p, px)| [&[0xA000_0000, p, 0x0002_0004][..], &px[..]].concat()),
        Just(vec![0x1F00_0000]),
        any::<u32>().prop_map(|w| vec![w]),
    ]
}

/// Words in the packet a command word starts, for the generator (docs/hardware/gpu.md §2):
/// polygons 1 + vertices x (1 + textured) + Gouraud colours, lines 3 or 4 (polylines start
/// with 3 or 4), rectangles 2-4.
fn gpu_packet_len(cmd: u32) -> usize {
    let op = cmd >> 24;
    match op {
        0x20..=0x3F => {
            let verts = if op & 0x08 != 0 { 4 } else { 3 };
            let per = 1 + (op >> 2 & 1) as usize;
            let colors = if op & 0x10 != 0 { verts - 1 } else { 0 };
            1 + verts * per + colors
        }
        0x40..=0x5F => {
            if op & 0x10 != 0 {
                4
            } else {
                3
            }
        }
        _ => {
            let size = if op & 0x18 == 0 { 1 } else { 0 };
            2 + (op >> 2 & 1) as usize + size
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// `gp0_words` over blocks of any size has the effect of `gp0_words` word by word: the
    /// same VRAM, GPUSTAT (with the FIFO-full bit), pending input and next event, with the
    /// GPU run between blocks.
    #[test]
    fn blocks_equal_single_words(
        packets in prop::collection::vec(packet(), 1..40),
        splits in prop::collection::vec((1usize..30, 0u32..3000), 1..40),
    ) {
        let words: Vec<u32> = packets.concat();
        let (mut blocks, mut single) = (Gpu::new(), Gpu::new());
        // GP1(04h) = 1: GPUSTAT.25 shows whether the FIFO is full (docs/hardware/gpu.md §8).
        blocks.gp1(0x0400_0001);
        single.gp1(0x0400_0001);
        let mut at = 0;
        let mut i = 0;
        while at < words.len() {
            let (len, cycles) = splits[i % splits.len()];
            i += 1;
            let end = (at + len).min(words.len());
            blocks.gp0_words(&words[at..end]);
            for &w in &words[at..end] {
                single.gp0_words(&[w]);
            }
            prop_assert_eq!(blocks.run(cycles), single.run(cycles));
            prop_assert_eq!(blocks.gpustat(), single.gpustat());
            prop_assert_eq!(blocks.pending_input(), single.pending_input());
            prop_assert_eq!(blocks.cycles_until_next_event(), single.cycles_until_next_event());
            at = end;
        }
        prop_assert!(blocks.vram() == single.vram());
    }
}
