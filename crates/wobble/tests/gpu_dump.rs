//! GPU dumps replayed frame by frame: the default animation recorded through the pipeline
//! replays to the frames `render` draws; frames are cut at VSync packets; discard and
//! readback packets consume a VRAM-to-CPU transfer as the CPU's reads did; a command
//! stream's text replays through the same player with its line numbers.

use gpu::dump::{Dialect, RecordInfo, VsyncTime, Writer};
use gpu::{PendingInput, VideoStandard};
use wobble::gpu_dump::{Dump, Player};
use wobble::pipeline::{PipelineOptions, Renderer};
use wobble::scene::Scene;
use wobble::scene::default::default_animation;
use wobble::vram_image::Expand;

/// The whole default animation rendered as `wobble render` renders it, and recorded by a
/// second renderer into a DuckStation-dialect dump: replayed on a fresh GPU, each frame's
/// displayed picture is the rendered frame, pixel for pixel.
#[test]
fn recorded_animation_replays_to_the_rendered_frames() {
    let animation = default_animation();
    let base = Scene::default_scene();
    let mut plain = Renderer::new(base.clone(), PipelineOptions::default()).unwrap();
    let mut recording = Renderer::new(base.clone(), PipelineOptions::default()).unwrap();
    let info = RecordInfo {
        dialect: Dialect::DuckStation,
        game_id: Some("WOBBLE-00001"),
        comment: Some("the default animation"),
    };
    let mut rec = recording.start_recording(Vec::new(), &info).unwrap();
    let mut rendered = Vec::new();
    for frame in 0..animation.frames {
        plain.pose(&animation, &base, frame).unwrap();
        plain.render_frame(frame);
        rendered.push(plain.image());
        recording.pose(&animation, &base, frame).unwrap();
        recording.render_frame_recorded(frame, &mut rec).unwrap();
    }
    let dump = Dump::from_bytes(rec.finish().unwrap()).unwrap();
    let summary = dump.summary(&mut |_| {}).unwrap();
    assert_eq!(summary.frames.len(), animation.frames as usize);
    assert_eq!(summary.game_id.as_deref(), Some("WOBBLE-00001"));
    assert_eq!(summary.video_format.as_deref(), Some("NTSC"));
    assert_eq!(summary.header.dialect, Dialect::DuckStation);
    let mut player = Player::new(&dump, summary.video_standard());
    for (i, expected) in rendered.iter().enumerate() {
        let r = player.run_frame().unwrap().unwrap();
        assert_eq!(r.index, i);
        assert_eq!(r.vsync, Some(VsyncTime::None));
        assert!(r.draws > 0 && r.display_enabled);
        let img = player.displayed_image(Expand::Replicate).unwrap();
        assert!(img == *expected, "frame {i} differs");
    }
    assert!(player.run_frame().unwrap().is_none());
    // The whole VRAM (both buffers, textures) matches too.
    assert!(player.gpu().vram() == plain.gpu().vram());
}

/// Frames end at VSync packets; port data after the last VSync is one more, unfinished,
/// frame; a VSync with nothing before it is a frame of its own (a repeated picture).
#[test]
fn frames_are_cut_at_vsyncs() {
    let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
    w.gp1(&[0x0300_0000]).unwrap();
    w.trace_begin().unwrap();
    // Frame 0: fill 16x1 red at (0, 0).
    w.gp0(&[0x0200_00FF, 0, 0x0001_0010]).unwrap();
    w.vsync(VsyncTime::Cycles32(100)).unwrap();
    // Frame 1: nothing.
    w.vsync(VsyncTime::Cycles64(200)).unwrap();
    // Frame 2: green, then half a triangle.
    w.gp0(&[0x0200_FF00, 0, 0x0001_0010]).unwrap();
    w.gp0(&[0x2000_00FF, 0]).unwrap();
    w.comment(b"the end").unwrap();
    let dump = Dump::from_bytes(w.into_inner()).unwrap();
    let s = dump.summary(&mut |_| {}).unwrap();
    assert_eq!(s.frames.len(), 3);
    assert_eq!(s.frames[0].gp0_words, 3);
    assert_eq!(s.frames[0].gp1_words, 1);
    assert_eq!(s.frames[1].packets, 1);
    assert_eq!(s.frames[2].vsync, None);
    assert_eq!(s.trace_begin, Some(1));
    let mut p = Player::new(&dump, VideoStandard::Ntsc);
    let f0 = p.run_frame().unwrap().unwrap();
    assert_eq!(
        (f0.commands, f0.draws, f0.vsync),
        (1, 0, Some(VsyncTime::Cycles32(100)))
    );
    assert_eq!(p.gpu().vram().pixel(0, 0), 0x001F);
    let f1 = p.run_frame().unwrap().unwrap();
    assert_eq!((f1.index, f1.commands), (1, 0));
    let f2 = p.run_frame().unwrap().unwrap();
    assert_eq!((f2.commands, f2.draws, f2.vsync), (2, 1, None));
    assert_eq!(p.gpu().vram().pixel(0, 0), 0x03E0);
    assert_eq!(
        p.unfinished().map(|u| u.pending),
        Some(PendingInput::Packet {
            command: 0x2000_00FF,
            received: 2,
            expected: 4
        })
    );
    assert!(p.run_frame().unwrap().is_none());
}

/// Each VSync runs the GPU's video timing to its next vblank: in 480i the field alternates
/// from frame to frame, as GPUSTAT bit 13 shows (docs/hardware/timing.md §7).
#[test]
fn vsyncs_advance_the_video_timing() {
    let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
    // 320x480 interlaced, display on.
    w.gp1(&[0x0800_0025, 0x0300_0000]).unwrap();
    for _ in 0..4 {
        w.vsync(VsyncTime::None).unwrap();
    }
    let dump = Dump::from_bytes(w.into_inner()).unwrap();
    let mut p = Player::new(&dump, VideoStandard::Ntsc);
    let mut fields = Vec::new();
    while p.run_frame().unwrap().is_some() {
        fields.push(p.gpu().gpustat() >> 13 & 1);
    }
    assert_eq!(fields.len(), 4);
    assert!(fields.windows(2).all(|w| w[0] != w[1]), "{fields:?}");
}

/// A GP0(C0h) VRAM-to-CPU transfer of 4x2 pixels is 4 GPUREAD words: a discard packet of 3
/// leaves the transfer going (GPUSTAT bit 27), a readback of the last word ends it, as the
/// console's CPU reading those words would.
#[test]
fn readback_consumes_gpuread_words() {
    let mut w = Writer::new(Vec::new(), Dialect::DuckStation).unwrap();
    w.gp0(&[0xC000_0000, 0, 0x0002_0004]).unwrap();
    w.discard(3).unwrap();
    w.vsync(VsyncTime::None).unwrap();
    w.readback(1).unwrap();
    w.vsync(VsyncTime::None).unwrap();
    let dump = Dump::from_bytes(w.into_inner()).unwrap();
    let mut p = Player::new(&dump, VideoStandard::Ntsc);
    let f0 = p.run_frame().unwrap().unwrap();
    assert_eq!(f0.read_words, 3);
    assert_ne!(p.gpu().gpustat() & 1 << 27, 0, "transfer still has a word");
    p.run_frame().unwrap().unwrap();
    assert_eq!(p.gpu().gpustat() & 1 << 27, 0, "transfer consumed");
}

/// A command stream with directives replays through the same player; the packets keep
/// their text lines (for the inspector and for the unfinished-input warning).
#[test]
fn text_streams_replay_with_their_lines() {
    let text = "# two frames\n\
                gp1 03000000\n\
                gp0 020000ff 00000000 00010010\n\
                \n\
                vsync\n\
                comment \"between\"\n\
                gp0 20ff0000 00000000\n";
    let dump = Dump::from_text(text).unwrap();
    assert!(dump.from_stream_text());
    assert_eq!(
        (0..5).map(|i| dump.packet_line(i)).collect::<Vec<_>>(),
        [2, 3, 5, 6, 7]
    );
    let mut p = Player::new(&dump, VideoStandard::Ntsc);
    p.run_frame().unwrap().unwrap();
    p.run_frame().unwrap().unwrap();
    let u = p.unfinished().unwrap();
    assert_eq!(u.line, 7);
    // The second frame's commands for the inspector, with the GPU entering it.
    let mut p = Player::new(&dump, VideoStandard::Ntsc);
    p.skip_to(1, &mut |_| {}).unwrap();
    let f = p.take_frame_commands().unwrap().unwrap();
    assert_eq!(f.index, 1);
    assert_eq!(f.commands.len(), 1);
    assert_eq!(f.commands[0].line, 7);
    assert_eq!(p.gpu().vram().pixel(0, 0), 0x001F);
    let e = Player::new(&dump, VideoStandard::Ntsc)
        .skip_to(5, &mut |_| {})
        .unwrap_err();
    assert!(e.contains("2 frame(s)"), "{e}");
}

/// A display turned off by GP1(03h) shows black; the area GP1 selects otherwise.
#[test]
fn displayed_picture_follows_gp1() {
    let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
    w.gp0(&[0x0200_00FF, 0, 0x00F0_0140]).unwrap(); // 320x240 red
    w.gp1(&[0x0800_0001]).unwrap(); // 320 wide
    w.vsync(VsyncTime::None).unwrap();
    w.gp1(&[0x0300_0000]).unwrap(); // display on
    w.vsync(VsyncTime::None).unwrap();
    let dump = Dump::from_bytes(w.into_inner()).unwrap();
    let mut p = Player::new(&dump, VideoStandard::Ntsc);
    let f0 = p.run_frame().unwrap().unwrap();
    assert!(!f0.display_enabled);
    let img = p.displayed_image(Expand::Replicate).unwrap();
    assert_eq!(img.dimensions(), (320, 240));
    assert_eq!(img.get_pixel(5, 5).0, [0, 0, 0]);
    p.run_frame().unwrap().unwrap();
    let img = p.displayed_image(Expand::Replicate).unwrap();
    assert_eq!(img.get_pixel(5, 5).0, [255, 0, 0]);
}
