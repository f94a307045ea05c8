//! Save states (feature `serde`): a GPU serialized mid-packet, mid CPU-to-VRAM transfer and
//! with a latched CLUT that no longer matches VRAM continues exactly like one never
//! interrupted; malformed VRAM data is an error.
#![cfg(feature = "serde")]

use gpu::Gpu;

fn xy(x: u32, y: u32) -> u32 {
    y << 16 | x
}

/// Index in `script()` where the polygon's packet is half received.
const MID_POLYGON: usize = 3;

/// The word stream, with the split positions it is cut at.
fn script() -> (Vec<u32>, [usize; 2]) {
    let mut w = vec![0xE300_0000, 0xE407_FFFF, 0xE500_0000];
    // CLUT at (0, 300): entry i = i * 0421h.
    w.extend([0xA000_0000, xy(0, 300), 1 << 16 | 16]);
    for pair in 0..8u32 {
        w.push((((2 * pair + 1) * 0x421) << 16) | ((2 * pair) * 0x421));
    }
    // 4-bit texels 1..15 then 0 in row 0 of the page at x = 512.
    w.extend([0xA000_0000, xy(512, 0), 1 << 16 | 4]);
    w.extend([0x8765_4321, 0x0FED_CBA9]);
    w.push(0xE100_0008); // page 512, 4-bit
    // Raw 16x1 sprite through the CLUT: latches it.
    w.extend([0x6500_0000, xy(0, 100), 300 << 22, 1 << 16 | 16]);
    // Overwrite the CLUT in VRAM with green; the latched entries stay (docs/hardware/gpu.md §7).
    w.extend([0x0200_FF00, xy(0, 300), 1 << 16 | 16]);
    // Raw textured triangle, split after its third word.
    let tri_start = w.len();
    w.extend([
        0x2500_0000,
        xy(0, 200),
        300 << 22,
        xy(16, 200),
        8 << 16 | 4,
        xy(0, 216),
        0,
    ]);
    // CPU-to-VRAM 4x2, split after two of its four data words.
    let transfer_start = w.len();
    w.extend([0xA000_0000, xy(100, 100), 2 << 16 | 4]);
    w.extend([0x1111_2222, 0x3333_4444, 0x5555_6666, 0x7777_0001]);
    // A sprite through the latched CLUT.
    w.extend([0x6500_0000, xy(0, 110), 300 << 22, 1 << 16 | 4]);
    (w, [tri_start + MID_POLYGON, transfer_start + 5])
}

fn round_trip(g: &Gpu) -> Gpu {
    let json = serde_json::to_string(g).expect("serializes");
    serde_json::from_str(&json).expect("deserializes")
}

#[test]
fn resumes_mid_packet_mid_transfer_with_latched_clut() {
    let (words, splits) = script();
    let mut reference = Gpu::new();
    reference.gp0_words(&words);
    // The last sprite used the latched CLUT: texel index 2 -> entry 2 = 0842h, not green.
    assert_eq!(reference.vram().pixel(1, 110), 2 * 0x421);
    assert_eq!(reference.vram().pixel(1, 300), 0x03E0);
    for split in splits {
        let mut first = Gpu::new();
        first.gp0_words(&words[..split]);
        assert_eq!(
            first.gpustat() >> 26 & 1,
            0,
            "split {split} is inside a packet or transfer"
        );
        let mut resumed = round_trip(&first);
        assert_eq!(resumed.gpustat(), first.gpustat());
        resumed.gp0_words(&words[split..]);
        assert_eq!(resumed.gpustat(), reference.gpustat(), "split {split}");
        assert!(
            resumed.vram().as_slice() == reference.vram().as_slice(),
            "split {split}: VRAM differs"
        );
    }
}

/// VRAM data of the wrong length, or not halfwords, is refused with an error.
#[test]
fn bad_vram_is_an_error() {
    let g = Gpu::new();
    let mut value = serde_json::to_value(&g).expect("serializes");
    let vram = value["vram"].as_array_mut().expect("vram is a sequence");
    assert_eq!(vram.len(), 1024 * 512);
    vram.pop();
    assert!(serde_json::from_value::<Gpu>(value.clone()).is_err());
    let vram = value["vram"].as_array_mut().expect("vram is a sequence");
    vram.push(0.into());
    vram.push(0.into());
    assert!(serde_json::from_value::<Gpu>(value.clone()).is_err());
    let vram = value["vram"].as_array_mut().expect("vram is a sequence");
    vram.pop();
    vram[5] = 70000.into();
    assert!(serde_json::from_value::<Gpu>(value.clone()).is_err());
    value["vram"][5] = 7.into();
    let back: Gpu = serde_json::from_value(value).expect("exact length accepted");
    assert_eq!(back.vram().pixel(5, 0), 7);
}
