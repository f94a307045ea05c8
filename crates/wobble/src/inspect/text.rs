//! How the report writes what [`gpu::decode`] decodes: each field's name and value, the
//! command classes and the rasterizer's drop reasons.

use gpu::decode::{Class, DropReason, Field, Flags, Texture};
use gpu::gp1::Gp1;
use gpu::{BlendMode, TextureDepth};

/// `(name, value)` rows of one decoded field, in the order the page lists them. A
/// texture gives up to three rows (page, CLUT, raw).
pub(super) fn field_rows(field: &Field, rows: &mut Vec<(String, String)>) {
    let mut row = |name: &str, value: String| rows.push((name.to_string(), value));
    let point = |x: i64, y: i64| format!("({x}, {y})");
    let on_off = |b: bool| if b { "on" } else { "off" }.to_string();
    match *field {
        Field::VertexColor { vertex, rgb } => row(&format!("color {vertex}"), hex_color(rgb)),
        Field::Vertex { vertex, x, y, uv } => {
            row(&format!("vertex {vertex}"), vertex_text(x, y, uv))
        }
        Field::Color(rgb) => row("color", hex_color(rgb)),
        Field::Position { x, y, uv } => row("position", vertex_text(x, y, uv)),
        Field::Size { width, height } => row("size", format!("{width}x{height}")),
        Field::Texture(t) => texture_rows(&t, &mut row),
        Field::TextureDisabled => row("texture", "disabled (E1.11)".into()),
        Field::Blend(b) => row("blend", blend_name(b).into()),
        Field::Flags(f) => row("flags", flags_text(&f)),
        Field::Segments(n) => row("segments", n.to_string()),
        Field::Source { x, y } => row("source", point(x.into(), y.into())),
        Field::Destination { x, y } => row("destination", point(x.into(), y.into())),
        Field::DataWords(n) => row("data words", n.to_string()),
        Field::Texpage { x, y, depth } => row("texpage", page_text(x, y, depth)),
        Field::Dither(b) => row("dither", on_off(b)),
        Field::DrawToDisplay(b) => row("draw to display", on_off(b)),
        Field::TextureDisable(b) => row("texture disable", on_off(b)),
        Field::FlipX(b) => row("flip X", on_off(b)),
        Field::FlipY(b) => row("flip Y", on_off(b)),
        Field::WindowMask { x, y } => row("mask", format!("({x}, {y}) x8")),
        Field::WindowOffset { x, y } => row("offset", format!("({x}, {y}) x8")),
        Field::AreaTopLeft { x, y } => row("top-left", point(x.into(), y.into())),
        Field::AreaBottomRight { x, y } => row("bottom-right", point(x.into(), y.into())),
        Field::DrawingOffset { x, y } => row("offset", point(x.into(), y.into())),
        Field::SetMask(b) => row("set bit 15", on_off(b)),
        Field::CheckMask(b) => row("skip masked", on_off(b)),
        Field::Words(n) => row("words", n.to_string()),
        Field::Gp1(command) => gp1_rows(command, &mut row),
    }
}

/// The rows of a GP1 command's fields; none for a command without fields.
fn gp1_rows(command: Gp1, row: &mut impl FnMut(&str, String)) {
    match command {
        Gp1::DisplayEnabled(on) => row("display", if on { "on" } else { "off" }.into()),
        Gp1::DmaDirection(d) => row("direction", d.to_string()),
        Gp1::DisplayStart { x, y } => row("start", format!("({x}, {y})")),
        Gp1::HorizontalRange { x1, x2 } => row("x1..x2", format!("{x1}..{x2}")),
        Gp1::VerticalRange { y1, y2 } => row("y1..y2", format!("{y1}..{y2}")),
        Gp1::DisplayMode(bits) => row("mode bits", format!("{bits:02x}h")),
        Gp1::AllowTextureDisable(b) => row("allowed", u8::from(b).to_string()),
        Gp1::GetInfo(r) => row("register", r.to_string()),
        Gp1::Reset | Gp1::ResetCommandBuffer | Gp1::AcknowledgeIrq | Gp1::Unused(_) => {}
    }
}

fn texture_rows(t: &Texture, row: &mut impl FnMut(&str, String)) {
    row("texpage", page_text(t.page_x, t.page_y, t.depth));
    if t.depth != TextureDepth::Direct15 {
        row("clut", format!("({}, {})", t.clut_x, t.clut_y));
    }
    if t.raw {
        row("raw texture", "yes (unmodulated)".into());
    }
}

fn hex_color(rgb: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2])
}

fn vertex_text(x: i32, y: i32, uv: Option<(u8, u8)>) -> String {
    match uv {
        Some((u, v)) => format!("({x}, {y}) uv ({u}, {v})"),
        None => format!("({x}, {y})"),
    }
}

fn page_text(x: u16, y: u16, depth: TextureDepth) -> String {
    let depth = match depth {
        TextureDepth::Clut4 => "4-bit CLUT",
        TextureDepth::Clut8 => "8-bit CLUT",
        TextureDepth::Direct15 => "15-bit direct",
    };
    format!("({x}, {y}) {depth}")
}

fn blend_name(b: BlendMode) -> &'static str {
    match b {
        BlendMode::Average => "0: B/2+F/2",
        BlendMode::Add => "1: B+F",
        BlendMode::Subtract => "2: B-F",
        BlendMode::AddQuarter => "3: B+F/4",
    }
}

/// The flags that are set, comma-separated; `-` for none.
fn flags_text(f: &Flags) -> String {
    let names = [
        (f.gouraud, "Gouraud"),
        (f.textured, "textured"),
        (f.semi_transparent, "semi-transparent"),
        (f.dithered, "dithered"),
        (f.flip_x, "flip X"),
        (f.flip_y, "flip Y"),
        (f.mask_set, "mask set"),
        (f.mask_check, "mask check"),
    ];
    let set: Vec<&str> = names
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, n)| *n)
        .collect();
    if set.is_empty() {
        "-".into()
    } else {
        set.join(", ")
    }
}

/// The class's name in a row's data.
pub(super) fn class_name(class: Class) -> &'static str {
    match class {
        Class::Draw => "draw",
        Class::Transfer => "transfer",
        Class::Environment => "environment",
        Class::Display => "display",
        Class::Other => "other",
    }
}

/// Why the rasterizer dropped a primitive, in a few words.
pub(super) fn drop_reason(r: DropReason) -> &'static str {
    match r {
        DropReason::SizeLimit => "size limit: a vertex pair is >= 1024 apart in X or >= 512 in Y",
        DropReason::ZeroArea => "zero area",
        DropReason::Clipped => "clipped away: outside the drawing area",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(f: Field) -> Vec<(String, String)> {
        let mut out = Vec::new();
        field_rows(&f, &mut out);
        out
    }

    fn pair(name: &str, value: &str) -> (String, String) {
        (name.to_string(), value.to_string())
    }

    #[test]
    fn texture_rows_follow_the_depth() {
        let t = Texture {
            page_x: 640,
            page_y: 256,
            depth: TextureDepth::Clut4,
            clut_x: 16,
            clut_y: 500,
            raw: true,
        };
        assert_eq!(
            rows(Field::Texture(t)),
            [
                pair("texpage", "(640, 256) 4-bit CLUT"),
                pair("clut", "(16, 500)"),
                pair("raw texture", "yes (unmodulated)")
            ]
        );
        let direct = Texture {
            depth: TextureDepth::Direct15,
            raw: false,
            ..t
        };
        assert_eq!(
            rows(Field::Texture(direct)),
            [pair("texpage", "(640, 256) 15-bit direct")]
        );
    }

    #[test]
    fn values() {
        assert_eq!(
            rows(Field::Vertex {
                vertex: 2,
                x: -3,
                y: 7,
                uv: Some((1, 255))
            }),
            [pair("vertex 2", "(-3, 7) uv (1, 255)")]
        );
        assert_eq!(
            rows(Field::VertexColor {
                vertex: 1,
                rgb: [0xFF, 0x80, 0]
            }),
            [pair("color 1", "#ff8000")]
        );
        assert_eq!(rows(Field::Flags(Flags::default())), [pair("flags", "-")]);
        let f = Flags {
            gouraud: true,
            dithered: true,
            mask_check: true,
            ..Flags::default()
        };
        assert_eq!(
            rows(Field::Flags(f)),
            [pair("flags", "Gouraud, dithered, mask check")]
        );
        let gp1 = |g| rows(Field::Gp1(g));
        assert_eq!(gp1(Gp1::DisplayMode(1)), [pair("mode bits", "01h")]);
        assert_eq!(gp1(Gp1::DisplayEnabled(false)), [pair("display", "off")]);
        assert_eq!(
            gp1(Gp1::DisplayStart { x: 0, y: 256 }),
            [pair("start", "(0, 256)")]
        );
        assert_eq!(gp1(Gp1::AcknowledgeIrq), []);
    }
}
