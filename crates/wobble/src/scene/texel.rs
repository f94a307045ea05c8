//! Image pixels as the GPU's texels: 8-bit RGBA (a PNG's pixels) to the 1555 format
//! (docs/hardware/gpu.md §1).

/// 8-bit RGBA to a 1555 texel: alpha below 128 is transparent (0000h); pure black becomes
/// 8000h, which the GPU draws as opaque black (0000h would be transparent).
pub fn to_1555(rgba: [u8; 4]) -> u16 {
    if rgba[3] < 128 {
        return 0;
    }
    let c = (rgba[0] >> 3) as u16 | ((rgba[1] >> 3) as u16) << 5 | ((rgba[2] >> 3) as u16) << 10;
    if c == 0 { 0x8000 } else { c }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn black_and_transparent() {
        assert_eq!(to_1555([0, 0, 0, 255]), 0x8000);
        assert_eq!(to_1555([255, 255, 255, 0]), 0);
        assert_eq!(to_1555([255, 8, 0, 255]), 31 | 1 << 5);
    }
}
