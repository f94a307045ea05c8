//! GPU dumps (`.psxgpu`): dumps built byte by byte from the text of `GPUDUMP.md` (ps1dev
//! standards) and from DuckStation's two differences (a 14-byte magic, GPU versions numbered
//! from 0) read back as the packets they spell; the writer produces those same bytes;
//! malformed dumps give the error the reader documents; the recorder's prologue restores a
//! GPU's state; no input makes the reader panic.

use gpu::dump::{
    Dialect, DumpError, DumpErrorKind, GpuVersion, Packet, PacketType, Reader, RecordInfo,
    Recorder, VsyncTime, WriteError, Writer,
};
use gpu::{Gpu, VRAM_LEN};
use proptest::prelude::*;

/// A packet header: length in bits 0-23, type in bits 24-31, little-endian.
fn head(kind: u8, words: u32) -> [u8; 4] {
    ((kind as u32) << 24 | words).to_le_bytes()
}

fn word(w: u32) -> [u8; 4] {
    w.to_le_bytes()
}

/// The packets of a dump, payload words copied out.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Owned {
    Gp0(Vec<u32>),
    Gp1(Vec<u32>),
    VSync(VsyncTime),
    Discard(u32),
    Readback(u32),
    TraceBegin,
    Version(u32, Option<GpuVersion>),
    GameId(Vec<u8>),
    Video(Vec<u8>),
    Comment(Vec<u8>),
    Unknown(u8, Vec<u32>),
}

fn owned(p: &Packet<'_>) -> Owned {
    match p {
        Packet::Gp0(w) => Owned::Gp0(w.iter().collect()),
        Packet::Gp1(w) => Owned::Gp1(w.iter().collect()),
        Packet::VSync(t) => Owned::VSync(*t),
        Packet::Discard(n) => Owned::Discard(*n),
        Packet::Readback(n) => Owned::Readback(*n),
        Packet::TraceBegin => Owned::TraceBegin,
        Packet::GpuVersion { word, version } => Owned::Version(*word, *version),
        Packet::GameId(t) => Owned::GameId(t.as_bytes().to_vec()),
        Packet::VideoFormat(t) => Owned::Video(t.as_bytes().to_vec()),
        Packet::Comment(t) => Owned::Comment(t.as_bytes().to_vec()),
        Packet::Unknown { kind, payload } => Owned::Unknown(*kind, payload.iter().collect()),
    }
}

fn read_all(bytes: &[u8]) -> Result<Vec<(usize, Owned)>, DumpError> {
    Reader::new(bytes)?
        .map(|p| p.map(|(at, p)| (at, owned(&p))))
        .collect()
}

/// Every packet type of revision 1, and an unknown one, after `magic`, as the
/// specification lays them out; with the packets they must read as.
fn sample(magic: &[u8], version_word: u32) -> (Vec<u8>, Vec<Owned>) {
    let mut b = magic.to_vec();
    b.extend(head(0x06, 1));
    b.extend(word(version_word));
    // "SLUS-00001": 10 bytes, a zero, one byte of padding: 3 words.
    b.extend(head(0x10, 3));
    b.extend(b"SLUS-00001\0\0");
    // "NTSC": 4 bytes, then a whole zero word for its terminator.
    b.extend(head(0x11, 2));
    b.extend(b"NTSC\0\0\0\0");
    b.extend(head(0x12, 1));
    b.extend(b"hi\0\0");
    // State restore: one GP1 word, two GP0 words.
    b.extend(head(0x01, 1));
    b.extend(word(0x0300_0000));
    b.extend(head(0x00, 2));
    b.extend(word(0xE100_0200));
    b.extend(word(0xE600_0000));
    b.extend(head(0x05, 0));
    // A packet of a type revision 1 does not define: skipped by its length.
    b.extend(head(0x13, 2));
    b.extend(word(0xDEAD_BEEF));
    b.extend(word(0x0000_0005));
    b.extend(head(0x02, 0));
    b.extend(head(0x02, 1));
    b.extend(word(0x1234_5678));
    b.extend(head(0x02, 2));
    b.extend(word(0x9ABC_DEF0));
    b.extend(word(0x0000_0001));
    b.extend(head(0x03, 1));
    b.extend(word(8));
    b.extend(head(0x04, 1));
    b.extend(word(2));
    let packets = vec![
        Owned::Version(version_word, None),
        Owned::GameId(b"SLUS-00001".to_vec()),
        Owned::Video(b"NTSC".to_vec()),
        Owned::Comment(b"hi".to_vec()),
        Owned::Gp1(vec![0x0300_0000]),
        Owned::Gp0(vec![0xE100_0200, 0xE600_0000]),
        Owned::TraceBegin,
        Owned::Unknown(0x13, vec![0xDEAD_BEEF, 5]),
        Owned::VSync(VsyncTime::None),
        Owned::VSync(VsyncTime::Cycles32(0x1234_5678)),
        Owned::VSync(VsyncTime::Cycles64(0x1_9ABC_DEF0)),
        Owned::Discard(8),
        Owned::Readback(2),
    ];
    (b, packets)
}

/// Packet offsets of `sample`: each header follows the previous payload.
fn offsets(start: usize) -> Vec<usize> {
    let sizes = [1, 3, 2, 1, 1, 2, 0, 2, 0, 1, 2, 1, 1];
    let mut at = start;
    sizes
        .iter()
        .map(|s| {
            let here = at;
            at += 4 + 4 * s;
            here
        })
        .collect()
}

fn expect(
    mut packets: Vec<Owned>,
    version: Option<GpuVersion>,
    start: usize,
) -> Vec<(usize, Owned)> {
    if let Owned::Version(_, v) = &mut packets[0] {
        *v = version;
    }
    offsets(start).into_iter().zip(packets).collect()
}

/// Both dialects read every packet type. DuckStation's magic is 14 bytes: the first packet
/// header is at byte 14, and every later one at 14 + 4k, none of them word-aligned in the
/// file; the specification's is 16 bytes with the revision.
#[test]
fn each_dialect_reads_every_packet_type() {
    let dialects = [
        (&b"PSXGPUDUMPv1r1\0\0"[..], 2, Dialect::Spec, Some(1), 16),
        (&b"PSXGPUDUMPv1\0\0"[..], 1, Dialect::DuckStation, None, 14),
    ];
    for (magic, version_word, dialect, minor, len) in dialects {
        let (bytes, packets) = sample(magic, version_word);
        let r = Reader::new(&bytes).unwrap();
        assert_eq!(r.dialect(), dialect);
        assert_eq!(r.header().minor, minor);
        assert_eq!(r.header().len, len);
        assert_eq!(
            read_all(&bytes).unwrap(),
            expect(packets, Some(GpuVersion::V2), len)
        );
    }
}

/// GPUDUMP.md: 1 = v1 1 MB, 2 = v2 1 MB, 3 = v2 2 MB, other values reserved; DuckStation's
/// enum (V1_1MB_VRAM, V2_1MB_VRAM, V2_2MB_VRAM) starts at 0.
#[test]
fn gpu_version_numbering_per_dialect() {
    let cases = [
        (Dialect::Spec, 0, None),
        (Dialect::Spec, 1, Some(GpuVersion::V1)),
        (Dialect::Spec, 2, Some(GpuVersion::V2)),
        (Dialect::Spec, 3, Some(GpuVersion::V2Vram2Mb)),
        (Dialect::Spec, 4, None),
        (Dialect::DuckStation, 0, Some(GpuVersion::V1)),
        (Dialect::DuckStation, 1, Some(GpuVersion::V2)),
        (Dialect::DuckStation, 2, Some(GpuVersion::V2Vram2Mb)),
        (Dialect::DuckStation, 3, None),
        (Dialect::DuckStation, u32::MAX, None),
    ];
    for (dialect, w, version) in cases {
        let mut bytes = dialect.magic().to_vec();
        bytes.extend(head(0x06, 1));
        bytes.extend(word(w));
        let got = read_all(&bytes).unwrap();
        assert_eq!(got[0].1, Owned::Version(w, version), "{dialect:?} {w}");
        if let Some(v) = version {
            assert_eq!(v.word(dialect), w);
        }
    }
}

/// The writer produces the bytes the specification spells, in both dialects; a GPU-version
/// packet copied across dialects is renumbered.
#[test]
fn writer_produces_the_hand_built_bytes() {
    for (dialect, version_word) in [(Dialect::Spec, 2), (Dialect::DuckStation, 1)] {
        let (bytes, _) = sample(dialect.magic(), version_word);
        let mut w = Writer::new(Vec::new(), dialect).unwrap();
        w.gpu_version(GpuVersion::V2).unwrap();
        w.game_id(b"SLUS-00001").unwrap();
        w.video_format(b"NTSC").unwrap();
        w.comment(b"hi").unwrap();
        w.gp1(&[0x0300_0000]).unwrap();
        w.gp0(&[0xE100_0200, 0xE600_0000]).unwrap();
        w.trace_begin().unwrap();
        w.unknown(0x13, &[0xDEAD_BEEF, 5]).unwrap();
        w.vsync(VsyncTime::None).unwrap();
        w.vsync(VsyncTime::Cycles32(0x1234_5678)).unwrap();
        w.vsync(VsyncTime::Cycles64(0x1_9ABC_DEF0)).unwrap();
        w.discard(8).unwrap();
        w.readback(2).unwrap();
        assert_eq!(w.into_inner(), bytes, "{dialect:?}");

        // Copy every packet into the other dialect: same bytes but the magic and the
        // version word.
        let other = match dialect {
            Dialect::Spec => Dialect::DuckStation,
            Dialect::DuckStation => Dialect::Spec,
        };
        let mut copy = Writer::new(Vec::new(), other).unwrap();
        for p in Reader::new(&bytes).unwrap() {
            copy.packet(&p.unwrap().1).unwrap();
        }
        let (expected, _) = sample(other.magic(), GpuVersion::V2.word(other));
        assert_eq!(copy.into_inner(), expected);
    }
}

/// Strings are zero-terminated and zero-padded to a word: n bytes take n / 4 + 1 words.
#[test]
fn strings_are_terminated_and_padded() {
    for n in 0..=9usize {
        let text: Vec<u8> = (0..n).map(|i| b'A' + i as u8).collect();
        let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
        w.comment(&text).unwrap();
        let bytes = w.into_inner();
        let words = n / 4 + 1;
        assert_eq!(bytes.len(), 16 + 4 + 4 * words, "{n}");
        assert_eq!(&bytes[16..20], &head(0x12, words as u32));
        assert_eq!(&bytes[20..20 + n], &text[..]);
        assert!(bytes[20 + n..].iter().all(|&b| b == 0));
        assert_eq!(read_all(&bytes).unwrap()[0].1, Owned::Comment(text));
    }
    let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
    assert_eq!(w.game_id(b"A\0B"), Err(WriteError::ZeroInString));
    assert_eq!(
        w.unknown(0x02, &[]),
        Err(WriteError::KnownType { kind: 0x02 })
    );
}

fn error_of(bytes: &[u8]) -> DumpError {
    match Reader::new(bytes) {
        Err(e) => e,
        Ok(r) => r
            .filter_map(Result::err)
            .next()
            .expect("the dump should be malformed"),
    }
}

#[test]
fn malformed_dumps_give_their_error() {
    let spec = b"PSXGPUDUMPv1r1\0\0".to_vec();
    let at = |offset, kind| DumpError { offset, kind };
    // Magic.
    assert_eq!(
        error_of(b""),
        at(0, DumpErrorKind::TruncatedMagic { len: 0 })
    );
    assert_eq!(
        error_of(b"PSXGPUDUMPv1r1\0"),
        at(0, DumpErrorKind::TruncatedMagic { len: 15 })
    );
    assert_eq!(
        error_of(b"PSXGPUDUMPv1\0"),
        at(0, DumpErrorKind::TruncatedMagic { len: 13 })
    );
    for bad in [
        &b"gp0 02000000\n"[..],
        b"PSXGPUDUMPx1r1\0\0",
        b"PSXGPUDUMPvXr1\0\0",
        b"PSXGPUDUMPv1r1\0X",
        b"PSXGPUDUMPv1rZ\0\0",
        b"PSXGPUDUMPv1\0X",
        b"PSXGPUDUMPv1r12345\0\0\0\0",
        b"\x28\xB5\x2F\xFD compressed",
    ] {
        assert_eq!(error_of(bad), at(0, DumpErrorKind::BadMagic), "{bad:?}");
    }
    // Format version 2 would be a breaking change: refused, in either magic form.
    for v2 in [
        &b"PSXGPUDUMPv2r0\0\0"[..],
        b"PSXGPUDUMPv2\0\0",
        b"PSXGPUDUMPv10r1\0",
    ] {
        let major = if v2[12] == b'0' { 10 } else { 2 };
        assert_eq!(
            error_of(v2),
            at(0, DumpErrorKind::UnsupportedVersion { major })
        );
    }
    // A later revision of version 1 is read (unknown packets are skipped).
    assert_eq!(
        Reader::new(b"PSXGPUDUMPv1r7\0\0").unwrap().header().minor,
        Some(7)
    );

    // A packet header cut short.
    let mut b = spec.clone();
    b.extend(head(0x02, 0));
    b.extend([0x01, 0x00]);
    assert_eq!(
        error_of(&b),
        at(20, DumpErrorKind::TruncatedPacketHeader { bytes: 2 })
    );
    // A length past the end.
    let mut b = spec.clone();
    b.extend(head(0x00, 3));
    b.extend(word(0xE100_0000));
    b.extend([0u8; 5]);
    assert_eq!(
        error_of(&b),
        at(
            16,
            DumpErrorKind::PastEnd {
                kind: 0,
                words: 3,
                available: 2
            }
        )
    );
    // The largest length a header can give, in a tiny file.
    let mut b = spec.clone();
    b.extend(head(0x13, 0xFF_FFFF));
    assert!(matches!(
        error_of(&b).kind,
        DumpErrorKind::PastEnd {
            words: 0xFF_FFFF,
            ..
        }
    ));
    // A string without its zero.
    let mut b = spec.clone();
    b.extend(head(0x10, 1));
    b.extend(b"SLUS");
    assert_eq!(
        error_of(&b),
        at(
            16,
            DumpErrorKind::UnterminatedString {
                kind: PacketType::GameId
            }
        )
    );
    // Fixed-size packets of another size.
    for (kind, words, t) in [
        (0x02u8, 3u32, PacketType::VSync),
        (0x03, 0, PacketType::Discard),
        (0x04, 2, PacketType::Readback),
        (0x05, 1, PacketType::TraceBegin),
        (0x06, 0, PacketType::GpuVersion),
    ] {
        let mut b = spec.clone();
        b.extend(head(kind, words));
        b.extend(vec![0u8; 4 * words as usize]);
        assert_eq!(
            error_of(&b),
            at(16, DumpErrorKind::PayloadSize { kind: t, words })
        );
    }
    // Errors print the offset and what is wrong.
    let mut b = spec.clone();
    b.extend(head(0x06, 0));
    let e = error_of(&b);
    assert_eq!(
        e.to_string(),
        "byte 16: packet type 06h (GPU version) has 0 words; it holds 1"
    );
}

/// After an error the reader yields nothing more.
#[test]
fn reader_stops_after_an_error() {
    let mut b = b"PSXGPUDUMPv1\0\0".to_vec();
    b.extend(head(0x02, 0));
    b.extend(head(0x02, 9));
    b.extend(head(0x02, 0));
    let items: Vec<_> = Reader::new(&b).unwrap().collect();
    assert_eq!(items.len(), 2);
    assert!(items[0].is_ok() && items[1].is_err());
}

/// A dump replayed the simple way: GP0/GP1 words to their port, discard/readback as
/// GPUREAD reads, everything else ignored.
fn replay(bytes: &[u8]) -> Gpu {
    let mut gpu = Gpu::new();
    for p in Reader::new(bytes).unwrap() {
        match p.unwrap().1 {
            Packet::Gp0(w) => w.iter().for_each(|x| {
                gpu.gp0(x);
            }),
            Packet::Gp1(w) => w.iter().for_each(|x| gpu.gp1(x)),
            Packet::Discard(n) | Packet::Readback(n) => {
                for _ in 0..n {
                    gpu.gpuread();
                }
            }
            _ => {}
        }
    }
    gpu
}

/// A GP0(A0h) transfer of size 0x0 covers the whole 1024x512 VRAM (psx-spx "GPU Memory
/// Transfer Commands": size ((n - 1) & 3FFh) + 1 by ((n - 1) & 1FFh) + 1), as DuckStation's
/// prologue relies on.
#[test]
fn zero_size_transfer_loads_all_of_vram() {
    let pixel = |i: usize| ((i * 2_654_435_761) >> 7) as u16;
    let mut w = Writer::new(Vec::new(), Dialect::DuckStation).unwrap();
    let mut words = vec![0xA000_0000, 0, 0];
    words.extend((0..VRAM_LEN / 2).map(|i| pixel(2 * i) as u32 | (pixel(2 * i + 1) as u32) << 16));
    w.gp0(&words).unwrap();
    let gpu = replay(&w.into_inner());
    for (i, &p) in gpu.vram().as_slice().iter().enumerate() {
        assert_eq!(p, pixel(i), "pixel {i}");
    }
    assert!(gpu.pending_input().is_none());
}

/// GPU states reached by arbitrary environment, display and transfer commands.
fn driven_gpu(gp0: &[u32], gp1: &[u32], fill: u16) -> Gpu {
    let mut gpu = Gpu::new();
    gpu.vram_mut()
        .as_mut_slice()
        .iter_mut()
        .enumerate()
        .for_each(|(i, p)| *p = (i as u16).wrapping_mul(fill) ^ fill);
    for &w in gp1 {
        // Display registers 03h-09h only (not resets, not information reads).
        gpu.gp1((3 + (w >> 24) % 7) << 24 | w & 0xFF_FFFF);
    }
    for &w in gp0 {
        gpu.gp0((0xE1 + (w >> 24) % 6) << 24 | w & 0xFF_FFFF);
    }
    gpu
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The recorder's prologue, replayed on a fresh GPU, gives back VRAM (mask bits
    /// included, even with E6h forcing and testing them), the display and drawing state,
    /// GP1(09h) and the GPUSTAT bits they show.
    #[test]
    fn prologue_restores_the_state(
        gp0 in prop::collection::vec(any::<u32>(), 0..12),
        gp1 in prop::collection::vec(any::<u32>(), 0..12),
        fill in any::<u16>(),
        duckstation in any::<bool>(),
    ) {
        let live = driven_gpu(&gp0, &gp1, fill);
        let dialect = if duckstation { Dialect::DuckStation } else { Dialect::Spec };
        let info = RecordInfo { dialect, game_id: Some("SLUS-00001"), comment: Some("test") };
        let bytes = Recorder::start(Vec::new(), &live, &info).unwrap().finish().unwrap();
        let replayed = replay(&bytes);
        prop_assert!(replayed.vram() == live.vram());
        // GP1(04h), the DMA direction, is the CPU side's business: not restored.
        let mut display = *live.display_state();
        display.dma_direction = 0;
        prop_assert_eq!(replayed.display_state(), &display);
        prop_assert_eq!(replayed.draw_state(), live.draw_state());
        prop_assert_eq!(replayed.texture_disable_allowed(), live.texture_disable_allowed());
        // Bits 0-12 and 14-23: environment and display (13 and 31 follow video timing).
        let mask = 0x00FF_DFFF;
        prop_assert_eq!(replayed.gpustat() & mask, live.gpustat() & mask);
        let packets = read_all(&bytes).unwrap();
        let first = match dialect { Dialect::Spec => 1, Dialect::DuckStation => 0 };
        prop_assert_eq!(&packets[0].1, &Owned::Version(first + 1, Some(GpuVersion::V2)));
        prop_assert!(packets.iter().any(|(_, p)| *p == Owned::TraceBegin));
    }

    /// Bytes at random, and valid dumps with bytes replaced, inserted or cut off, read as
    /// packets or an error, never a panic; offsets grow and stay inside the data.
    #[test]
    fn any_bytes_read_without_panic(
        junk in prop::collection::vec(any::<u8>(), 0..96),
        edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 0..6),
        cut in any::<prop::sample::Index>(),
        duckstation in any::<bool>(),
    ) {
        let (mut b, _) = if duckstation {
            sample(b"PSXGPUDUMPv1\0\0", 1)
        } else {
            sample(b"PSXGPUDUMPv1r1\0\0", 2)
        };
        for (at, byte, op) in &edits {
            let i = at.index(b.len());
            match op {
                0 => b[i] = *byte,
                1 => b.insert(i, *byte),
                _ => { b.remove(i); }
            }
        }
        b.truncate(cut.index(b.len() + 1));
        for data in [&b[..], &junk[..]] {
            if let Ok(r) = Reader::new(data) {
                let mut last = None;
                for item in r {
                    match item {
                        Ok((at, p)) => {
                            prop_assert!(last.is_none_or(|l| at > l) && at < data.len());
                            last = Some(at);
                            // Text displays without panicking, whatever its bytes.
                            if let Packet::Comment(t) | Packet::GameId(t) | Packet::VideoFormat(t) = p {
                                let _ = t.to_string();
                            }
                        }
                        Err(e) => {
                            prop_assert!(e.offset < data.len());
                            let _ = e.to_string();
                        }
                    }
                }
            }
        }
    }
}

/// What the recorder writes after the prologue: a GP0 packet per block of words (single
/// words gathered), GP1
/// words without GP1(04h) and GP1(10h) and above, GPUREAD reads of a VRAM-to-CPU transfer as
/// one discard packet (reads outside one are not recorded), VSyncs; the dump replays to the
/// same VRAM and leaves the same transfer state.
#[test]
fn recorder_logs_ports_reads_and_vsyncs() {
    let mut gpu = Gpu::new();
    let mut rec = Recorder::start(Vec::new(), &gpu, &RecordInfo::default()).unwrap();
    rec.gp0(&mut gpu, 0xE300_0000);
    rec.gp0_words(&mut gpu, &[0xE407_FFFF, 0x0200_00FF, 0, 0x0002_0010]);
    rec.gp1(&mut gpu, 0x0400_0003); // DMA direction: not recorded
    rec.gp1(&mut gpu, 0x1000_0007); // GPU version info read: not recorded
    rec.gp1(&mut gpu, 0x0500_0400); // display start (0, 1)
    // No transfer: the latch, which GP1(10h) index 7 set to 2 (v2 GPU); not recorded.
    assert_eq!(rec.gpuread(&mut gpu), 2);
    rec.gp0_words(&mut gpu, &[0xC000_0000, 0, 0x0002_0004]); // read 4x2 = 4 words
    let mut out = [0u32; 3];
    rec.dma_block_read(&mut gpu, &mut out);
    assert_eq!(out, [0x001F_001F; 3]);
    assert_eq!(rec.gpuread(&mut gpu), 0x001F_001F);
    assert_eq!(rec.gpuread(&mut gpu), 0x001F_001F); // transfer over: latch, not recorded
    rec.vsync(VsyncTime::Cycles64(1 << 40));
    let bytes = rec.finish().unwrap();
    let packets: Vec<Owned> = read_all(&bytes)
        .unwrap()
        .into_iter()
        .map(|(_, p)| p)
        .collect();
    let begin = packets
        .iter()
        .position(|p| *p == Owned::TraceBegin)
        .unwrap();
    assert_eq!(
        packets[begin + 1..],
        [
            Owned::Gp0(vec![0xE300_0000]),
            Owned::Gp0(vec![0xE407_FFFF, 0x0200_00FF, 0, 0x0002_0010]),
            Owned::Gp1(vec![0x0500_0400]),
            Owned::Gp0(vec![0xC000_0000, 0, 0x0002_0004]),
            Owned::Discard(4),
            Owned::VSync(VsyncTime::Cycles64(1 << 40)),
        ]
    );
    let replayed = replay(&bytes);
    assert!(replayed.vram() == gpu.vram());
    assert_eq!(replayed.gpustat() & 1 << 27, gpu.gpustat() & 1 << 27);
}

/// A DMA linked list is recorded as the data words the channel sends, a packet per node
/// with data; the replay draws what the list drew.
#[test]
fn recorder_logs_linked_list_dma() {
    let mut ram = vec![0u8; 2 << 20];
    let mut put = |at: usize, words: &[u32]| {
        for (i, w) in words.iter().enumerate() {
            ram[at + 4 * i..at + 4 * i + 4].copy_from_slice(&w.to_le_bytes());
        }
    };
    // Node at 1000h (no data) -> 2000h (environment, 2 words) -> 3000h (fill, 3 words) -> end.
    put(0x1000, &[0x0000_2000]);
    put(0x2000, &[0x0200_3000, 0xE300_0000, 0xE407_FFFF]);
    put(
        0x3000,
        &[0x03FF_FFFF, 0x0200_FF00, 0x0010_0010, 0x0008_0020],
    );
    let mut gpu = Gpu::new();
    let mut rec = Recorder::start(Vec::new(), &gpu, &RecordInfo::default()).unwrap();
    let report = rec.dma_linked_list(&mut gpu, &ram, 0x1000);
    assert_eq!((report.nodes, report.words), (3, 5));
    let bytes = rec.finish().unwrap();
    let packets: Vec<Owned> = read_all(&bytes)
        .unwrap()
        .into_iter()
        .map(|(_, p)| p)
        .collect();
    assert_eq!(
        packets[packets.len() - 2..],
        [
            Owned::Gp0(vec![0xE300_0000, 0xE407_FFFF]),
            Owned::Gp0(vec![0x0200_FF00, 0x0010_0010, 0x0008_0020])
        ]
    );
    assert_eq!(gpu.vram().pixel(0x10, 0x10), 0x03E0);
    assert!(replay(&bytes).vram() == gpu.vram());
}

/// Recording cannot start in the middle of GP0 input: the dump could not restore it.
#[test]
fn recorder_refuses_to_start_mid_packet() {
    let mut gpu = Gpu::new();
    gpu.gp0(0x2000_00FF);
    assert!(matches!(
        Recorder::start(Vec::new(), &gpu, &RecordInfo::default()),
        Err(gpu::dump::RecordError::Busy(
            gpu::PendingInput::Packet { .. }
        ))
    ));
}

/// A sink that fails after some bytes: the error is kept and returned by `finish`, and the
/// GPU is still driven.
#[test]
fn recorder_keeps_the_first_write_error() {
    #[derive(Debug)]
    struct Full(usize);
    impl gpu::dump::Sink for Full {
        type Error = &'static str;
        fn write_bytes(&mut self, bytes: &[u8]) -> Result<(), &'static str> {
            if self.0 < bytes.len() {
                return Err("disk full");
            }
            self.0 -= bytes.len();
            Ok(())
        }
    }
    let mut gpu = Gpu::new();
    // Room for the prologue (about 1 MiB of VRAM) and a little more.
    let mut rec = Recorder::start(Full(1_049_000), &gpu, &RecordInfo::default()).unwrap();
    for _ in 0..1000 {
        rec.gp0_words(&mut gpu, &[0x0200_00FF, 0, 0x0001_0010]);
        rec.vsync(VsyncTime::None);
    }
    assert!(rec.error().is_some());
    assert_eq!(gpu.vram().pixel(0, 0), 0x001F);
    assert_eq!(
        rec.finish().unwrap_err(),
        gpu::dump::RecordError::Write(WriteError::Sink("disk full"))
    );
}

mod text {
    //! The text form of a dump (`command_stream`'s directives) converts both ways without
    //! losing a packet.
    use super::*;
    use gpu::command_stream::{Directive, Entry, VersionName, from_dump, parse_entries, to_dump};

    /// One packet of a random dump: non-empty GP0 payloads, one-word GP1 packets (the text
    /// writes a `gp1` line per word), strings without zeros.
    fn packet() -> impl Strategy<Value = Owned> {
        let text = prop::collection::vec(1u8..=255, 0..12);
        prop_oneof![
            prop::collection::vec(any::<u32>(), 1..20).prop_map(Owned::Gp0),
            any::<u32>().prop_map(|w| Owned::Gp1(vec![w])),
            Just(Owned::VSync(VsyncTime::None)),
            any::<u32>().prop_map(|t| Owned::VSync(VsyncTime::Cycles32(t))),
            any::<u64>().prop_map(|t| Owned::VSync(VsyncTime::Cycles64(t))),
            any::<u32>().prop_map(Owned::Discard),
            any::<u32>().prop_map(Owned::Readback),
            Just(Owned::TraceBegin),
            any::<u32>().prop_map(|w| Owned::Version(w, None)),
            text.clone().prop_map(Owned::GameId),
            text.clone().prop_map(Owned::Video),
            text.prop_map(Owned::Comment),
            (0x13u8..=0xFF, prop::collection::vec(any::<u32>(), 0..4))
                .prop_map(|(k, w)| Owned::Unknown(k, w)),
        ]
    }

    fn write(dialect: Dialect, packets: &[Owned]) -> Vec<u8> {
        let mut w = Writer::new(Vec::new(), dialect).unwrap();
        for p in packets {
            match p {
                Owned::Gp0(x) => w.gp0(x),
                Owned::Gp1(x) => w.gp1(x),
                Owned::VSync(t) => w.vsync(*t),
                Owned::Discard(n) => w.discard(*n),
                Owned::Readback(n) => w.readback(*n),
                Owned::TraceBegin => w.trace_begin(),
                Owned::Version(n, _) => w.gpu_version_word(*n),
                Owned::GameId(t) => w.game_id(t),
                Owned::Video(t) => w.video_format(t),
                Owned::Comment(t) => w.comment(t),
                Owned::Unknown(k, x) => w.unknown(*k, x),
            }
            .unwrap();
        }
        w.into_inner()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// dump -> text -> dump gives the same bytes, in either dialect.
        #[test]
        fn dump_text_dump(packets in prop::collection::vec(packet(), 0..24), duck in any::<bool>()) {
            let dialect = if duck { Dialect::DuckStation } else { Dialect::Spec };
            let bytes = write(dialect, &packets);
            let mut text = String::new();
            let n = from_dump(Reader::new(&bytes).unwrap(), &mut text).unwrap();
            prop_assert_eq!(n, packets.len());
            let entries = parse_entries(&text).unwrap();
            let mut again = Writer::new(Vec::new(), dialect).unwrap();
            to_dump(&entries, &mut again).unwrap();
            prop_assert_eq!(again.into_inner(), bytes, "{}", text);
        }

        /// text -> dump -> text gives the same lines.
        #[test]
        fn text_dump_text(packets in prop::collection::vec(packet(), 0..24)) {
            let bytes = write(Dialect::Spec, &packets);
            let mut text = String::new();
            from_dump(Reader::new(&bytes).unwrap(), &mut text).unwrap();
            let mut dump = Writer::new(Vec::new(), Dialect::DuckStation).unwrap();
            to_dump(&parse_entries(&text).unwrap(), &mut dump).unwrap();
            let mut again = String::new();
            from_dump(Reader::new(&dump.into_inner()).unwrap(), &mut again).unwrap();
            // The first line names the dialect; the rest is the same.
            prop_assert_eq!(text.split_once('\n').unwrap().1, again.split_once('\n').unwrap().1);
        }
    }

    #[test]
    fn directives_parse_and_print() {
        let text = "\
            gp1 00000000\n\
            Vsync\n\
            vsync 4294967295   # one word\n\
            VSYNC64 18446744073709551615\n\
            discard 1024\n\
            readback 2\n\
            trace-begin\n\
            gpu-version v2-2mb\n\
            gpu-version raw 7\n\
            game-id \"SLUS-00001\"\n\
            video-format \"PAL\"\n\
            comment \"a # is text, \\\"quoted\\\", \\\\, \\x01 and caf\u{e9}\"  # a real comment\n\
            packet 7f 00000001 2\n\
            gp0 02000000 0 10001\n";
        let entries = parse_entries(text).unwrap();
        let d = |line, directive| Entry::Directive { line, directive };
        assert_eq!(entries.len(), 14);
        assert_eq!(entries[1], d(2, Directive::VSync(VsyncTime::None)));
        assert_eq!(
            entries[2],
            d(3, Directive::VSync(VsyncTime::Cycles32(u32::MAX)))
        );
        assert_eq!(
            entries[3],
            d(4, Directive::VSync(VsyncTime::Cycles64(u64::MAX)))
        );
        assert_eq!(entries[4], d(5, Directive::Discard(1024)));
        assert_eq!(entries[5], d(6, Directive::Readback(2)));
        assert_eq!(entries[6], d(7, Directive::TraceBegin));
        assert_eq!(
            entries[7],
            d(
                8,
                Directive::GpuVersion(VersionName::Known(GpuVersion::V2Vram2Mb))
            )
        );
        assert_eq!(entries[8], d(9, Directive::GpuVersion(VersionName::Raw(7))));
        assert_eq!(entries[9], d(10, Directive::GameId(b"SLUS-00001".to_vec())));
        assert_eq!(entries[10], d(11, Directive::VideoFormat(b"PAL".to_vec())));
        let comment = "a # is text, \"quoted\", \\, \u{1} and caf\u{e9}"
            .as_bytes()
            .to_vec();
        assert_eq!(entries[11], d(12, Directive::Comment(comment)));
        assert_eq!(
            entries[12],
            d(
                13,
                Directive::Packet {
                    kind: 0x7F,
                    words: vec![1, 2]
                }
            )
        );
        // Printed, each directive reads back as itself.
        for e in &entries {
            if let Entry::Directive { directive, .. } = e {
                let line = directive.to_string();
                let back = parse_entries(&line).unwrap();
                assert_eq!(
                    back,
                    [Entry::Directive {
                        line: 1,
                        directive: directive.clone()
                    }],
                    "{line}"
                );
            }
        }
        // Port writes alone, for the commands' consumers.
        assert_eq!(gpu::command_stream::parse(text).unwrap().len(), 2);
    }

    #[test]
    fn bad_directives_name_the_line() {
        for (bad, says) in [
            ("vsync x", "not a decimal number"),
            ("vsync 4294967296", "too large"),
            ("vsync 1 2", "unexpected `2`"),
            ("discard", "word count missing"),
            ("discard -1", "not a decimal number"),
            ("trace-begin now", "unexpected"),
            ("gpu-version v3", "v1, v2, v2-2mb or raw N"),
            ("game-id SLUS", "double quotes"),
            ("game-id \"a\\x00\"", "\\x00"),
            ("comment \"a\\q\"", "unknown escape"),
            ("comment \"a\"b\"", "quote inside"),
            ("packet 02", "VSync event: use its own line"),
            ("packet 100", "not a packet type"),
            ("draw 1", "unknown port `draw`"),
        ] {
            let e = parse_entries(&format!("gp1 0\n{bad}\n")).unwrap_err();
            assert_eq!(e.line, 2, "{bad}");
            assert!(e.message.contains(says), "{bad}: {}", e.message);
        }
    }
}
