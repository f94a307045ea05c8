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

/// VRAM data of the wrong length, or not bytes, is refused with an error. VRAM is one block
/// of 2 x 1024 x 512 bytes, each halfword little-endian (JSON writes it as a number array).
#[test]
fn bad_vram_is_an_error() {
    let mut g = Gpu::new();
    g.vram_mut().set_pixel(5, 0, 0x1234);
    let mut value = serde_json::to_value(&g).expect("serializes");
    let vram = value["vram"]
        .as_array_mut()
        .expect("vram is a byte sequence");
    assert_eq!(vram.len(), 2 * 1024 * 512);
    assert_eq!(
        (vram[10].as_u64(), vram[11].as_u64()),
        (Some(0x34), Some(0x12))
    );
    vram.pop();
    assert!(serde_json::from_value::<Gpu>(value.clone()).is_err());
    let vram = value["vram"]
        .as_array_mut()
        .expect("vram is a byte sequence");
    vram.push(0.into());
    vram.push(0.into());
    assert!(serde_json::from_value::<Gpu>(value.clone()).is_err());
    let vram = value["vram"]
        .as_array_mut()
        .expect("vram is a byte sequence");
    vram.pop();
    vram[10] = 256.into();
    assert!(serde_json::from_value::<Gpu>(value.clone()).is_err());
    value["vram"][10] = 7.into();
    let back: Gpu = serde_json::from_value(value).expect("exact length accepted");
    assert_eq!(back.vram().pixel(5, 0), 0x1207);
    // Binary: a block one byte short or long.
    let bytes = postcard::to_allocvec(&g).unwrap();
    let block = postcard::to_allocvec(g.vram()).unwrap();
    let body = &bytes[..bytes.len() - block.len()];
    for len in [2 * 1024 * 512 - 1, 2 * 1024 * 512 + 1] {
        let mut wrong = body.to_vec();
        wrong.extend(postcard::to_allocvec(&serde_bytes_of(len)).unwrap());
        assert!(postcard::from_bytes::<Gpu>(&wrong).is_err(), "{len} bytes");
    }
}

/// A byte block of `len` zero bytes, serialized as bytes.
fn serde_bytes_of(len: usize) -> impl serde::Serialize {
    struct Block(usize);
    impl serde::Serialize for Block {
        fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            s.serialize_bytes(&vec![0u8; self.0])
        }
    }
    Block(len)
}

// ---------------------------------------------------------------------------------------
// Versioned save states (`Gpu::save_state` / `SaveState`).

use gpu::{SAVE_STATE_MAGIC, SAVE_STATE_OLDEST_VERSION, SAVE_STATE_VERSION, SaveState};
use proptest::prelude::*;

fn save(g: &Gpu) -> Vec<u8> {
    postcard::to_allocvec(&g.save_state()).expect("serializes")
}

fn load(bytes: &[u8]) -> Result<Gpu, postcard::Error> {
    postcard::from_bytes::<SaveState>(bytes).map(SaveState::into_gpu)
}

/// A GPU with state in every part: mid CPU-to-VRAM transfer, a VRAM-to-CPU transfer half
/// read, latched CLUT, queued FIFO words, a raised IRQ not yet reported, interlace.
fn busy_gpu() -> Gpu {
    let (words, _) = script();
    let mut g = Gpu::new();
    g.gp1(0x0800_0024); // 480i
    g.gp0_words(&words);
    g.run(300_000);
    g.gp0_words(&[0xC000_0000, xy(0, 100), 2 << 16 | 4]);
    g.gpuread();
    g.gp0(0x1F00_0000);
    // A large fill keeps the GPU busy; the next commands wait in the FIFO.
    g.gp0_words(&[0x0200_00FF, 0, 256 << 16 | 512]);
    g.gp0_words(&[0x2000_00FF, xy(0, 0), xy(8, 0), xy(0, 8)]);
    g.gp0_words(&[0xA000_0000, xy(200, 200), 2 << 16 | 2, 0x1234_5678]);
    g
}

/// Where the version-1 save state of [`busy_gpu`] is kept: postcard, zlib-compressed.
const VERSION_1_FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../fixtures/save-states/busy-v1.postcard.zlib"
);

/// The fields of the `Gpu` value (the order a positional format writes them).
fn body_json(g: &Gpu) -> serde_json::Value {
    serde_json::to_value(g).expect("serializes")
}

#[test]
fn header_then_body_round_trips() {
    let g = busy_gpu();
    assert!(g.pending_input().is_some());
    assert_eq!(g.gpustat() >> 27 & 1, 1, "VRAM-to-CPU data waiting");
    let bytes = save(&g);
    // postcard: magic and version as varints first.
    let mut header = postcard::to_allocvec(&(SAVE_STATE_MAGIC, SAVE_STATE_VERSION)).unwrap();
    assert_eq!(&bytes[..header.len()], &header[..]);
    header.clear();
    let back = load(&bytes).expect("loads");
    assert!(back == g, "the loaded GPU equals the saved one");
    assert_eq!(save(&back), bytes);
    assert_eq!(body_json(&back), body_json(&g));
    assert_eq!(back.gpustat(), g.gpustat());
    assert_eq!(back.pending_input(), g.pending_input());
    assert_eq!(back.cycles_until_next_event(), g.cycles_until_next_event());
    // JSON: header fields by name.
    let json = serde_json::to_string(&g.save_state()).unwrap();
    assert!(json.starts_with(&format!(
        "{{\"magic\":{SAVE_STATE_MAGIC},\"version\":{SAVE_STATE_VERSION},\"gpu\":"
    )));
    let back: SaveState = serde_json::from_str(&json).expect("loads");
    assert_eq!(body_json(&back.into_gpu()), body_json(&g));
}

#[test]
fn every_truncation_is_an_error() {
    let g = busy_gpu();
    let bytes = save(&g);
    // The registers lead the state and VRAM comes last: every cut through the registers,
    // a sample through VRAM, every cut in its last 64 bytes.
    let vram_start = bytes.len() - postcard::to_allocvec(g.vram()).unwrap().len();
    let cuts = (0..vram_start + 16)
        .chain((vram_start..bytes.len()).step_by(9973))
        .chain(bytes.len() - 64..bytes.len());
    for cut in cuts {
        assert!(
            load(&bytes[..cut]).is_err(),
            "cut at {cut} of {}",
            bytes.len()
        );
    }
    let json = serde_json::to_string(&g.save_state()).unwrap();
    let vram_at = json.find("\"vram\"").unwrap();
    for cut in (0..vram_at + 40).chain((vram_at..json.len()).step_by(49_999)) {
        assert!(serde_json::from_str::<SaveState>(&json[..cut]).is_err());
    }
}

#[test]
fn other_version_or_magic_is_refused_before_the_body() {
    let g = Gpu::new();
    let mut json: serde_json::Value = serde_json::to_value(g.save_state()).unwrap();
    json["version"] = (SAVE_STATE_VERSION + 1).into();
    let err = serde_json::from_value::<SaveState>(json.clone())
        .unwrap_err()
        .to_string();
    let expected = format!(
        "GPU save state version {}, this build reads versions 1 to {SAVE_STATE_VERSION}",
        SAVE_STATE_VERSION + 1
    );
    assert!(err.contains(&expected), "{err}");
    json["version"] = (SAVE_STATE_OLDEST_VERSION - 1).into();
    let err = serde_json::from_value::<SaveState>(json.clone())
        .unwrap_err()
        .to_string();
    assert!(err.contains("GPU save state version 0,"), "{err}");
    // Positional: a newer version followed by a body this build cannot parse still names
    // the version.
    let bytes =
        postcard::to_allocvec(&(SAVE_STATE_MAGIC, SAVE_STATE_VERSION + 1, [7u8; 9])).unwrap();
    assert!(matches!(load(&bytes), Err(postcard::Error::SerdeDeCustom)));
    let bytes = postcard::to_allocvec(&(0x1234_5678u32, SAVE_STATE_VERSION)).unwrap();
    assert!(matches!(load(&bytes), Err(postcard::Error::SerdeDeCustom)));
    json["version"] = SAVE_STATE_VERSION.into();
    json["magic"] = 0x1234_5678.into();
    let err = serde_json::from_value::<SaveState>(json.clone())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("not a GPU save state (magic 0x12345678)"),
        "{err}"
    );
    // A body without its header is refused.
    let text = format!("{{\"gpu\":{}}}", serde_json::to_string(&g).unwrap());
    let err = serde_json::from_str::<SaveState>(&text).unwrap_err();
    assert!(err.to_string().contains("missing field `magic`"), "{err}");
}

/// The version-1 state of `busy_gpu` written by the build that wrote version 1 (fixtures/
/// save-states) loads: the same VRAM, registers, transfers and GPUSTAT as `busy_gpu` built
/// now, and the same results when both continue.
#[test]
fn version_1_states_load() {
    let packed = std::fs::read(VERSION_1_FIXTURE).expect("fixture present");
    let bytes = miniz_oxide::inflate::decompress_to_vec_zlib(&packed).expect("zlib");
    assert_eq!(
        &bytes[..6],
        &postcard::to_allocvec(&(SAVE_STATE_MAGIC, 1u32)).unwrap()[..]
    );
    let mut old = load(&bytes).expect("a version-1 state loads");
    let mut now = busy_gpu();
    assert!(old.vram() == now.vram());
    assert_eq!(old.gpustat(), now.gpustat());
    assert_eq!(old.pending_input(), now.pending_input());
    assert_eq!(old.draw_state(), now.draw_state());
    assert_eq!(old.display_state(), now.display_state());
    assert_eq!(old.irq_pending(), now.irq_pending());
    // Saved again it is a version-2 state that loads equal.
    let resaved = save(&old);
    assert_eq!(&resaved[..6], &save(&now)[..6]);
    assert!(load(&resaved).unwrap() == old);
    // Both continue the same, in video time and in what they draw. The drawing time of the
    // work queued at the save is the one version 1 recorded (before the cost table was
    // calibrated), so when drawing ends is not compared.
    let mut seen = [vec![], vec![]];
    for (g, seen) in [&mut old, &mut now].into_iter().zip(&mut seen) {
        seen.push(g.gpuread());
        g.gp0_words(&[0x0200_0000, 0, 64 << 16 | 64]);
        for _ in 0..600 {
            let n = g.cycles_until(gpu::EventKind::HblankStart).min(10_000);
            seen.push(n);
            let ev = g.run(n.max(1));
            seen.push(ev.hblanks + ev.vblank_start as u32 * 1000 + ev.gpu_irq as u32 * 2000);
        }
    }
    assert_eq!(seen[0], seen[1]);
    assert!(old.vram() == now.vram());
    assert_eq!(old.gpustat(), now.gpustat());
}

/// A version-1 state in a self-describing format (JSON, VRAM as a halfword array), built here
/// from the version-2 one, loads as the same GPU, with its header first or its keys sorted.
#[test]
fn version_1_json_loads() {
    let g = busy_gpu();
    let mut body = serde_json::to_value(&g).unwrap();
    let halfwords: Vec<serde_json::Value> = g.vram().as_slice().iter().map(|&p| p.into()).collect();
    body["vram"] = halfwords.into();
    let text = format!("{{\"magic\":{SAVE_STATE_MAGIC},\"version\":1,\"gpu\":{body}}}");
    let back: SaveState = serde_json::from_str(&text).expect("version 1 loads");
    assert!(back.into_gpu() == g);
    // serde_json's Value keeps keys sorted: the body comes before the version.
    let sorted: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(sorted.as_object().unwrap().keys().next().unwrap() == "gpu");
    let back: SaveState = serde_json::from_value(sorted.clone()).expect("version 1 loads");
    assert!(back.into_gpu() == g);
    // A layout other than the version's is refused, in either direction.
    let mut wrong = sorted.clone();
    wrong["version"] = SAVE_STATE_VERSION.into();
    let err = serde_json::from_value::<SaveState>(wrong)
        .unwrap_err()
        .to_string();
    assert!(err.contains("VRAM as halfwords (version 1)"), "{err}");
    let mut wrong = sorted;
    wrong["gpu"]["vram"] = serde_json::to_value(g.vram()).unwrap();
    let err = serde_json::from_value::<SaveState>(wrong)
        .unwrap_err()
        .to_string();
    assert!(err.contains("VRAM as bytes (version 2 on)"), "{err}");
}

/// Each field set to a value the hardware cannot reach is refused with its reason.
#[test]
fn unreachable_fields_are_refused() {
    let g = busy_gpu();
    let base = body_json(&g);
    type Edit = fn(&mut serde_json::Value);
    let cases: [(&str, Edit); 17] = [
        ("GP0 packet buffer longer", |v| v["gp0"]["len"] = 13.into()),
        ("GP0 packet words during a transfer", |v| {
            v["gp0"]["len"] = 1.into()
        }),
        ("transfer position", |v| {
            v["gp0"]["mode"]["Write"]["next"] = 8.into()
        }),
        ("transfer position", |v| {
            v["gp0"]["mode"]["Write"]["next"] = 1.into()
        }),
        ("transfer rectangle", |v| {
            v["gp0"]["mode"]["Write"]["rect"]["w"] = 0.into()
        }),
        ("transfer rectangle", |v| {
            v["read"]["rect"]["h"] = 513.into()
        }),
        ("VRAM-to-CPU transfer position", |v| {
            v["read"]["next"] = 8.into()
        }),
        ("FIFO word count", |v| {
            v["drawing"]["fifo_words"] = 17.into()
        }),
        ("drawing queue index", |v| v["drawing"]["head"] = 16.into()),
        ("drawing-time carry", |v| {
            v["drawing"]["carry"] = (451_584u64 * 256).into()
        }),
        ("interlace field", |v| v["timing"]["field"] = 2.into()),
        ("video clock remainder", |v| {
            v["timing"]["remainder"] = 7.into()
        }),
        ("beam position", |v| {
            v["timing"]["position"] = 2_000_000.into()
        }),
        ("texture window", |v| {
            v["draw"]["window"]["mask_x"] = 32.into()
        }),
        ("drawing offset", |v| v["draw"]["offset_x"] = 1024.into()),
        ("CLUT cache position", |v| {
            v["clut"]["key"] = serde_json::json!([1009, 0])
        }),
        ("display register", |v| {
            v["display"]["dma_direction"] = 4.into()
        }),
    ];
    assert!(serde_json::from_value::<Gpu>(base.clone()).is_ok());
    for (reason, edit) in cases {
        let mut v = base.clone();
        edit(&mut v);
        let err = serde_json::from_value::<Gpu>(v).unwrap_err().to_string();
        assert!(err.contains(reason), "expected {reason:?}, got {err}");
    }
    // A complete packet waiting unexecuted.
    let mut idle = body_json(&Gpu::new());
    idle["gp0"]["buf"][0] = 0xE100_0000u32.into();
    idle["gp0"]["len"] = 1.into();
    let err = serde_json::from_value::<Gpu>(idle).unwrap_err().to_string();
    assert!(err.contains("complete GP0 packet"), "{err}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Garbage bytes, and a valid state with one byte of its registers replaced, load as an
    /// error or as a GPU that keeps working; never a panic.
    #[test]
    fn garbage_never_panics(
        junk in prop::collection::vec(any::<u8>(), 0..64),
        at in any::<prop::sample::Index>(),
        byte in any::<u8>(),
    ) {
        prop_assert!(load(&junk).is_err());
        let g = busy_gpu();
        let mut bytes = save(&g);
        let vram_start = bytes.len() - postcard::to_allocvec(g.vram()).unwrap().len();
        let i = at.index(vram_start);
        bytes[i] = byte;
        if let Ok(mut back) = load(&bytes) {
            back.gp0_words(&[0x2800_FFFF, xy(0, 0), xy(64, 0), xy(0, 64), xy(64, 64)]);
            for _ in 0..4 {
                let wait = back.cycles_until_next_event().min(200_000);
                back.run(wait.max(1));
            }
            back.gpuread();
            let _ = back.gpustat();
            prop_assert!(load(&save(&back)).is_ok());
        }
    }
}

// ---------------------------------------------------------------------------------------
// Save at a random point of a random command stream, restore, continue both.

/// One thing the CPU does to the GPU.
#[derive(Clone, Copy, Debug)]
enum Action {
    Gp0(u32),
    Gp1(u32),
    Run(u32),
    Read,
}

/// A position word in a 200x200 area, slightly past its edges.
fn pos(r: u32) -> u32 {
    let x = (r & 0xFF) % 220;
    let y = (r >> 8 & 0xFF) % 220;
    (y.wrapping_sub(10) & 0x7FF) << 16 | (x.wrapping_sub(10) & 0x7FF)
}

/// A texcoord word: UV anywhere, CLUT or texpage attribute in the high half.
fn uv(r: u32, attr: u32) -> u32 {
    attr << 16 | (r & 0xFFFF)
}

/// Append the actions of one structured item of class `kind`, from the random words `r`.
fn item(kind: u8, r: [u32; 8], out: &mut Vec<Action>) {
    let mut gp0 = |w: u32| out.push(Action::Gp0(w));
    match kind {
        // Polygons: flat/Gouraud, 3/4 vertices, textured or not, semi, raw.
        0..=2 => {
            let flags = r[0] >> 24 & 0x1F;
            let gouraud = flags & 0x10 != 0;
            let quad = flags & 0x08 != 0;
            let textured = flags & 0x04 != 0;
            gp0(0x2000_0000 | flags << 24 | (r[0] & 0xFF_FFFF));
            for v in 0..if quad { 4 } else { 3 } {
                if gouraud && v > 0 {
                    gp0(r[v].rotate_left(7) & 0xFF_FFFF);
                }
                gp0(pos(r[v + 1]));
                if textured {
                    let attr = match v {
                        0 => r[5] >> 16 & 0x7FFF,
                        1 => r[6] >> 16 & 0x9FF,
                        _ => 0,
                    };
                    gp0(uv(r[v + 4], attr));
                }
            }
        }
        // Lines and polylines, terminated.
        3 => {
            let flags = r[0] >> 24 & 0x1B;
            let gouraud = flags & 0x10 != 0;
            let poly = flags & 0x08 != 0;
            gp0(0x4000_0000 | flags << 24 | (r[0] & 0xFF_FFFF));
            gp0(pos(r[1]));
            let count = if poly { 1 + r[7] % 4 } else { 1 };
            for v in 0..count as usize {
                if gouraud {
                    gp0(r[v + 2] & 0xFF_FFFF);
                }
                gp0(pos(r[v + 3]));
            }
            if poly {
                gp0(0x5555_5555);
            }
        }
        // Rectangles of every size class.
        4 => {
            let flags = r[0] >> 24 & 0x1F;
            gp0(0x6000_0000 | flags << 24 | (r[0] & 0xFF_FFFF));
            gp0(pos(r[1]));
            if flags & 0x04 != 0 {
                gp0(uv(r[2], r[3] >> 16 & 0x7FFF));
            }
            if flags & 0x18 == 0 {
                gp0((r[4] & 0x3F) << 16 | (r[4] >> 8 & 0x3F));
            }
        }
        // Fill.
        5 => {
            gp0(0x0200_0000 | (r[0] & 0xFF_FFFF));
            gp0(r[1] & 0x01FF_03FF);
            gp0((r[2] & 0x3F) << 16 | (r[2] >> 8 & 0x3F));
        }
        // VRAM-to-VRAM copy.
        6 => {
            gp0(0x8000_0000);
            gp0(r[1] & 0x01FF_03FF);
            gp0(r[2] & 0x01FF_03FF);
            gp0((r[3] & 0x1F) << 16 | (r[3] >> 8 & 0x1F));
        }
        // CPU-to-VRAM with its data.
        7 => {
            let (w, h) = (1 + r[3] % 6, 1 + (r[3] >> 8) % 4);
            gp0(0xA000_0000);
            gp0(r[1] & 0x01FF_03FF);
            gp0(h << 16 | w);
            for i in 0..(w * h).div_ceil(2) {
                gp0(r[(i % 4) as usize + 4].rotate_left(i));
            }
        }
        // VRAM-to-CPU, then GPUREAD for all of it and one more.
        8 => {
            let (w, h) = (1 + r[3] % 6, 1 + (r[3] >> 8) % 4);
            gp0(0xC000_0000);
            gp0(r[1] & 0x01FF_03FF);
            gp0(h << 16 | w);
            for _ in 0..(w * h).div_ceil(2) + 1 {
                out.push(Action::Read);
            }
        }
        // Environment E1-E6.
        9 => gp0((0xE1 + r[0] % 6) << 24 | (r[1] & 0xFF_FFFF)),
        // GP1: reset, FIFO reset, IRQ ack, display enable, DMA direction, display area and
        // ranges, mode, texture-disable permission, info.
        10 => {
            let cmd = [
                0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x10, 0x10, 0x10,
            ][r[0] as usize % 13];
            let arg = match cmd {
                0x06 => (0x200 + (r[1] & 0x3FF)) | ((0xA00 + (r[1] >> 12 & 0x3FF)) << 12),
                0x07 => (r[1] & 0x3F) | (0xF0 + (r[1] >> 10 & 0x3F)) << 10,
                _ => r[1] & 0xFF_FFFF,
            };
            out.push(Action::Gp1(cmd << 24 | arg));
            if cmd == 0x10 {
                out.push(Action::Read);
            }
        }
        // GP0(1Fh) IRQ request, GP0(01h) CLUT invalidation.
        11 => gp0(if r[0] & 1 == 0 {
            0x1F00_0000
        } else {
            0x0100_0000
        }),
        // Time: up to about a third of a frame.
        12 | 13 => out.push(Action::Run(r[0] % 200_000)),
        // Noise: any word to GP0, or a GPUREAD with no transfer (the latch).
        _ if r[1] & 1 == 0 => out.push(Action::Read),
        _ => gp0(r[0]),
    }
}

/// Perform `a`; returns what the CPU observes (the GPUREAD value and the stall of a load or
/// store, or the events), with GPUSTAT and the GPU time received.
type Observed = (Option<(u32, u32)>, Option<gpu::Events>, u32, u64);
fn perform(g: &mut Gpu, a: Action) -> Observed {
    let (read, events) = match a {
        Action::Gp0(w) => (Some((0, g.gp0(w))), None),
        Action::Gp1(w) => {
            g.gp1(w);
            (None, None)
        }
        Action::Run(c) => (None, Some(g.run(c))),
        Action::Read => (Some(g.gpuread_timed()), None),
    };
    (read, events, g.gpustat(), g.work_cycles())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// VRAM, GPUSTAT, every GPUREAD value, every stall and every `Events` of a GPU restored
    /// from a save taken at any action stay those of the GPU that was never saved.
    #[test]
    fn save_anywhere_continues_identically(
        items in prop::collection::vec((0u8..16, prop::array::uniform8(any::<u32>())), 1..60),
        at in any::<prop::sample::Index>(),
    ) {
        // A drawing area over the test region, so primitives draw.
        let mut actions = vec![
            Action::Gp0(0xE300_0000),
            Action::Gp0(0xE403_FCFF),
            Action::Gp1(0x0300_0000),
        ];
        for (kind, r) in items {
            item(kind, r, &mut actions);
        }
        let split = at.index(actions.len() + 1);
        let mut reference = Gpu::new();
        for &a in &actions[..split] {
            perform(&mut reference, a);
        }
        let mut restored = load(&save(&reference)).expect("a reachable state loads");
        prop_assert!(restored == reference, "a restored GPU equals the saved one");
        prop_assert_eq!(restored.gpustat(), reference.gpustat());
        prop_assert_eq!(restored.cycles_until_next_event(), reference.cycles_until_next_event());
        for (i, &a) in actions[split..].iter().enumerate() {
            let expected = perform(&mut reference, a);
            prop_assert_eq!(perform(&mut restored, a), expected, "action {} {:?}", split + i, a);
        }
        // Drain time and events until both are idle.
        for _ in 0..8 {
            let wait = reference.cycles_until_next_event().min(100_000);
            prop_assert_eq!(restored.cycles_until_next_event().min(100_000), wait);
            prop_assert_eq!(restored.run(wait.max(1)), reference.run(wait.max(1)));
        }
        prop_assert!(restored.vram().as_slice() == reference.vram().as_slice(), "VRAM differs");
        prop_assert_eq!(save(&restored), save(&reference));
        prop_assert!(restored == reference, "equal after running the same actions");
    }
}

/// `Gpu` equality is that of the chip state: a GPU restored from a save equals the original
/// even though the shaded 4-bit CLUT table, a speed aid derived from the CLUT cache, is not
/// saved; and any difference in VRAM, registers or beam position makes two GPUs unequal.
#[test]
fn equality_is_the_chip_state() {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
    // CLUT at (0, 300), 4-bit texels at (512, 0), page 512.
    g.gp0_words(&[0xA000_0000, xy(0, 300), 1 << 16 | 16]);
    g.gp0_words(&[0x7C00_001F; 8]);
    g.gp0_words(&[
        0xA000_0000,
        xy(512, 0),
        1 << 16 | 4,
        0x7654_3210,
        0xFEDC_BA98,
    ]);
    // Three dithered, modulated 4-bit triangles of one colour: the third has the shaded
    // CLUT table built (docs/gpu.md).
    g.gp0(0xE100_0208);
    for y in [0, 40, 80] {
        g.gp0_words(&[
            0x2480_8080,
            xy(0, y),
            300 << 22,
            xy(30, y),
            8 << 16 | 15,
            xy(0, y + 30),
            0,
        ]);
    }
    let back = load(&save(&g)).expect("loads");
    assert!(back == g);
    assert_eq!(back.clone(), back);

    let mut other = back.clone();
    other.vram_mut().set_pixel(1023, 511, 1);
    assert!(other != g, "one VRAM pixel");
    let mut other = back.clone();
    other.gp1(0x0500_0001);
    assert!(other != g, "display start");
    let mut other = back.clone();
    other.run(1);
    assert!(other != g, "one CPU cycle of video time");
    let mut other = back;
    other.gp0(0xE100_0209);
    assert!(other != g, "texture page");
}

/// Rewind as a frontend does it: a postcard state saved at the start of every frame, a jump
/// back five frames, and the same input replayed gives the same GPU at every frame end;
/// run-ahead (save, run a frame, load) leaves the GPU as it was.
#[test]
fn rewind_and_run_ahead_every_frame() {
    /// One frame of a game: a fill, a moving triangle, a display flip, then video time to the
    /// vblank start.
    fn frame(g: &mut Gpu, f: u32) {
        let y = 240 * (f % 2);
        g.gp0_words(&[0x0200_3000, xy(0, y), 240 << 16 | 320]);
        g.gp0_words(&[0xE300_0000 | y << 10, 0xE400_0000 | (y + 239) << 10 | 319]);
        g.gp0_words(&[0xE500_0000 | y << 11]);
        g.gp0_words(&[
            0x3000_00FF,
            xy(10 + f, 10),
            0x0000_FF00,
            xy(200, 30 + f),
            0x00FF_0000,
        ]);
        g.gp0_words(&[xy(60, 200)]);
        g.gp1(0x0500_0000 | (240 - y) << 10);
        let n = g.cycles_until(gpu::EventKind::VblankStart);
        assert!(g.run(n).vblank_start);
    }
    let mut g = Gpu::new();
    g.gp1(0x0300_0000);
    g.gp1(0x0800_0001);
    let mut saves = vec![];
    let mut ends = vec![];
    for f in 0..12 {
        saves.push(save(&g));
        // Run-ahead: a frame into the future and back.
        let mut ahead = load(saves.last().unwrap()).unwrap();
        frame(&mut ahead, f);
        let back = load(saves.last().unwrap()).unwrap();
        assert!(back == g);
        frame(&mut g, f);
        assert!(ahead == g, "frame {f} run ahead is the frame run");
        ends.push(g.clone());
    }
    let mut rewound = load(&saves[6]).unwrap();
    for (f, end) in ends.iter().enumerate().skip(6) {
        frame(&mut rewound, f as u32);
        assert!(rewound == *end, "frame {f} replayed");
    }
}

/// A GPU whose texture cache holds an entry made stale by a fill: texel (0, 0) of the 15-bit
/// page at (512, 0) cached as 0421h, VRAM under it 7C1Fh.
fn stale_cache() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000, 0xE100_0108]);
    g.gp0_words(&[0x0208_0808, xy(512, 0), 1 << 16 | 16]);
    g.gp0_words(&[0x6D00_0000, xy(0, 480), 0]);
    g.gp0_words(&[0x02F8_00F8, xy(512, 0), 1 << 16 | 16]);
    g
}

/// The cache's tags, copies and miss count survive a save: the restored GPU still draws the
/// stale texel (docs/hardware/gpu.md §10) and its next misses cost the same.
#[test]
fn texture_cache_survives_a_save() {
    let mut reference = stale_cache();
    let mut restored = load(&save(&reference)).expect("loads");
    assert_eq!(
        restored.texture_cache_misses(),
        reference.texture_cache_misses()
    );
    for g in [&mut reference, &mut restored] {
        g.gp0_words(&[0x6D00_0000, xy(1, 480), 0]);
        assert_eq!(g.vram().pixel(1, 480), 0x0421);
        g.gp0_words(&[0x7D00_0000, xy(16, 480), 16]);
    }
    assert_eq!(
        restored.texture_cache_misses(),
        reference.texture_cache_misses()
    );
    assert_eq!(save(&restored), save(&reference));
}

/// Texture cache fields the GPU cannot reach are refused with their reason.
#[test]
fn unreachable_texture_cache_fields_are_refused() {
    let base = body_json(&stale_cache());
    assert!(serde_json::from_value::<Gpu>(base.clone()).is_ok());
    // Texel (600, 300) of a 15-bit page: entry 102 (docs/hardware/gpu.md §10), tag a / 4.
    let a = 300 * 1024 + 600;
    type Edit = fn(&mut serde_json::Value);
    let cases: [(&str, Edit); 5] = [
        ("256 entries", |v| {
            v["texture_cache"]["data"].as_array_mut().unwrap().pop();
        }),
        ("tag its entry cannot hold", |v| {
            v["texture_cache"]["tags"][0] = 5.into()
        }),
        ("off but not empty", |v| {
            v["texture_cache"]["enabled"] = false.into()
        }),
        ("page's corner", |v| {
            v["texture_cache"]["resident"] = serde_json::json!({"Page": {"x": 100, "y": 0}})
        }),
        ("outside the page", |v| {
            v["texture_cache"]["copies"] = false.into();
            v["texture_cache"]["tags"][102] = ((300 * 1024 + 600) / 4).into()
        }),
    ];
    assert_eq!(((a >> 2) & 7) | ((a >> 7) & 0xF8), 102);
    for (reason, edit) in cases {
        let mut v = base.clone();
        edit(&mut v);
        let err = serde_json::from_value::<Gpu>(v).unwrap_err().to_string();
        assert!(err.contains(reason), "expected {reason:?}, got {err}");
    }
}
