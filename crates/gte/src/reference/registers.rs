//! MTC2/CTC2 and MFC2/CFC2 on a [`Registers`] value, as docs/hardware/gte.md §2 states the
//! write and read rules of each register.

use super::arithmetic::flag;
use crate::Registers;

fn halves(word: u32) -> (i16, i16) {
    (word as i16, (word >> 16) as i16)
}

fn pack(low: i16, high: i16) -> u32 {
    low as u16 as u32 | (high as u16 as u32) << 16
}

fn sign_extend(half: i16) -> u32 {
    half as i32 as u32
}

/// IRn SAR 7 saturated to 0..=1Fh, the 5-bit field of IRGB/ORGB reads.
fn five_bits(ir: i16) -> u32 {
    (ir >> 7).clamp(0, 0x1F) as u32
}

/// LZCR: how many leading bits equal bit 31, 1..=32.
fn leading_sign_bits(value: u32) -> u32 {
    let mut count = 0;
    let top = value >> 31;
    while count < 32 && (value >> (31 - count)) & 1 == top {
        count += 1;
    }
    count
}

/// MFC2/CFC2 of register `index & 63` (0-31 data, 32-63 control).
pub fn read(regs: &Registers, index: u32) -> u32 {
    let r = &regs;
    let matrix = |m: &[[i16; 3]; 3], i: u32| match i {
        0 => pack(m[0][0], m[0][1]),
        1 => pack(m[0][2], m[1][0]),
        2 => pack(m[1][1], m[1][2]),
        3 => pack(m[2][0], m[2][1]),
        _ => sign_extend(m[2][2]),
    };
    match index & 63 {
        i @ (0 | 2 | 4) => pack(r.v[i as usize / 2][0], r.v[i as usize / 2][1]),
        i @ (1 | 3 | 5) => sign_extend(r.v[i as usize / 2][2]),
        6 => r.rgbc,
        7 => r.otz as u32,
        i @ 8..=11 => sign_extend(r.ir[i as usize - 8]),
        i @ 12..=14 => r.sxy[i as usize - 12],
        15 => r.sxy[2],
        i @ 16..=19 => r.sz[i as usize - 16] as u32,
        i @ 20..=22 => r.rgb[i as usize - 20],
        23 => r.res1,
        i @ 24..=27 => r.mac[i as usize - 24] as u32,
        28 | 29 => five_bits(r.ir[1]) | five_bits(r.ir[2]) << 5 | five_bits(r.ir[3]) << 10,
        30 => r.lzcs,
        31 => r.lzcr,
        i @ 32..=36 => matrix(&r.rt, i - 32),
        i @ 37..=39 => r.tr[i as usize - 37] as u32,
        i @ 40..=44 => matrix(&r.llm, i - 40),
        i @ 45..=47 => r.bk[i as usize - 45] as u32,
        i @ 48..=52 => matrix(&r.lcm, i - 48),
        i @ 53..=55 => r.fc[i as usize - 53] as u32,
        56 => r.ofx as u32,
        57 => r.ofy as u32,
        // H is unsigned in the maths but read sign-extended.
        58 => sign_extend(r.h as i16),
        59 => sign_extend(r.dqa),
        60 => r.dqb as u32,
        61 => sign_extend(r.zsf3),
        62 => sign_extend(r.zsf4),
        _ => r.flag.bits(),
    }
}

/// MTC2/CTC2 of `value` to register `index & 63` (0-31 data, 32-63 control), with the side
/// effects of SXYP, IRGB, LZCS and FLAG; ORGB and LZCR ignore writes.
pub fn write(regs: &mut Registers, index: u32, value: u32) {
    let r = regs;
    let (low, high) = halves(value);
    let matrix = |m: &mut [[i16; 3]; 3], i: u32| match i {
        0 => (m[0][0], m[0][1]) = (low, high),
        1 => (m[0][2], m[1][0]) = (low, high),
        2 => (m[1][1], m[1][2]) = (low, high),
        3 => (m[2][0], m[2][1]) = (low, high),
        _ => m[2][2] = low,
    };
    match index & 63 {
        i @ (0 | 2 | 4) => (r.v[i as usize / 2][0], r.v[i as usize / 2][1]) = (low, high),
        i @ (1 | 3 | 5) => r.v[i as usize / 2][2] = low,
        6 => r.rgbc = value,
        7 => r.otz = low as u16,
        i @ 8..=11 => r.ir[i as usize - 8] = low,
        i @ 12..=14 => r.sxy[i as usize - 12] = value,
        15 => r.sxy = [r.sxy[1], r.sxy[2], value],
        i @ 16..=19 => r.sz[i as usize - 16] = low as u16,
        i @ 20..=22 => r.rgb[i as usize - 20] = value,
        23 => r.res1 = value,
        i @ 24..=27 => r.mac[i as usize - 24] = value as i32,
        28 => {
            for n in 1..=3 {
                r.ir[n] = (((value >> (5 * (n - 1))) & 0x1F) << 7) as i16;
            }
        }
        29 | 31 => {}
        30 => {
            r.lzcs = value;
            r.lzcr = leading_sign_bits(value);
        }
        i @ 32..=36 => matrix(&mut r.rt, i - 32),
        i @ 37..=39 => r.tr[i as usize - 37] = value as i32,
        i @ 40..=44 => matrix(&mut r.llm, i - 40),
        i @ 45..=47 => r.bk[i as usize - 45] = value as i32,
        i @ 48..=52 => matrix(&mut r.lcm, i - 48),
        i @ 53..=55 => r.fc[i as usize - 53] = value as i32,
        56 => r.ofx = value as i32,
        57 => r.ofy = value as i32,
        58 => r.h = low as u16,
        59 => r.dqa = low,
        60 => r.dqb = value as i32,
        61 => r.zsf3 = low,
        62 => r.zsf4 = low,
        // FLAG keeps bits 12-30; bit 31 is their summary.
        _ => r.flag = flag(value & 0x7FFF_F000),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leading_sign_bits_examples() {
        // docs/hardware/gte.md §2: 1..=32; 0 and FFFFFFFFh both give 32.
        assert_eq!(leading_sign_bits(0), 32);
        assert_eq!(leading_sign_bits(u32::MAX), 32);
        assert_eq!(leading_sign_bits(0x8000_0000), 1);
        assert_eq!(leading_sign_bits(0x0000_FFFF), 16);
        assert_eq!(leading_sign_bits(0xFFF0_0000), 12);
    }
}
