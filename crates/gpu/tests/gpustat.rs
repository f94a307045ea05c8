//! GPUSTAT ready/DMA bits 25-30 before, during and after rendering, transcribed from
//! ps1-tests `gpu/gpustat` (main.cpp and psx.log, all twelve cases pass on a console).
//! ps1-tests is MIT-licensed, Copyright (c) 2020 Jakub Czekański
//! (fixtures/gpu/LICENSE-ps1-tests).
//!
//! "Before" is GPUSTAT just before the commands are sent, "during" right after the CPU
//! writes or the DMA returns, "after" once the GPU has had time to finish (the test waits a
//! `delay(1000000)` or `delay(100000)` loop: far longer than the two 128x128 tiles take).

use gpu::{Gpu, ListEnd};

const DMA_REQUEST: u32 = 25;
const READY_TO_RECV_CMD_WORD: u32 = 26;
const READY_TO_SEND_VRAM: u32 = 27;
const READY_TO_RECV_DMA_BLOCK: u32 = 28;
const DMA_DIRECTION: u32 = 29;

/// Bits 25, 26, 27, 28 and the direction field, as the test's `assertBit` calls list them.
fn bits(stat: u32) -> [u32; 5] {
    [
        stat >> DMA_REQUEST & 1,
        stat >> READY_TO_RECV_CMD_WORD & 1,
        stat >> READY_TO_SEND_VRAM & 1,
        stat >> READY_TO_RECV_DMA_BLOCK & 1,
        (stat & 0x6000_0000) >> DMA_DIRECTION,
    ]
}

/// The test's `main`: a 320x240 drawing area (`initVideo`), dithering and drawing to the
/// display area on (`setDithering(1)`).
fn gpu() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 239 << 10 | 319, 0xE100_0600]);
    g
}

/// A TILE (GP0 60h, variable size) as the PsyQ `setTile`/`setXY0`/`setWH`/`setRGB0` lay it
/// out: colour and code, position, size.
fn tile(x: u32, y: u32, w: u32, h: u32, rgb: [u32; 3]) -> [u32; 3] {
    [
        0x6000_0000 | rgb[2] << 16 | rgb[1] << 8 | rgb[0],
        y << 16 | x,
        h << 16 | w,
    ]
}

/// CPU cycles comfortably past the end of the drawing (the test's delay loops).
fn settle(g: &mut Gpu) {
    let mut guard = 0;
    while g.cycles_until_next_event() != u32::MAX && guard < 16 {
        let n = g.cycles_until_next_event().max(1);
        g.run(n);
        guard += 1;
    }
    g.run(100_000);
}

/// `runTestRenderFromCpu`: one 128x128 tile written through GP0 with DMA off.
#[test]
fn render_from_cpu() {
    let mut g = gpu();
    g.gp1(0x0400_0000);
    let before = g.gpustat();
    for w in tile(0, 0, 128, 128, [128, 0, 0]) {
        g.gp0(w);
    }
    let during = g.gpustat();
    settle(&mut g);
    let after = g.gpustat();
    assert_eq!(
        bits(before),
        [0, 1, 0, 1, 0],
        "testGpustat_CPU_beforeRender"
    );
    assert_eq!(
        bits(during),
        [0, 0, 0, 1, 0],
        "testGpustat_CPU_duringRender"
    );
    assert_eq!(bits(after), [0, 1, 0, 1, 0], "testGpustat_CPU_afterRender");
}

/// `runTestRenderFromDmaLinkedList`: two tiles in a two-node list, DMA direction 2.
#[test]
fn render_from_linked_list_dma() {
    let mut g = gpu();
    let mut ram = vec![0u8; 2 * 1024 * 1024];
    // renderList in the test's stack; any RAM address serves.
    let base = 0x0001_F000u32;
    let mut list = [0u32; 8];
    list[0] = 3 << 24 | (base + 16);
    list[1..4].copy_from_slice(&tile(128, 0, 128, 128, [0, 128, 0]));
    list[4] = 3 << 24 | 0x00FF_FFFF;
    list[5..8].copy_from_slice(&tile(256, 0, 128, 128, [0, 0, 128]));
    for (i, w) in list.iter().enumerate() {
        let a = base as usize + 4 * i;
        ram[a..a + 4].copy_from_slice(&w.to_le_bytes());
    }
    g.gp1(0x0400_0002);
    let before = g.gpustat();
    let report = g.dma_linked_list(&ram, 0x8000_0000 | base);
    let during = g.gpustat();
    settle(&mut g);
    let after = g.gpustat();
    assert_eq!(
        bits(before),
        [1, 1, 0, 1, 2],
        "testGpustat_linkedListDMA_beforeRender"
    );
    assert_eq!(
        bits(during),
        [0, 0, 0, 0, 2],
        "testGpustat_LinkedListDMA_duringRender"
    );
    assert_eq!(
        bits(after),
        [1, 1, 0, 1, 2],
        "testGpustat_LinkedListDMA_afterRender"
    );
    assert_eq!(report.end, ListEnd::EndMarker);
    assert_eq!((report.nodes, report.words), (2, 6));
    // Two headers and six data words at one cycle each, no FIFO wait (psx-spx "DMA
    // Transfer Rates").
    assert_eq!((report.cycles, report.wait_cycles), (8, 0));
    // Both tiles are in VRAM.
    assert_eq!(g.vram().pixel(200, 100), 16 << 5);
    assert_eq!(g.vram().pixel(300, 100), 16 << 10);
}

/// The eight words `runTestRenderFromDmaSyncBlock_dir*` send in sync mode (BCR 8 blocks of
/// one word): a NOP, a tile, a NOP, a tile.
fn sync_block() -> [u32; 8] {
    let mut words = [0u32; 8];
    words[1..4].copy_from_slice(&tile(0, 128, 128, 128, [128, 128, 0]));
    words[5..8].copy_from_slice(&tile(128, 128, 128, 128, [0, 128, 128]));
    words
}

/// `runTestRenderFromDmaSyncBlock_dir1`: DMA direction 1, bit 25 is "FIFO not full".
#[test]
fn render_from_sync_block_dma_direction_1() {
    let mut g = gpu();
    g.gp1(0x0400_0001);
    let before = g.gpustat();
    g.dma_block_write(&sync_block());
    let during = g.gpustat();
    settle(&mut g);
    let after = g.gpustat();
    assert_eq!(bits(before), [1, 1, 0, 1, 1], "dir1_beforeRender");
    assert_eq!(bits(during), [1, 0, 0, 0, 1], "dir1_duringRender");
    assert_eq!(bits(after), [1, 1, 0, 1, 1], "dir1_afterRender");
}

/// `runTestRenderFromDmaSyncBlock_dir2`: DMA direction 2, bit 25 follows bit 28.
#[test]
fn render_from_sync_block_dma_direction_2() {
    let mut g = gpu();
    g.gp1(0x0400_0002);
    let before = g.gpustat();
    g.dma_block_write(&sync_block());
    let during = g.gpustat();
    settle(&mut g);
    let after = g.gpustat();
    assert_eq!(bits(before), [1, 1, 0, 1, 2], "dir2_beforeRender");
    assert_eq!(bits(during), [0, 0, 0, 0, 2], "dir2_duringRender");
    assert_eq!(bits(after), [1, 1, 0, 1, 2], "dir2_afterRender");
}

/// Direction 3: bit 25 follows bit 27 (psx-spx "GPU Status Register"; the printout of
/// ps1-tests gpu/gpustat lists the same rule). While the GPU fetches the rectangle for
/// GPUREAD it is executing a command: bit 26 is clear (psx-spx "Ready Bits"; docs/emulator.md,
/// "Drawing time"), and the DMA waits for the word (its fetch: 570/256 CPU cycles a word,
/// 3 GPU cycles rounded down, 2 CPU cycles rounded up).
#[test]
fn direction_3_requests_while_vram_data_waits() {
    let mut g = gpu();
    g.gp1(0x0400_0003);
    assert_eq!(bits(g.gpustat()), [0, 1, 0, 1, 3]);
    g.gp0_words(&[0xC000_0000, 0, 0x0001_0002]);
    assert_eq!(bits(g.gpustat()), [1, 0, 1, 1, 3]);
    let mut out = [0u32; 1];
    assert_eq!(g.dma_block_read(&mut out), 2);
    assert_eq!(bits(g.gpustat()), [0, 1, 0, 1, 3]);
}
