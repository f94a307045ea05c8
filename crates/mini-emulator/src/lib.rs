//! A miniature emulator loop driving `gte` and `gpu` the way a PlayStation core does: the CPU
//! side is faked, everything the crates see is what real ports and DMA channels would give
//! (docs/emulator.md).
//!
//! Each frame: RTPT through MTC2/CTC2/COP2 (with the cycles it costs), GP0 packets linked into
//! an ordering table in byte RAM cleared by DMA6, a DMA2 linked-list walk long enough to fill
//! the GPU's command FIFO (the DMA waits, and its time is run through the GPU once), GP0(1Fh)
//! for IRQ1, then video time up to the vblank start (IRQ0) in one step, the displayed lines
//! taken as the beam scans them. At the end a VRAM-to-CPU copy is read back through GPUREAD
//! and the scanned picture is written to a binary PPM file.
//!
//! Run: `cargo run --release -p mini-emulator [out.ppm]`.

use gpu::gp1::Gp1;
use gpu::{EventKind, Gpu, PixelFormat};
use gte::Gte;
use std::path::{Path, PathBuf};

/// What the run saw.
#[derive(Debug)]
pub struct Summary {
    /// CPU cycles the GTE commands took.
    pub gte_cycles: u32,
    /// CPU cycles the DMA transfers took, FIFO waits included once.
    pub dma_cycles: u32,
    /// Of `dma_cycles`, the linked lists' cycles spent waiting for FIFO room.
    pub dma_wait_cycles: u32,
    /// Header and data words the linked lists read.
    pub list_words: u32,
    /// CPU cycles run through the GPU (DMA stalls and video time).
    pub video_cycles: u64,
    /// Vblank starts (IRQ0).
    pub vblanks: u32,
    /// GPU interrupts (IRQ1) from GP0(1Fh).
    pub gpu_irqs: u32,
    /// Displayed lines scanned out in the last frame.
    pub lines: u32,
    /// Size of the displayed frame.
    pub frame: (u32, u32),
    /// The PPM written.
    pub out: PathBuf,
}

/// Frames run.
pub const FRAMES: u32 = 3;
/// Ordering table: 8 entries at 0x1000 (DMA6 clears from the last entry down).
const OT_START: u32 = 0x1000;
const OT_LEN: u32 = 8;
/// Where the packets of each frame go in RAM.
const PACKETS_AT: u32 = 0x2000;

fn read_word(ram: &[u8], addr: u32) -> u32 {
    let a = addr as usize;
    u32::from_le_bytes([ram[a], ram[a + 1], ram[a + 2], ram[a + 3]])
}

fn write_word(ram: &mut [u8], addr: u32, value: u32) {
    let a = addr as usize;
    ram[a..a + 4].copy_from_slice(&value.to_le_bytes());
}

/// Link `packet` into ordering-table entry `entry` as a game's AddPrim does; returns the
/// address after it.
fn add_prim(ram: &mut [u8], entry: u32, at: u32, packet: &[u32]) -> u32 {
    let slot = OT_START + entry * 4;
    let next = read_word(ram, slot) & 0x00FF_FFFF;
    write_word(ram, at, (packet.len() as u32) << 24 | next);
    for (i, w) in packet.iter().enumerate() {
        write_word(ram, at + 4 + 4 * i as u32, *w);
    }
    write_word(ram, slot, at & 0x00FF_FFFF);
    at + 4 + 4 * packet.len() as u32
}

/// The GTE set-up a game does once: identity rotation, the object 1000 units ahead, screen
/// centre (160, 120), projection distance 200.
fn setup_gte(gte: &mut Gte) {
    gte.write_control(0, 0x1000); // RT11 = 1.0, RT12 = 0
    gte.write_control(1, 0);
    gte.write_control(2, 0x1000); // RT22 = 1.0
    gte.write_control(3, 0);
    gte.write_control(4, 0x1000); // RT33 = 1.0
    gte.write_control(5, 0); // TRX
    gte.write_control(6, 0); // TRY
    gte.write_control(7, 1000); // TRZ
    gte.write_control(24, 160 << 16); // OFX, 16.16
    gte.write_control(25, 120 << 16); // OFY
    gte.write_control(26, 200); // H
}

/// Screen XY packed as GP0 vertex words hold them.
fn xy(x: u32, y: u32) -> u32 {
    y << 16 | x
}

/// The loop. Errors say what the emulator observed that a console would not.
pub fn run(out: &Path) -> Result<Summary, String> {
    let mut gte = Gte::new();
    let mut gpu = Gpu::new();
    let mut ram = vec![0u8; 2 << 20];
    let mut s = Summary {
        gte_cycles: 0,
        dma_cycles: 0,
        dma_wait_cycles: 0,
        list_words: 0,
        video_cycles: 0,
        vblanks: 0,
        gpu_irqs: 0,
        lines: 0,
        frame: (0, 0),
        out: out.to_path_buf(),
    };

    // BIOS-like start: reset, 320x240 NTSC, display on; drawing area and offset.
    for w in [0x0000_0000, 0x0800_0001, 0x0500_0000, 0x0300_0000] {
        gpu.gp1(w);
    }
    gpu.gp0_words(&[0xE100_0000, 0xE300_0000, 0xE403_C13F, 0xE500_0000]);
    setup_gte(&mut gte);

    // The picture as the beam scans it: one row of RGB bytes per displayed line.
    let (width, height) = (320usize, 240usize);
    let mut picture = vec![0u8; width * height * 3];

    for frame in 0..FRAMES {
        // Background fill, a CPU write to GP0.
        gpu.gp0_words(&[0x0200_2010, 0, 240 << 16 | 320]);

        // RTPT: MTC2 the three vertices, COP2 0x0008_0030 (sf = 1), MFC2 the screen XYs.
        let verts = [(-100i16, -80i16), (100, -80), (frame as i16 * 4, 100)];
        for (i, (x, y)) in verts.iter().enumerate() {
            gte.write_data(2 * i as u32, (*x as u16 as u32) | (*y as u16 as u32) << 16);
            gte.write_data(2 * i as u32 + 1, 0);
        }
        s.gte_cycles += gte.execute(0x0008_0030).ok_or("RTPT is a valid command")?;
        let sxy: Vec<u32> = (12..15).map(|r| gte.read_data(r)).collect();

        // DMA6 clears the ordering table. The red triangle is linked at entry 3; behind it,
        // at entry 6 (drawn first), six large blue rectangles a little apart, each keeping the
        // GPU busy long enough that the words after it wait in the 16-word FIFO.
        s.dma_cycles +=
            gpu::dma_clear_ordering_table(&mut ram, OT_START + (OT_LEN - 1) * 4, OT_LEN)
                .map_err(|e| format!("OTC: {e:?}"))?;
        let mut at = add_prim(
            &mut ram,
            3,
            PACKETS_AT,
            &[0x2000_00FF, sxy[0], sxy[1], sxy[2]],
        );
        for i in 0..6 {
            at = add_prim(
                &mut ram,
                6,
                at,
                &[0x60FF_0000, xy(2 * i, 2 * i), xy(300, 200)],
            );
        }

        // DMA2 linked list from the far end of the table. The CPU is stalled while it runs,
        // FIFO waits included: that time passes on the GPU once.
        let report = gpu.dma_linked_list(&ram, OT_START + (OT_LEN - 1) * 4);
        if report.nodes != OT_LEN + 7 {
            return Err(format!(
                "walked {} nodes, expected {}",
                report.nodes,
                OT_LEN + 7
            ));
        }
        s.dma_cycles += report.cycles;
        s.dma_wait_cycles += report.wait_cycles;
        s.list_words += report.nodes + report.words;
        let ev = gpu.run(report.cycles);
        s.video_cycles += u64::from(report.cycles);
        s.vblanks += ev.vblank_start as u32;

        // GP0(1Fh): request IRQ1 once drawing is queued.
        gpu.gp0(0x1F00_0000);

        // Video time up to the vblank start in one step (IRQ0), the IRQ1 reported on the way;
        // every displayed line goes into the picture as the beam leaves it.
        let step = gpu.cycles_until(EventKind::VblankStart);
        if step == u32::MAX {
            return Err("no vblank comes with the GP1(07h) reset range".into());
        }
        s.lines = 0;
        let ev = gpu.run_lines(step, |line| {
            let at = line.row as usize * width * 3;
            if let Some(row) = picture.get_mut(at..at + width * 3)
                && line.decode(row, PixelFormat::Rgb888).is_ok()
            {
                s.lines += 1;
            }
        });
        s.video_cycles += u64::from(step);
        if ev.gpu_irq {
            s.gpu_irqs += 1;
            gpu.gp1(Gp1::AcknowledgeIrq.word());
        }
        if !ev.vblank_start {
            return Err(format!("frame {frame}: no vblank after {step} cycles"));
        }
        s.vblanks += 1;
    }

    // Poll GPUSTAT until the GPU takes commands (bit 26) and DMA blocks (bit 28).
    let mut polls = 0;
    while gpu.gpustat() & (1 << 26 | 1 << 28) != (1 << 26 | 1 << 28) {
        gpu.run(64);
        polls += 1;
        if polls > 100_000 {
            return Err("GPUSTAT never showed the GPU ready".into());
        }
    }

    // VRAM-to-CPU copy of 2x1 pixels inside the triangle, read through GPUREAD.
    gpu.gp0_words(&[0xC000_0000, 120 << 16 | 159, 1 << 16 | 2]);
    if gpu.gpustat() & (1 << 27) == 0 {
        return Err("GPUSTAT bit 27 (VRAM-to-CPU ready) is clear after GP0(C0h)".into());
    }
    let word = gpu.gpuread();
    if word != 0x001F_001F {
        return Err(format!(
            "GPUREAD gave {word:08X}, expected 001F001F (two red pixels)"
        ));
    }

    // The scanned picture is the frame VRAM holds: nothing changed while the beam ran.
    let size = gpu.frame_size();
    s.frame = (size.width, size.height);
    let mut whole = vec![0u8; size.bytes(PixelFormat::Rgb888)];
    gpu.display_frame(&mut whole, PixelFormat::Rgb888)
        .map_err(|e| format!("display_frame: {e}"))?;
    if (size.width as usize, size.height as usize) != (width, height) || whole != picture {
        return Err("the scanned lines differ from the displayed frame".into());
    }
    let red = picture.chunks(3).filter(|p| p == &[255, 0, 0]).count();
    if red < 100 {
        return Err(format!(
            "the displayed frame has {red} red pixels; the triangle is missing"
        ));
    }
    write_ppm(out, size.width, size.height, &picture)?;
    Ok(s)
}

/// A binary PPM (P6): header, then R, G, B bytes row by row.
fn write_ppm(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<(), String> {
    let mut bytes = format!("P6\n{width} {height}\n255\n").into_bytes();
    bytes.extend_from_slice(rgb);
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}
