//! Save states: `Gte::state` / `Gte::load_state` restore the engine exactly, without the side
//! effects of register writes (docs/hardware/gte.md §2), and (with `serde`) survive serialization.

use gte::{DivideMode, Flag, Gte, GteState, Registers, StateError};
use proptest::prelude::*;

fn supported_modes() -> Vec<DivideMode> {
    [DivideMode::Unr, DivideMode::Exact, DivideMode::F32]
        .into_iter()
        .filter(|m| m.is_supported())
        .collect()
}

/// Any register file: every field an arbitrary bit pattern (FLAG as a CTC2 write keeps it).
fn registers() -> impl Strategy<Value = Registers> {
    prop::collection::vec(any::<u32>(), 96).prop_map(|w| {
        let mut it = w.into_iter();
        let mut next = move || it.next().unwrap_or(0);
        let m3 = |f: &mut dyn FnMut() -> u32| -> [[i16; 3]; 3] {
            std::array::from_fn(|_| std::array::from_fn(|_| f() as i16))
        };
        Registers {
            v: m3(&mut next),
            rgbc: next(),
            otz: next() as u16,
            ir: std::array::from_fn(|_| next() as i16),
            sxy: std::array::from_fn(|_| next()),
            sz: std::array::from_fn(|_| next() as u16),
            rgb: std::array::from_fn(|_| next()),
            res1: next(),
            mac: std::array::from_fn(|_| next() as i32),
            lzcs: next(),
            lzcr: next(),
            rt: m3(&mut next),
            tr: std::array::from_fn(|_| next() as i32),
            llm: m3(&mut next),
            bk: std::array::from_fn(|_| next() as i32),
            lcm: m3(&mut next),
            fc: std::array::from_fn(|_| next() as i32),
            ofx: next() as i32,
            ofy: next() as i32,
            h: next() as u16,
            dqa: next() as i16,
            dqb: next() as i32,
            zsf3: next() as i16,
            zsf4: next() as i16,
            flag: Flag::from_bits(next()),
        }
    })
}

fn state() -> impl Strategy<Value = GteState> {
    (registers(), prop::sample::select(supported_modes())).prop_map(|(registers, divide_mode)| {
        GteState {
            version: GteState::VERSION,
            registers,
            divide_mode,
        }
    })
}

/// A command word: mostly defined opcodes, with random field bits.
fn command() -> impl Strategy<Value = u32> {
    (
        prop::sample::select(gte::Opcode::ALL.to_vec()),
        any::<u32>(),
    )
        .prop_map(|(op, bits)| (bits & 0x01FF_FFC0) | op.bits())
}

fn all_registers(gte: &Gte) -> Vec<u32> {
    (0..64).map(|r| gte.read(r)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// A raw state loads exactly: the fields are the ones saved (no IRGB, SXYP, LZCS or FLAG
    /// write rule applied), all 64 register reads agree, and commands then agree.
    #[test]
    fn load_restores_exactly(s in state(), cmds in prop::collection::vec(command(), 0..8)) {
        let mut original = Gte::new();
        original.load_state(&s).unwrap();
        prop_assert_eq!(&original.state(), &s);
        let mut restored = Gte::new();
        restored.load_state(&original.state()).unwrap();
        prop_assert_eq!(all_registers(&restored), all_registers(&original));
        for &c in &cmds {
            prop_assert_eq!(original.execute(c), restored.execute(c));
            prop_assert_eq!(all_registers(&restored), all_registers(&original));
        }
        prop_assert_eq!(original.state(), restored.state());
        prop_assert_eq!(&original, &restored);
    }

    /// Saving through the 64 register reads and writing them back is not a restore (IRGB
    /// rewrites IR1-3, SXYP pushes the FIFO, LZCS recomputes LZCR); `load_state` is.
    #[test]
    fn register_round_trip_differs_where_state_does_not(s in state()) {
        let mut original = Gte::new();
        original.load_state(&s).unwrap();
        let mut via_registers = Gte::new();
        for r in 0..64 {
            via_registers.write(r, original.read(r));
        }
        let r = &s.registers;
        let irgb_exact = (1..4).all(|n| r.ir[n] as u16 & !0xF80 == 0);
        let lzcr_exact = r.lzcr == if r.lzcs >> 31 == 1 { r.lzcs.leading_ones() } else { r.lzcs.leading_zeros() };
        let sxy_exact = r.sxy[0] == r.sxy[1] && r.sxy[1] == r.sxy[2];
        prop_assert_eq!(via_registers.registers() == original.registers(), irgb_exact && lzcr_exact && sxy_exact);
    }

    /// Random commands, a JSON save at a random point, restore into a fresh engine: both
    /// continue with identical registers and FLAG.
    #[cfg(feature = "serde")]
    #[test]
    fn serde_save_restore_mid_sequence(
        s in state(),
        cmds in prop::collection::vec(command(), 1..12),
        at in any::<prop::sample::Index>(),
    ) {
        let mut gte = Gte::new();
        gte.load_state(&s).unwrap();
        let split = at.index(cmds.len() + 1);
        for &c in &cmds[..split] {
            gte.execute(c);
        }
        let json = serde_json::to_string(&gte.state()).unwrap();
        let mut restored = Gte::new();
        restored.load_state(&serde_json::from_str(&json).unwrap()).unwrap();
        for &c in &cmds[split..] {
            prop_assert_eq!(gte.execute(c), restored.execute(c));
            prop_assert_eq!(all_registers(&restored), all_registers(&gte));
            prop_assert_eq!(restored.flag(), gte.flag());
        }
        prop_assert_eq!(restored.state(), gte.state());
        // Every truncation is an error, never a panic.
        for cut in (0..json.len()).step_by(7) {
            prop_assert!(serde_json::from_str::<GteState>(&json[..cut]).is_err());
        }
    }

    /// Any reachable state survives the binary layout (postcard: the registers as one block)
    /// exactly, and an engine loaded from it equals the one saved.
    #[cfg(feature = "serde")]
    #[test]
    fn binary_round_trip(s in state()) {
        let mut gte = Gte::new();
        gte.load_state(&s).unwrap();
        let bytes = postcard::to_allocvec(&gte.state()).unwrap();
        let back: GteState = postcard::from_bytes(&bytes).unwrap();
        prop_assert_eq!(&back, &gte.state());
        let mut restored = Gte::new();
        restored.load_state(&back).unwrap();
        prop_assert_eq!(restored, gte);
    }
}

/// One COP2 operation of the CPU.
#[cfg(feature = "serde")]
#[derive(Clone, Copy, Debug)]
enum Op {
    Mtc2(u32, u32),
    Ctc2(u32, u32),
    Execute(u32),
    Mfc2(u32),
    Cfc2(u32),
}

#[cfg(feature = "serde")]
fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (0..32u32, any::<u32>()).prop_map(|(r, v)| Op::Mtc2(r, v)),
        (0..32u32, any::<u32>()).prop_map(|(r, v)| Op::Ctc2(r, v)),
        command().prop_map(Op::Execute),
        (0..32u32).prop_map(Op::Mfc2),
        (0..32u32).prop_map(Op::Cfc2),
    ]
}

/// Perform `op`; returns what the CPU observes (a read, or a command's cycle count).
#[cfg(feature = "serde")]
fn perform(gte: &mut Gte, op: Op) -> Option<u32> {
    match op {
        Op::Mtc2(r, v) => {
            gte.write_data(r, v);
            None
        }
        Op::Ctc2(r, v) => {
            gte.write_control(r, v);
            None
        }
        Op::Execute(c) => gte.execute(c),
        Op::Mfc2(r) => Some(gte.read_data(r)),
        Op::Cfc2(r) => Some(gte.read_control(r)),
    }
}

#[cfg(feature = "serde")]
proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A random sequence of MTC2, CTC2, commands, MFC2 and CFC2 from a random state, saved
    /// (JSON) at a random point and restored into a fresh engine: every read and cycle count
    /// after it, and all 64 registers after each step, are those of the engine never saved.
    #[test]
    fn save_anywhere_in_a_register_and_command_sequence(
        s in state(),
        ops in prop::collection::vec(op(), 1..40),
        at in any::<prop::sample::Index>(),
    ) {
        let mut gte = Gte::new();
        gte.load_state(&s).unwrap();
        let split = at.index(ops.len() + 1);
        for &o in &ops[..split] {
            perform(&mut gte, o);
        }
        let json = serde_json::to_string(&gte.state()).unwrap();
        let mut restored = Gte::new();
        restored.load_state(&serde_json::from_str(&json).unwrap()).unwrap();
        prop_assert_eq!(restored.divide_mode(), gte.divide_mode());
        for &o in &ops[split..] {
            prop_assert_eq!(perform(&mut restored, o), perform(&mut gte, o), "{:?}", o);
            prop_assert_eq!(all_registers(&restored), all_registers(&gte));
        }
        prop_assert_eq!(restored.state(), gte.state());
    }
}

#[test]
fn other_version_is_refused() {
    let mut gte = Gte::new();
    gte.write_control(26, 320);
    let mut s = gte.state();
    s.version = GteState::VERSION + 1;
    let mut fresh = Gte::new();
    assert_eq!(
        fresh.load_state(&s),
        Err(StateError::Version {
            found: GteState::VERSION + 1,
            expected: GteState::VERSION
        })
    );
    assert_eq!(fresh, Gte::new(), "a refused state changes nothing");
}

#[cfg(not(feature = "divide-modes"))]
#[test]
fn unsupported_divide_mode_is_refused() {
    let mut s = Gte::new().state();
    s.divide_mode = DivideMode::Exact;
    assert_eq!(
        Gte::new().load_state(&s),
        Err(StateError::DivideMode(gte::UnsupportedDivideMode(
            DivideMode::Exact
        )))
    );
}

#[cfg(feature = "serde")]
#[test]
fn serialized_versions_and_size() {
    let mut gte = Gte::new();
    for r in 0..64 {
        gte.write(r, 0x8765_4321u32.rotate_left(r));
    }
    let json = serde_json::to_string(&gte.state()).unwrap();
    // The version is written first, and checked as soon as it is read.
    assert!(json.starts_with(&format!("{{\"version\":{}", GteState::VERSION)));
    let other = json.replacen(
        &format!("\"version\":{}", GteState::VERSION),
        "\"version\":7",
        1,
    );
    let err = serde_json::from_str::<GteState>(&other)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("version 7")
            && err.contains(&format!("reads versions 1 to {}", GteState::VERSION)),
        "{err}"
    );
    let garbage = r#"{"version":7,"registers":[1,2,3]}"#;
    let err = serde_json::from_str::<GteState>(garbage)
        .unwrap_err()
        .to_string();
    assert!(err.contains("version 7"), "{err}");
    eprintln!("serialized GTE state: {} bytes of JSON", json.len());
    assert!(json.len() < 2048);
}

/// `Gte` equality is that of the architectural state: an engine restored from the state of one
/// that has just run a command (whose FLAG bits were collected in a per-command scratch word)
/// equals it; a difference in one register or in the divide mode does not.
#[test]
fn equality_is_the_architectural_state() {
    let mut gte = Gte::new();
    gte.write_control(26, 1); // H = 1
    gte.write_data(1, 1); // VZ0 = 1: H / SZ3 overflows (FLAG bit 17)
    gte.write_data(0, 0x7FFF_7FFF); // VX0 = VY0 = 7FFFh: SX2/SY2 saturate
    assert_eq!(gte.execute(0x0008_0001), Some(15)); // RTPS
    assert!(!gte.flag().is_empty(), "the command set FLAG bits");
    let mut restored = Gte::new();
    restored.load_state(&gte.state()).unwrap();
    assert_eq!(restored, gte);
    let mut other = restored.clone();
    other.write_data(8, 1); // IR0
    assert_ne!(other, gte);
    #[cfg(feature = "divide-modes")]
    {
        let mut other = restored.clone();
        other.set_divide_mode(DivideMode::Exact).unwrap();
        assert_ne!(other, gte);
    }
}

/// Binary formats (postcard here) hold the registers as one block of 64 little-endian words,
/// data r0-r31 then control c0-c31, each as MFC2/CFC2 reads it except r15/r28/r29 (SXYP, IRGB,
/// ORGB: not stored, 0); JSON keeps the named fields.
#[cfg(feature = "serde")]
#[test]
fn binary_states_hold_the_registers_as_one_block() {
    let mut gte = Gte::new();
    for r in 0..64 {
        gte.write(r, 0x8765_4321u32.rotate_left(r));
    }
    gte.execute(0x0008_0030); // RTPT
    let state = gte.state();
    let bytes = postcard::to_allocvec(&state).unwrap();
    // version (varint 2), block length (varint 256: 80h 02h), the block, divide mode (0).
    assert_eq!(&bytes[..3], &[GteState::VERSION as u8, 0x80, 0x02]);
    assert_eq!(bytes.len(), 3 + 256 + 1);
    let word = |r: usize| u32::from_le_bytes(bytes[3 + 4 * r..7 + 4 * r].try_into().unwrap());
    for r in 0..64u32 {
        let expected = match r {
            15 | 28 | 29 => 0,
            _ => gte.read(r),
        };
        assert_eq!(word(r as usize), expected, "register {r}");
    }
    let back: GteState = postcard::from_bytes(&bytes).unwrap();
    assert_eq!(back, state);
    let mut restored = Gte::new();
    restored.load_state(&back).unwrap();
    assert_eq!(restored, gte);
    // Every truncation is an error.
    for cut in 0..bytes.len() {
        assert!(
            postcard::from_bytes::<GteState>(&bytes[..cut]).is_err(),
            "cut {cut}"
        );
    }
    // A word the engine cannot hold: bits above VZ0's sign extension, a stored SXYP, FLAG
    // bits 0-11.
    for (r, value) in [(1usize, 0x0001_0000u32), (15, 1), (63, 1)] {
        let mut wrong = bytes.clone();
        let at = 3 + 4 * r;
        wrong[at..at + 4].copy_from_slice(&(word(r) ^ value).to_le_bytes());
        let err = postcard::from_bytes::<GteState>(&wrong).unwrap_err();
        assert_eq!(err, postcard::Error::SerdeDeCustom, "register {r}");
    }
    // JSON: the registers field by field.
    let json = serde_json::to_value(&state).unwrap();
    assert_eq!(json["version"], GteState::VERSION);
    assert_eq!(json["registers"]["h"], state.registers.h);
    assert_eq!(serde_json::from_value::<GteState>(json).unwrap(), state);
}

/// States of version 1 (the registers field by field in every format), built here from the
/// public `Registers` serialization, load: postcard and JSON, the JSON also with its keys
/// sorted (registers before version).
#[cfg(feature = "serde")]
#[test]
fn version_1_states_load() {
    let mut gte = Gte::new();
    for r in 0..64 {
        gte.write(r, 0x1357_9BDFu32.rotate_left(3 * r));
    }
    let state = gte.state();
    let v1 = postcard::to_allocvec(&(1u32, &state.registers, state.divide_mode)).unwrap();
    let back: GteState = postcard::from_bytes(&v1).expect("version 1 loads");
    assert_eq!(back.version, 1);
    assert_eq!(back.registers, state.registers);
    let mut restored = Gte::new();
    restored.load_state(&back).unwrap();
    assert_eq!(restored, gte);
    let mut json = serde_json::to_value(&state).unwrap();
    json["version"] = 1.into();
    let text = format!(
        "{{\"version\":1,\"registers\":{},\"divide_mode\":{}}}",
        json["registers"], json["divide_mode"]
    );
    for back in [
        serde_json::from_str::<GteState>(&text).unwrap(),
        serde_json::from_value::<GteState>(json).unwrap(),
    ] {
        assert_eq!((back.version, &back.registers), (1, &state.registers));
    }
}

#[cfg(feature = "serde")]
proptest! {
    /// Any 256-byte register block in a version-2 binary state loads or is refused with an
    /// error, never a panic (run with debug assertions: `cargo test -p gte --all-features`);
    /// a block that loads is one the engine would write back unchanged.
    #[test]
    fn any_binary_block_loads_or_is_refused(words in prop::collection::vec(any::<u32>(), 64)) {
        let mut bytes = vec![GteState::VERSION as u8, 0x80, 0x02];
        for w in &words {
            bytes.extend_from_slice(&w.to_le_bytes());
        }
        bytes.push(0); // divide mode
        if let Ok(state) = postcard::from_bytes::<GteState>(&bytes) {
            prop_assert_eq!(postcard::to_allocvec(&state).unwrap(), bytes);
        }
    }
}
