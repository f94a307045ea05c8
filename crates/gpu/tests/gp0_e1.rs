//! GP0(E1h) draw mode as GPUSTAT reads it back, and the texture-disable rules, transcribed
//! from ps1-tests `gpu/gp0-e1` (main.cpp and psx.log, all ten cases pass on a console).
//! ps1-tests is MIT-licensed, Copyright (c) 2020 Jakub Czekański
//! (fixtures/gpu/LICENSE-ps1-tests).

use gpu::Gpu;

/// GPUSTAT bits 0-10 and 15 (E1 bits 0-10 and 11).
const E1_MASK: u32 = 0b1000_0111_1111_1111;

fn allow_texture_disable(g: &mut Gpu, allow: bool) {
    g.gp1(0x0900_0000 | allow as u32);
}

fn write_e1(g: &mut Gpu, bits: u32) {
    g.gp0(0xE100_0000 | bits);
}

/// `drawTexturedPolygon`: a POLY_FT4 (GP0 2Ch) with colour 808080h, CLUT 0, UV 0,0 to
/// 255,255 and the given texpage attribute.
fn draw_textured_polygon(g: &mut Gpu, texpage: u32) {
    g.gp0_words(&[
        0x2C80_8080,
        0x0000_0000,
        0x0000_0000,
        0x0020_0000,
        texpage << 16 | 0x00FF,
        0x0000_0020,
        0xFF00,
        0x0020_0020,
        0xFFFF,
    ]);
}

fn gpu() -> Gpu {
    let mut g = Gpu::new();
    // main(): clearScreen(), then GP0(01h).
    g.gp0(0x0100_0000);
    g
}

#[test]
fn write_zeros_to_e1() {
    let mut g = gpu();
    allow_texture_disable(&mut g, false);
    write_e1(&mut g, 0x000);
    assert_eq!(g.gpustat() & E1_MASK, 0);
}

#[test]
fn write_ones_to_e1() {
    let mut g = gpu();
    allow_texture_disable(&mut g, false);
    write_e1(&mut g, 0xFFF);
    assert_eq!(g.gpustat() & E1_MASK, 0b0000_0111_1111_1111);
}

#[test]
fn write_ones_to_e1_with_texture_disable() {
    let mut g = gpu();
    allow_texture_disable(&mut g, true);
    write_e1(&mut g, 0xFFF);
    assert_eq!(g.gpustat() & E1_MASK, 0b1000_0111_1111_1111);
}

/// A textured polygon's texpage rewrites bits 0-8 (and 11 when allowed), never 9-10.
#[test]
fn textured_polygons() {
    let mut g = gpu();
    allow_texture_disable(&mut g, false);
    write_e1(&mut g, 0x000);
    draw_textured_polygon(&mut g, 0xFFFF);
    assert_eq!(g.gpustat() & E1_MASK, 0b0000_0001_1111_1111);
}

#[test]
fn textured_polygons_texture_disable() {
    let mut g = gpu();
    allow_texture_disable(&mut g, true);
    write_e1(&mut g, 0x000);
    draw_textured_polygon(&mut g, 0xFFFF);
    assert_eq!(g.gpustat() & E1_MASK, 0b1000_0001_1111_1111);
}

#[test]
fn textured_polygons_do_not_change_other_bits() {
    let mut g = gpu();
    allow_texture_disable(&mut g, true);
    write_e1(&mut g, 0xFFF);
    draw_textured_polygon(&mut g, 0x0000);
    assert_eq!(g.gpustat() & E1_MASK, 0b0000_0110_0000_0000);
}

#[test]
fn texture_disable_bit_is_ignored_when_not_allowed() {
    let mut g = gpu();
    allow_texture_disable(&mut g, false);
    write_e1(&mut g, 1 << 11);
    assert_eq!(g.gpustat() & 1 << 15, 0);
}

#[test]
fn texture_disable_bit_is_written_when_allowed() {
    let mut g = gpu();
    allow_texture_disable(&mut g, true);
    write_e1(&mut g, 1 << 11);
    assert_eq!(g.gpustat() & 1 << 15, 1 << 15);
}

/// Clearing the allow bit only blocks later writes; the stored bit still reads back.
#[test]
fn unset_allow_texture_disable_preserves_bit() {
    let mut g = gpu();
    allow_texture_disable(&mut g, true);
    write_e1(&mut g, 1 << 11);
    allow_texture_disable(&mut g, false);
    assert_eq!(g.gpustat() & 1 << 15, 1 << 15);
}

#[test]
fn unset_allow_texture_disable_clears_bit_after_write() {
    let mut g = gpu();
    allow_texture_disable(&mut g, true);
    write_e1(&mut g, 1 << 11);
    allow_texture_disable(&mut g, false);
    write_e1(&mut g, 0);
    assert_eq!(g.gpustat() & 1 << 15, 0);
}
