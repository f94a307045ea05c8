//! DMA channel 2 (block and linked-list mode) and channel 6 (OTC), drawing time, the FIFO
//! and the GPU interrupt. Console expectations come from ps1-tests `dma/otc-test` and
//! `dma/chain-looping` (main.cpp and psx.log; MIT, Copyright (c) 2020 Jakub Czekański,
//! fixtures/gpu/LICENSE-ps1-tests) and psx-spx "DMA Channels"; cycle figures are worked out
//! here from the cost table in docs/emulator.md with floating-point clock ratios.

use gpu::{DmaError, Gpu, LINKED_LIST_WORD_BUDGET, ListEnd, dma_clear_ordering_table};
use proptest::prelude::*;

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

/// Draw units (half CPU cycles) to GPU cycles, rounded up: the NTSC console's GPU clock is
/// 11/7 of the CPU clock (docs/hardware/timing.md §1), so a unit is 11/14 GPU cycle.
fn units_to_gpu(units: f64) -> u32 {
    (units * 11.0 / 14.0 - 1e-9).ceil() as u32
}

/// GPU cycles to CPU cycles, rounded up (7/11).
fn gpu_to_cpu(gpu: u32) -> u32 {
    (gpu as f64 * 7.0 / 11.0 - 1e-9).ceil() as u32
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

/// A flat opaque triangle costs its set-up (82 units) plus one unit per drawn pixel; the
/// pixels are counted here from VRAM.
#[test]
fn flat_triangle_time_follows_drawn_pixels() {
    let mut g = quiet();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    g.gp0_words(&[0x2000_00FF, 0x0000_0000, 0x0000_0040, 0x0030_0000]);
    let drawn = g.vram().as_slice().iter().filter(|&&p| p != 0).count();
    assert!(drawn > 1000);
    let gpu_cycles = units_to_gpu(82.0 + drawn as f64);
    assert_eq!(g.cycles_until_next_event(), gpu_to_cpu(gpu_cycles));
}

/// Busy-to-idle is reported exactly when the predicted cycles have run, once.
#[test]
fn drawing_done_arrives_at_the_predicted_cycle() {
    let mut g = quiet();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 511 << 10 | 1023]);
    g.gp0_words(&[0x6000_00FF, 0, 0x0040_0040]);
    let n = g.cycles_until_next_event();
    // A 64x64 rectangle: 16 set-up units + 4096 pixels.
    assert_eq!(n, gpu_to_cpu(units_to_gpu(16.0 + 4096.0)));
    assert!(!g.run(n - 1).drawing_done);
    assert_eq!(g.cycles_until_next_event(), 1);
    assert!(g.run(1).drawing_done);
    assert!(!g.run(1000).drawing_done);
    assert_eq!(g.cycles_until_next_event(), u32::MAX);
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

/// Seven small fills (21 words) by DMA: the first executes, five wait in the FIFO (15
/// words), the seventh's first word fills it; its second word waits for the first fill to
/// end and the second to leave the FIFO.
#[test]
fn block_dma_waits_while_the_fifo_is_full() {
    let fill = [0x0200_0000u32, 0, 0x0001_0010];
    let words: Vec<u32> = fill.iter().copied().cycle().take(21).collect();
    let mut g = Gpu::new();
    let cycles = g.dma_block_write(&words);
    // A 16x1 fill: 46 + 1 * (16 / 8 + 9) units.
    let fill_gpu = units_to_gpu(46.0 + 11.0);
    assert_eq!(cycles, 21 + 21 / 16 + gpu_to_cpu(fill_gpu));
    // GPUSTAT: the FIFO holds 15 words again (fills 3 to 7), complete commands waiting.
    assert_eq!(g.gpustat() >> 28 & 1, 0);
    g.gp1(0x0400_0001);
    assert_eq!(g.gpustat() >> 25 & 1, 1, "FIFO not full");
}

/// The time a DMA waited is not counted twice: seen from the clock, the seven fills end
/// seven fill-times after the DMA started, and running the returned cycles leaves the rest.
#[test]
fn dma_wait_is_not_counted_twice() {
    let fill = [0x0200_0000u32, 0, 0x0001_0010];
    let words: Vec<u32> = fill.iter().copied().cycle().take(21).collect();
    let mut g = quiet();
    let fill_gpu = units_to_gpu(57.0);
    let cycles = g.dma_block_write(&words);
    assert_eq!(g.cycles_until_next_event(), gpu_to_cpu(7 * fill_gpu));
    let mut done_at = None;
    for t in 1..=gpu_to_cpu(7 * fill_gpu) + 1 {
        if g.run(1).drawing_done {
            done_at = Some(t);
            break;
        }
    }
    assert_eq!(done_at, Some(gpu_to_cpu(7 * fill_gpu)));
    // The DMA itself ended well before the drawing.
    assert!(cycles < gpu_to_cpu(7 * fill_gpu));
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
    /// drawing, reported exactly once, after the sum of the fills' times; the GPU is then
    /// ready for commands and DMA blocks again.
    #[test]
    fn fills_by_dma_end_when_predicted(sizes in prop::collection::vec((1u32..64, 1u32..64), 1..40)) {
        let mut words = Vec::new();
        let mut total_gpu = 0u32;
        for &(w, h) in &sizes {
            words.extend_from_slice(&[0x0200_0000, 0, h << 16 | w]);
            let width = (w + 15) & !15;
            total_gpu += units_to_gpu(46.0 + (h * (width / 8 + 9)) as f64);
        }
        let mut g = quiet();
        g.dma_block_write(&words);
        prop_assert_eq!(g.cycles_until_next_event(), gpu_to_cpu(total_gpu));
        let mut done = 0;
        for _ in 0..4 {
            let n = g.cycles_until_next_event();
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
