//! DMA channel 2 (block and linked-list mode) and channel 6 (OTC), drawing time, the FIFO
//! and the GPU interrupt. Console expectations come from ps1-tests `dma/otc-test` and
//! `dma/chain-looping` and `dma/chopping` (main.cpp and psx.log; MIT, Copyright (c) 2020
//! Jakub Czekański, fixtures/gpu/LICENSE-ps1-tests) and psx-spx "DMA Channels"; cycle
//! figures are worked out here from the cost table in docs/emulator.md with floating-point
//! clock ratios.

use gpu::{DmaError, EventKind, Gpu, LINKED_LIST_WORD_BUDGET, ListEnd, dma_clear_ordering_table};
use proptest::prelude::*;

#[path = "support/cost.rs"]
mod cost;
#[path = "support/quiet.rs"]
mod quiet;
use quiet::quiet;

const MIB2: usize = 2 * 1024 * 1024;

fn read(ram: &[u8], addr: u32) -> u32 {
    let a = (addr & 0x1F_FFFF) as usize;
    u32::from_le_bytes(ram[a..a + 4].try_into().unwrap())
}

fn write(ram: &mut [u8], addr: u32, value: u32) {
    let a = (addr & 0x1F_FFFF) as usize;
    ram[a..a + 4].copy_from_slice(&value.to_le_bytes());
}

// ---- DMA6 OTC: ps1-tests dma/otc-test ----

/// `testOtcStandard` (and `testOtcForward`, `testOtcFromRam`, `testOtcSyncMode*`, which
/// show the channel ignores those CHCR bits: same result): four words at 80100000h.
#[test]
fn otc_standard() {
    let mut ram = vec![0u8; MIB2];
    for (i, v) in [0x1111_1111u32, 0x2222_2222, 0x3333_3333, 0x4444_4444]
        .iter()
        .enumerate()
    {
        write(&mut ram, 0x10_0000 + 4 * i as u32, *v);
    }
    let cycles = dma_clear_ordering_table(&mut ram, 0x8010_000C, 4).unwrap();
    assert_eq!(read(&ram, 0x10_000C), 0x8010_0008 & 0xFF_FFFF);
    assert_eq!(read(&ram, 0x10_0008), 0x8010_0004 & 0xFF_FFFF);
    assert_eq!(read(&ram, 0x10_0004), 0x8010_0000 & 0xFF_FFFF);
    assert_eq!(read(&ram, 0x10_0000), 0xFF_FFFF);
    // Neighbours untouched.
    assert_eq!(read(&ram, 0x10_0010), 0);
    assert_eq!(read(&ram, 0x0F_FFFC), 0);
    // One cycle per word (psx-spx "DMA Transfer Rates").
    assert_eq!(cycles, 4);
}

/// `testOtcBigTransfer`: a count of 0 clears 10000h words (psx-spx "D#_BCR": 0 = 10000h).
#[test]
fn otc_count_zero_is_65536_words() {
    let mut ram = vec![0u8; MIB2];
    let last = 0x4_0000 + 4 * 0xFFFF;
    let cycles = dma_clear_ordering_table(&mut ram, last, 0).unwrap();
    assert_eq!(read(&ram, last), last - 4);
    assert_eq!(read(&ram, last - 4), last - 8);
    assert_eq!(read(&ram, 0x4_0004), 0x4_0000);
    assert_eq!(read(&ram, 0x4_0000), 0xFF_FFFF);
    assert_eq!(read(&ram, 0x3_FFFC), 0);
    // 110h cycles per 100h words.
    assert_eq!(cycles, 0x1_0000 / 0x100 * 0x110);
}

/// The table is built in mirrored RAM: 80300000h is 100000h in 2 MiB; links keep the
/// 24-bit address.
#[test]
fn otc_links_keep_the_24_bit_address() {
    let mut ram = vec![0u8; MIB2];
    dma_clear_ordering_table(&mut ram, 0x8030_0004, 2).unwrap();
    assert_eq!(read(&ram, 0x10_0004), 0x30_0000);
    assert_eq!(read(&ram, 0x10_0000), 0xFF_FFFF);
}

/// Counting down past address 0 wraps to FFFFFCh, past RAM: those words are not written
/// (psx-spx "D#_MADR").
#[test]
fn otc_wrapping_below_zero_writes_nothing_there() {
    let mut ram = vec![0u8; MIB2];
    write(&mut ram, 0x1F_FFFC, 0xAAAA_AAAA);
    dma_clear_ordering_table(&mut ram, 4, 3).unwrap();
    assert_eq!(read(&ram, 4), 0);
    assert_eq!(read(&ram, 0), 0xFF_FFFC);
    assert_eq!(read(&ram, 0x1F_FFFC), 0xAAAA_AAAA);
}

#[test]
fn otc_errors_write_nothing() {
    let mut ram = vec![0x55u8; 64];
    assert_eq!(
        dma_clear_ordering_table(&mut ram, 0x40, 2),
        Err(DmaError::AddressOutOfRange(0x40))
    );
    assert!(ram.iter().all(|&b| b == 0x55));
    assert_eq!(
        dma_clear_ordering_table(&mut ram, 0x3C, 0x1_0001),
        Err(DmaError::CountTooLarge(0x1_0001))
    );
}

// ---- DMA2 linked list: ps1-tests dma/chain-looping ----

/// `TestEmptyChain`: two empty nodes ending in 00FFFFFFh finish (finished = true).
#[test]
fn empty_complete_chain_finishes() {
    let mut ram = vec![0u8; MIB2];
    write(&mut ram, 0x1000, 0x1004);
    write(&mut ram, 0x1004, 0x00FF_FFFF);
    let mut g = Gpu::new();
    let r = g.dma_linked_list(&ram, 0x8000_1000);
    assert_eq!(r.end, ListEnd::EndMarker);
    assert_eq!((r.nodes, r.words, r.cycles), (2, 0, 2));
}

/// `TestSingleSelfReferencingChain` and `TestDoubleSelfReferencingChain`: the console never
/// finishes (finished = false, no IRQ) and the CPU keeps running. Here each call stops after
/// the word budget and says where the list goes on.
#[test]
fn self_referencing_chains_pause_at_the_budget() {
    let mut ram = vec![0u8; MIB2];
    write(&mut ram, 0x2000, 0x2000);
    write(&mut ram, 0x2004, 0x00FF_FFFF);
    let mut g = Gpu::new();
    let r = g.dma_linked_list(&ram, 0x2000);
    assert_eq!(r.end, ListEnd::Paused { next: 0x2000 });
    assert_eq!(r.nodes, LINKED_LIST_WORD_BUDGET);
    assert_eq!(r.cycles, LINKED_LIST_WORD_BUDGET * 0x110 / 0x100);

    write(&mut ram, 0x3000, 0x3004);
    write(&mut ram, 0x3004, 0x3000);
    write(&mut ram, 0x3008, 0x00FF_FFFF);
    let r = g.dma_linked_list(&ram, 0x3000);
    assert_eq!(r.end, ListEnd::Paused { next: 0x3000 });
    assert_eq!(r.nodes, LINKED_LIST_WORD_BUDGET);
}

/// Link bit 23 ends the list (psx-spx "Linked List DMA"); links are masked to 2 MiB.
#[test]
fn links_mirror_ram_and_bit_23_ends() {
    let mut ram = vec![0u8; MIB2];
    // 0x100 -> 0x500100 (mirror of 0x100100) -> end (link 800000h).
    write(&mut ram, 0x100, 0x50_0100);
    write(&mut ram, 0x10_0100, 1 << 24 | 0x80_0000);
    write(&mut ram, 0x10_0104, 0xE600_0001);
    let mut g = Gpu::new();
    let r = g.dma_linked_list(&ram, 0x100);
    assert_eq!(r.end, ListEnd::EndMarker);
    assert_eq!((r.nodes, r.words), (2, 1));
    // The E6h word arrived: set-mask is on.
    assert_eq!(g.gpustat() >> 11 & 1, 1);
}

/// RAM shorter than 2 MiB: a header or data word beyond it ends the walk before the node's
/// words are sent.
#[test]
fn short_ram_reports_bad_addresses() {
    let mut ram = vec![0u8; 0x100];
    write(&mut ram, 0x00, 0x80);
    write(&mut ram, 0x80, 2 << 24 | 0xF8);
    write(&mut ram, 0xF8, 3 << 24 | 0xFF_FFFF);
    let mut g = Gpu::new();
    let r = g.dma_linked_list(&ram, 0);
    assert_eq!(r.end, ListEnd::BadAddress(0xF8));
    assert_eq!((r.nodes, r.words), (2, 2));
    let r = g.dma_linked_list(&ram, 0x1000);
    assert_eq!(r.end, ListEnd::BadAddress(0x1000));
    assert_eq!(r.nodes, 0);
}

proptest! {
    /// Any RAM content and start: the walk ends, within the budget, without panicking.
    #[test]
    fn random_lists_end(words in prop::collection::vec(any::<u32>(), 1..64), start in any::<u32>()) {
        let ram: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let mut g = Gpu::new();
        let r = g.dma_linked_list(&ram, start);
        prop_assert!(r.nodes + r.words <= LINKED_LIST_WORD_BUDGET + 255);
        let _ = g.gpustat();
    }
}

// ---- Drawing time, FIFO waits, IRQ ----

/// A flat opaque triangle costs its set-up, its rows and its drawn pixels; the pixels are
/// counted here from VRAM.
#[test]
fn flat_triangle_time_follows_drawn_pixels() {
    let mut g = quiet();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    g.gp0_words(&[0x2000_00FF, 0x0000_0000, 0x0000_0040, 0x0030_0000]);
    let drawn = g.vram().as_slice().iter().filter(|&&p| p != 0).count();
    assert!(drawn > 1000);
    // Rows 0 to 47: from the top vertex down to the bottom one.
    let time = cost::TRIANGLE_SETUP + 48.0 * cost::ROW + drawn as f64 * cost::PIXEL;
    assert_eq!(
        g.cycles_until(EventKind::DrawingDone),
        cost::cycles_to_idle(time)
    );
}

/// Busy-to-idle is reported exactly when the predicted cycles have run, once.
#[test]
fn drawing_done_arrives_at_the_predicted_cycle() {
    let mut g = quiet();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    g.gp0_words(&[0x6000_00FF, 0, 0x0040_0040]);
    let n = g.cycles_until(EventKind::DrawingDone);
    // A 64x64 rectangle: set-up, 64 rows, 4096 pixels.
    let time = cost::RECTANGLE_SETUP + 64.0 * cost::ROW + 4096.0 * cost::PIXEL;
    assert_eq!(n, cost::cycles_to_idle(time));
    assert!(!g.run(n - 1).drawing_done);
    assert_eq!(g.cycles_until(EventKind::DrawingDone), 1);
    assert!(g.run(1).drawing_done);
    assert!(!g.run(1000).drawing_done);
    assert_eq!(g.cycles_until(EventKind::DrawingDone), u32::MAX);
}

/// A textured rectangle costs what a flat one of the same pixels costs plus its texture
/// cache misses, and nothing per texel (docs/emulator.md, "Drawing time": Mednafen's sprite
/// path). A 64x64 raw 15-bit sprite from the page at x = 512: 15-bit cache blocks are 32x32
/// texels with an entry of 4 texels (docs/hardware/gpu.md §10), so a 64-texel row reads
/// 8 entries of one block and then the same 8 entry numbers of the next block, and every
/// one of its 16 reads of a new entry misses: 64 x 16 = 1,024 misses.
#[test]
fn textured_rectangle_time_is_the_flat_time_plus_misses() {
    let mut g = quiet();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    // GP0(E1h): page x = 8 * 64 = 512, 15-bit texels.
    g.gp0_words(&[0xE100_0000 | 2 << 7 | 8]);
    g.gp0_words(&[0x6500_0000, 0, 0, 0x0040_0040]);
    let n = g.cycles_until(EventKind::DrawingDone);
    let misses = 64.0 * 16.0;
    let time = cost::RECTANGLE_SETUP
        + 64.0 * cost::ROW
        + 4096.0 * cost::PIXEL
        + misses * cost::TEXTURE_MISS;
    assert_eq!(n, cost::cycles_to_idle(time));
    assert_eq!(g.texture_cache_misses(), 1024);
}

/// A PAL console converts the same costs at its own clock ratio (53,203,425 / 33,868,800,
/// docs/hardware/timing.md §1): a draw takes the same CPU time on both consoles, in fewer
/// GPU cycles on the slower PAL clock.
#[test]
fn pal_console_draw_time_uses_the_pal_clock() {
    let time = cost::RECTANGLE_SETUP + 64.0 * cost::ROW + 4096.0 * cost::PIXEL;
    let mut pal = Gpu::with_standard(gpu::VideoStandard::Pal);
    pal.gp1(0x0600_0000);
    pal.gp1(0x07FF_FFFF);
    pal.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    pal.gp0_words(&[0x6000_00FF, 0, 0x0040_0040]);
    let (num, den) = (53_203_425.0, 33_868_800.0);
    let gpu = (time * num / den + 1e-9).floor();
    let expected = (gpu * den / num - 1e-9).ceil() as u32;
    assert_eq!(pal.cycles_until(EventKind::DrawingDone), expected);
    assert!(expected.abs_diff(cost::cycles_to_idle(time)) <= 1);
}

/// GP0(1Fh) sets GPUSTAT.24, reported once by the next run; GP1(02h) acknowledges.
#[test]
fn gp0_1f_raises_the_irq_once() {
    let mut g = Gpu::new();
    g.gp0(0x1F00_0000);
    assert!(g.irq_pending());
    assert_eq!(g.gpustat() >> 24 & 1, 1);
    assert_eq!(g.cycles_until_next_event(), 0);
    assert!(g.run(1).gpu_irq);
    assert!(!g.run(1).gpu_irq);
    assert!(g.irq_pending());
    // Raising it again while it is pending is no new interrupt.
    g.gp0(0x1F00_0000);
    assert!(!g.run(1).gpu_irq);
    g.gp1(0x0200_0000);
    assert!(!g.irq_pending());
    assert_eq!(g.gpustat() >> 24 & 1, 0);
    g.gp0(0x1F00_0000);
    assert!(g.run(0).gpu_irq);
}

/// GPU cycles the drawing side has run when word `n` of a DMA arrives: the words move at
/// one CPU cycle each plus one per 16 (docs/hardware/dma.md §10), and the GPU drains the
/// FIFO meanwhile (floor of 11/7 of the CPU cycles).
fn gpu_at_word(n: u32) -> u64 {
    ((n + n / 16) as u64 * 11) / 7
}

/// Seven small fills (21 words) by DMA: the first starts with its third word and the next
/// five wait in the FIFO (15 words); the sixth's second word finds the FIFO full and waits
/// for the first fill to end and the second to leave the FIFO; the last word follows.
#[test]
fn block_dma_waits_while_the_fifo_is_full() {
    let fill = [0x0200_0000u32, 0, 0x0001_0010];
    let words: Vec<u32> = fill.iter().copied().cycle().take(21).collect();
    let mut g = Gpu::new();
    let cycles = g.dma_block_write(&words);
    // A 16x1 fill: its set-up, one row, one 16-pixel group.
    let fill_gpu = cost::gpu_cycles(cost::fill(16, 1));
    // Word 20 waits until the first fill ends, word 21 takes one more cycle.
    assert_eq!(cycles, cost::cpu_cycles(gpu_at_word(3) + fill_gpu) + 1);
    // GPUSTAT: the FIFO holds 15 words again (fills 3 to 7), complete commands waiting.
    assert_eq!(g.gpustat() >> 28 & 1, 0);
    g.gp1(0x0400_0001);
    assert_eq!(g.gpustat() >> 25 & 1, 1, "FIFO not full");
}

/// The time a DMA waited is not counted twice: seen from the clock, the seven fills end
/// seven fill-times after the first one's words arrived, and running the returned cycles
/// leaves the rest.
#[test]
fn dma_wait_is_not_counted_twice() {
    let fill = [0x0200_0000u32, 0, 0x0001_0010];
    let words: Vec<u32> = fill.iter().copied().cycle().take(21).collect();
    let mut g = quiet();
    let cycles = g.dma_block_write(&words);
    let done = cost::cpu_cycles(gpu_at_word(3) + cost::gpu_cycles(7.0 * cost::fill(16, 1)));
    assert_eq!(g.cycles_until(EventKind::DrawingDone), done);
    let mut done_at = None;
    for t in 1..=done + 1 {
        if g.run(1).drawing_done {
            done_at = Some(t);
            break;
        }
    }
    assert_eq!(done_at, Some(done));
    // The DMA itself ended well before the drawing.
    assert!(cycles < done);
}

/// The DMA's own time overlaps the drawing: a 64x64 rectangle and six 16x1 fills by one
/// DMA. The rectangle starts with its third word, while the DMA goes on; the FIFO holds
/// words 4-19, so word 20 waits until the rectangle ends, and word 21 follows. Without the
/// overlap, word 20 would wait for the whole rectangle after the DMA's first 20 cycles.
#[test]
fn block_dma_overlaps_the_drawing() {
    let mut g = quiet();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    let mut words = vec![0x6000_00FF, 0, 0x0040_0040];
    let fill = [0x0200_0000u32, 0, 0x0001_0010];
    words.extend(fill.iter().copied().cycle().take(3 * 6));
    let rect = cost::gpu_cycles(cost::RECTANGLE_SETUP + 64.0 * cost::ROW + 4096.0 * cost::PIXEL);
    let cycles = g.dma_block_write(&words);
    assert_eq!(cycles, cost::cpu_cycles(gpu_at_word(3) + rect) + 1);
    // Everything ends after the rectangle and the six fills.
    let fills = cost::gpu_cycles(6.0 * cost::fill(16, 1));
    assert_eq!(
        g.cycles_until(EventKind::DrawingDone),
        cost::cpu_cycles(gpu_at_word(3) + rect + fills)
    );
}

/// A CPU store into a full FIFO waits for room: `gp0` returns the stall, the drawing side has
/// run through it, and running the stall keeps the clock and the drawing in step.
#[test]
fn cpu_store_into_a_full_fifo_stalls() {
    let mut g = quiet();
    let fill = [0x0200_0000u32, 0, 0x0001_0010];
    // The first fill starts at once; five more fill the FIFO to 15 words, the sixth's first
    // word to 16.
    for w in fill.iter().cycle().take(19) {
        assert_eq!(g.gp0(*w), 0);
    }
    let fill_gpu = cost::gpu_cycles(cost::fill(16, 1));
    // The next word waits for the first fill to end (and the second to leave the FIFO).
    let stall = g.gp0(0);
    assert_eq!(stall, cost::cpu_cycles(fill_gpu));
    // A NOP takes no FIFO space and never waits (psx-spx "GPU Other Commands").
    let mut nop = quiet();
    for w in fill.iter().cycle().take(18) {
        nop.gp0(*w);
    }
    assert_eq!(nop.gp0(0x0000_0000), 0);
    // The stall's time, run through `run`, is not counted twice: the six complete fills
    // end where they would have without it.
    g.run(stall);
    let left = cost::cpu_cycles(cost::gpu_cycles(6.0 * cost::fill(16, 1))) - stall;
    assert!(g.cycles_until(EventKind::DrawingDone).abs_diff(left) <= 1);
}

/// GPUREAD by DMA: the GPU fetches the rectangle from VRAM at its own rate, and the DMA,
/// faster, waits for the words.
#[test]
fn vram_to_cpu_dma_waits_for_the_fetch() {
    let mut g = quiet();
    // 64x64 = 2048 words.
    g.gp0_words(&[0xC000_0000, 0, 0x0040_0040]);
    let mut out = vec![0u32; 2048];
    let cycles = g.dma_block_read(&mut out);
    let fetch = cost::gpu_cycles(2048.0 * cost::READ_WORD);
    // The last word is ready when the fetch ends, and the DMA takes it one cycle later at
    // most.
    let end = cost::cpu_cycles(fetch);
    assert!(cycles >= end && cycles <= end + 1, "{cycles} vs {end}");
    // A CPU reading slower than the fetch never waits.
    let mut slow = quiet();
    slow.gp0_words(&[0xC000_0000, 0, 0x0001_0010]);
    let mut waits = 0;
    for _ in 0..8 {
        slow.run(10);
        waits += slow.gpuread_timed().1;
    }
    assert_eq!(waits, 0);
}

/// GP1(01h) drops the FIFO's waiting words; GP1(00h) also ends the drawing in progress.
#[test]
fn command_buffer_reset_empties_the_fifo() {
    let mut g = Gpu::new();
    g.gp1(0x0400_0002);
    g.gp0_words(&[0x6000_00FF, 0, 0x0100_0100, 0x6000_00FF, 0, 0x0100_0100]);
    assert_eq!(g.gpustat() >> 28 & 1, 0);
    g.gp1(0x0100_0000);
    assert_eq!(g.gpustat() >> 28 & 1, 1);
    assert_eq!(g.gpustat() >> 26 & 1, 0, "still drawing the first");
    g.gp1(0x0000_0000);
    assert_eq!(g.gpustat() >> 26 & 1, 1);
    assert!(g.run(0).drawing_done);
}

proptest! {
    /// Any number of fills of any size by DMA: running to each predicted event ends the
    /// drawing, reported exactly once, after the first fill's words and the sum of the
    /// fills' times; the GPU is then ready for commands and DMA blocks again.
    #[test]
    fn fills_by_dma_end_when_predicted(sizes in prop::collection::vec((1u32..64, 1u32..64), 1..40)) {
        let mut words = Vec::new();
        let mut total = 0.0;
        for &(w, h) in &sizes {
            words.extend_from_slice(&[0x0200_0000, 0, h << 16 | w]);
            total += cost::fill((w + 15) & !15, h);
        }
        let mut g = quiet();
        g.dma_block_write(&words);
        prop_assert_eq!(
            g.cycles_until(EventKind::DrawingDone),
            cost::cpu_cycles(gpu_at_word(3) + cost::gpu_cycles(total))
        );
        let mut done = 0;
        for _ in 0..4 {
            let n = g.cycles_until(EventKind::DrawingDone);
            if n == u32::MAX {
                break;
            }
            if g.run(n).drawing_done {
                done += 1;
            }
        }
        prop_assert_eq!(done, 1);
        prop_assert_eq!(g.gpustat() >> 26 & 1, 1);
        prop_assert_eq!(g.gpustat() >> 28 & 1, 1);
    }
}

// ---- DMA2 slice and burst mode to GP0: ps1-tests dma/chopping ----

/// `dma/chopping`: a 64x64 CPU-to-VRAM transfer (8192 bytes) by DMA2 in sync mode 1 with
/// block sizes 1 to 16, 32, 64 and 128, and in sync mode 0, timed from the CHCR write to
/// the end of `waitForChannel` (psx.log, "took N CPU cycles"). The controller's time per
/// block, `gpu::bus::DMA_BLOCK_CYCLES`, comes from the block size 1 row; the other rows
/// check it together with the GPU's CPU-to-VRAM rate (two pixels at the calibrated
/// per-pixel cost, docs/emulator.md, "Drawing time").
#[test]
fn chopping_slice_mode_times() {
    let console: [(Option<u32>, u64); 20] = [
        (Some(1), 22819),
        (Some(2), 12508),
        (Some(3), 9116),
        (Some(4), 7309),
        (Some(5), 6297),
        (Some(6), 5650),
        (Some(7), 5131),
        (Some(8), 4790),
        (Some(9), 4509),
        (Some(10), 4346),
        (Some(11), 4099),
        (Some(12), 4005),
        (Some(13), 3895),
        (Some(14), 3758),
        (Some(15), 3640),
        (Some(16), 3607),
        (Some(32), 2998),
        (Some(64), 2662),
        (Some(128), 2471),
        (None, 2196),
    ];
    for (block, took) in console {
        // `beginCpuToVramTransfer`: GP1(01h), DrawSync, the CPU2VRAM packet by DrawPrim,
        // GP1(04h) = 2; then the BCR (block size, 8192 / size / 4 blocks) and the timed
        // CHCR write and `waitForChannel`.
        let words = match block {
            Some(n) => 2048 / n * n,
            None => 2048,
        };
        let mode = block.map_or("burst".to_string(), |n| n.to_string());
        let text = format!(
            "gp1 01000000\ngp1 04000000\ngp0 a0000000 0 00400040\ngp1 04000002\n\
             dma-block {mode}\ntimer\ncpu 4\ndma 0*{words}\ncpu 8\nreport took\n"
        );
        let stream = gpu::bus::parse(&text).unwrap();
        let mut g = Gpu::new();
        let run = gpu::bus::run(&mut g, &stream).unwrap();
        let model = run.reports[0].cycles;
        let ratio = model as f64 / took as f64;
        println!("block {mode}: model {model}, console {took}, {ratio:.3}x");
        assert!(
            (0.9..=1.1).contains(&ratio),
            "block {mode}: model {model}, console {took}"
        );
    }
}
