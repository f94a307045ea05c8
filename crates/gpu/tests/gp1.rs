//! GP1 words built by `gpu::gp1::Gp1` against the layouts of docs/hardware/gpu.md §9 and
//! psx-spx "GPU Display Control Commands", and against the GPU executing the original word.

use gpu::Gpu;
use gpu::gp1::Gp1;
use proptest::prelude::*;

/// Words worked out by hand from psx-spx's field positions: 05h X bits 0-9, Y 10-18; 06h X1
/// bits 0-11, X2 12-23; 07h Y1 bits 0-9, Y2 10-19; 03h bit 0 = display off.
#[test]
fn words_have_the_documented_layout() {
    let cases = [
        (Gp1::Reset, 0x0000_0000),
        (Gp1::ResetCommandBuffer, 0x0100_0000),
        (Gp1::AcknowledgeIrq, 0x0200_0000),
        (Gp1::DisplayEnabled(true), 0x0300_0000),
        (Gp1::DisplayEnabled(false), 0x0300_0001),
        (Gp1::DmaDirection(2), 0x0400_0002),
        // 3FFh | 1FFh << 10 = 7FFFFh.
        (Gp1::DisplayStart { x: 0x3FF, y: 0x1FF }, 0x0507_FFFF),
        // The NTSC 320-pixel range of psx-spx: 260h..260h + 320 * 8 = C60h.
        (
            Gp1::HorizontalRange {
                x1: 0x260,
                x2: 0xC60,
            },
            0x06C6_0260,
        ),
        // 10h | 100h << 10 = 40010h.
        (
            Gp1::VerticalRange {
                y1: 0x10,
                y2: 0x100,
            },
            0x0704_0010,
        ),
        (Gp1::DisplayMode(0x09), 0x0800_0009),
        (Gp1::AllowTextureDisable(true), 0x0900_0001),
        (Gp1::GetInfo(7), 0x1000_0007),
        (Gp1::Unused(0x20), 0x2000_0000),
    ];
    for (command, word) in cases {
        assert_eq!(command.word(), word, "{command:?}");
        assert_eq!(Gp1::from_word(word), command, "{word:08X}");
    }
}

/// A field wider than its bits is cut to them, as the GPU reads it.
#[test]
fn wide_fields_are_cut_to_their_bits() {
    assert_eq!(Gp1::DisplayStart { x: 0x401, y: 0x202 }.word(), 0x0500_0801);
    assert_eq!(
        Gp1::HorizontalRange {
            x1: 0x1001,
            x2: 0x1002
        }
        .word(),
        0x0600_2001
    );
    assert_eq!(
        Gp1::VerticalRange {
            y1: 0x401,
            y2: 0x402
        }
        .word(),
        0x0700_0801
    );
    assert_eq!(Gp1::DmaDirection(6).word(), 0x0400_0002);
    assert_eq!(Gp1::GetInfo(0x0D).word(), 0x1000_0005);
}

/// 10h-1Fh are one command; the other bytes past 09h have no fields.
#[test]
fn command_bytes() {
    for op in 0u32..=0xFF {
        let command = Gp1::from_word(op << 24 | 0xFF_FFFF);
        let expected = match op {
            0x10..=0x1F => 0x10,
            _ => op as u8,
        };
        assert_eq!(command.op(), expected, "{op:02X}");
        assert_eq!(
            matches!(command, Gp1::Unused(_)),
            op > 0x09 && !(0x10..=0x1F).contains(&op)
        );
    }
}

/// What the GPU shows after a GP1 write: display registers, GPUSTAT, the GPUREAD latch.
fn observed(gpu: &mut Gpu) -> (gpu::DisplayState, u32, u32) {
    (*gpu.display_state(), gpu.gpustat(), gpu.gpuread())
}

/// Any GP1 word, the command bytes with fields (00h-1Fh) most of the time.
fn gp1_word() -> impl Strategy<Value = u32> {
    prop_oneof![
        4 => (0u32..0x20, any::<u32>()).prop_map(|(op, bits)| op << 24 | bits & 0xFF_FFFF),
        1 => any::<u32>(),
    ]
}

proptest! {
    /// Executing the re-encoded command does what executing the original word does, and
    /// reading it back gives the same command.
    #[test]
    fn the_encoded_word_acts_as_the_original(
        word in gp1_word(),
        before in proptest::collection::vec(gp1_word(), 0..4),
    ) {
        let command = Gp1::from_word(word);
        prop_assert_eq!(Gp1::from_word(command.word()), command);
        let (mut original, mut encoded) = (Gpu::new(), Gpu::new());
        for &w in &before {
            original.gp1(w);
            encoded.gp1(w);
        }
        original.gp1(word);
        encoded.gp1(command.word());
        prop_assert_eq!(observed(&mut original), observed(&mut encoded));
    }
}
