//! `wobble render --inspect`: the report for one rendered frame, each GP0 packet traced back
//! to the object and mesh face it draws, with a table of what happened to every face.

use super::{InspectOptions, InspectSummary, Origin, write_report};
use crate::pipeline::{DropCause, FaceFate, FaceRecord, FrameTrace, PacketOrigin};
use crate::scene::Scene;
use gpu::command_stream::{Port, StreamCommand};
use std::collections::HashMap;
use std::path::Path;

fn fate_text(f: &FaceFate) -> String {
    match f {
        FaceFate::Split => "split by tessellation".into(),
        FaceFate::Culled => "culled (NCLIP: back face)".into(),
        FaceFate::Dropped(DropCause::NearPlane) => {
            "dropped: near plane (SZ3 / divide overflow / SX,SY saturated)".into()
        }
        FaceFate::Dropped(DropCause::SizeLimit) => "dropped: larger than the GPU draws".into(),
        FaceFate::Offscreen => "off screen".into(),
        FaceFate::Overflow => "dropped: polygon list full".into(),
        FaceFate::Drawn { ot_slot } => format!("drawn, OT slot {ot_slot}"),
    }
}

fn object_name(scene: &Scene, r: &FaceRecord) -> String {
    let mesh = scene
        .objects
        .get(r.object)
        .and_then(|o| scene.meshes.get(o.mesh))
        .map_or_else(String::new, |m| format!(" ({})", m.name));
    format!("object {}{mesh}", r.object)
}

/// Write the report of a traced frame: the commands are the frame's GP0 packets (one a
/// line, in the order the GPU received them) and the GP1 display word.
pub fn write_frame_report(
    scene: &Scene,
    trace: &FrameTrace,
    out: &Path,
    title: &str,
    options: InspectOptions,
) -> Result<InspectSummary, String> {
    let mut commands = Vec::with_capacity(trace.packets.len() + 1);
    let mut origins = HashMap::new();
    let mut line_of_face = HashMap::new();
    for (i, packet) in trace.packets.iter().enumerate() {
        let line = i + 1;
        commands.push(StreamCommand {
            line,
            port: Port::Gp0,
            words: packet.words.clone(),
        });
        let face = |f: usize| trace.faces.get(f).map(|r| (f, r));
        let text = match packet.origin {
            Some(PacketOrigin::Face(f)) if let Some((f, r)) = face(f) => {
                line_of_face.insert(f, line);
                format!(
                    "{}, face {}{}; {}",
                    object_name(scene, r),
                    r.face,
                    if r.level > 0 {
                        format!(" (tessellation level {})", r.level)
                    } else {
                        String::new()
                    },
                    fate_text(&r.fate)
                )
            }
            Some(PacketOrigin::Environment) => {
                "frame set-up: drawing environment and background fill".into()
            }
            Some(PacketOrigin::BlendMode(_)) => "blend-mode E1 for the polygon drawn next".into(),
            Some(PacketOrigin::Face(_)) | None => "a packet of the ordering table".into(),
        };
        origins.insert(line, Origin { text });
    }
    commands.push(StreamCommand {
        line: trace.packets.len() + 1,
        port: Port::Gp1,
        words: vec![trace.display_word],
    });
    let columns = ["#", "object", "face", "level", "fate", "packet line"];
    let rows: Vec<Vec<String>> = trace
        .faces
        .iter()
        .enumerate()
        .map(|(i, r)| {
            vec![
                i.to_string(),
                object_name(scene, r),
                r.face.to_string(),
                r.level.to_string(),
                fate_text(&r.fate),
                line_of_face
                    .get(&i)
                    .map_or_else(String::new, |l| l.to_string()),
            ]
        })
        .collect();
    let mut gpu = trace.gpu_before.clone();
    write_report(
        &mut gpu,
        &commands,
        out,
        title,
        options,
        Some(&origins),
        Some((&columns, &rows)),
    )
}
