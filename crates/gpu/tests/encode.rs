//! The packet encoder against the decoder: a packet built by `gpu::encode` decodes to the
//! vertices, colours, texture and flags it was built from, for any shape of polygon, line and
//! rectangle.

use gpu::command::{self, Command};
use gpu::decode::{Field, Kind};
use gpu::encode::{Line, Polygon, PolygonTexture, Rectangle, RectangleTexture, SpriteSize, Vertex};
use gpu::{BlendMode, ClutAttr, Gpu, Texpage, TextureDepth};
use proptest::prelude::*;

fn vertex() -> impl Strategy<Value = Vertex> {
    (
        -1024i16..1024,
        -1024i16..1024,
        any::<[u8; 3]>(),
        any::<u8>(),
        any::<u8>(),
    )
        .prop_map(|(x, y, color, u, v)| Vertex { x, y, color, u, v })
}

fn texpage() -> impl Strategy<Value = Texpage> {
    (0u16..16, 0u16..2, 0u32..4, 0u32..3).prop_map(|(x, y, blend, depth)| Texpage {
        page_x: x * 64,
        page_y: y * 256,
        blend: BlendMode::from_bits(blend),
        depth: TextureDepth::from_bits(depth),
        ..Texpage::default()
    })
}

fn clut() -> impl Strategy<Value = ClutAttr> {
    (0u16..64, 0u16..512).prop_map(|(x, y)| ClutAttr { x: x * 16, y })
}

/// A GPU drawing anywhere with no offset, so decoded positions are the packet's.
fn gpu() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[
        gpu::encode::area_top_left(0, 0),
        gpu::encode::area_bottom_right(1023, 511),
        gpu::encode::drawing_offset(0, 0),
    ]);
    g
}

proptest! {
    #[test]
    fn polygons_decode_to_what_was_encoded(
        vertices in prop::array::uniform4(vertex()),
        quad in any::<bool>(),
        gouraud in any::<bool>(),
        semi_transparent in any::<bool>(),
        texture in prop::option::of((clut(), texpage(), any::<bool>())),
    ) {
        let polygon = Polygon {
            vertices,
            quad,
            gouraud,
            semi_transparent,
            texture: texture.map(|(clut, page, raw)| PolygonTexture { clut, page, raw }),
        };
        let packet = polygon.packet();
        let row = Command::of(packet[0]);
        prop_assert_eq!(row.kind, command::Kind::Polygon(polygon.op()));
        prop_assert_eq!(packet.len(), row.words);
        let d = gpu().decode_gp0(&packet);
        prop_assert_eq!(d.kind, Kind::Gp0(row.kind));
        prop_assert!(d.truncated.is_none());
        let n = if quad { 4 } else { 3 };
        for (i, v) in (0u8..).zip(&vertices[..n]) {
            let uv = polygon.texture.map(|_| (v.u, v.v));
            let expected = Field::Vertex { vertex: i, x: v.x.into(), y: v.y.into(), uv };
            prop_assert!(d.fields.contains(&expected), "{:?} in {:?}", expected, d.fields);
            let color = if gouraud { v.color } else { vertices[0].color };
            let c = d.fields.iter().find_map(|f| match *f {
                Field::VertexColor { vertex, rgb } if vertex == i => Some(rgb),
                _ => None,
            });
            prop_assert!(c.is_none_or(|c| c == color));
        }
        if let Some(t) = polygon.texture {
            let decoded = d.fields.iter().find_map(|f| match f {
                Field::Texture(t) => Some(*t),
                _ => None,
            });
            let decoded = decoded.expect("texture field");
            prop_assert_eq!((decoded.clut_x, decoded.clut_y), (t.clut.x, t.clut.y));
            prop_assert_eq!((decoded.page_x, decoded.page_y), (t.page.page_x, t.page.page_y));
            prop_assert_eq!((decoded.depth, decoded.raw), (t.page.depth, t.raw));
        }
        prop_assert_eq!(
            d.fields.iter().any(|f| matches!(f, Field::Blend(_))),
            semi_transparent
        );
    }

    #[test]
    fn lines_decode_to_what_was_encoded(
        vertices in prop::array::uniform2(vertex()),
        gouraud in any::<bool>(),
        semi_transparent in any::<bool>(),
    ) {
        let line = Line { vertices, gouraud, semi_transparent };
        let d = gpu().decode_gp0(&line.packet());
        prop_assert_eq!(d.kind, Kind::Gp0(command::Kind::Line(line.op())));
        for (i, v) in (0u8..).zip(&vertices) {
            let expected = Field::Vertex { vertex: i, x: v.x.into(), y: v.y.into(), uv: None };
            prop_assert!(d.fields.contains(&expected));
        }
        let second = Field::VertexColor { vertex: 1, rgb: vertices[1].color };
        prop_assert_eq!(d.fields.contains(&second), gouraud);
    }

    #[test]
    fn rectangles_decode_to_what_was_encoded(
        at in vertex(),
        size in 0u8..4,
        (width, height) in (0u16..1024, 0u16..512),
        texture in prop::option::of((clut(), any::<bool>())),
    ) {
        let rectangle = Rectangle {
            x: at.x,
            y: at.y,
            color: at.color,
            size: SpriteSize::from_bits(size),
            width,
            height,
            semi_transparent: false,
            texture: texture.map(|(clut, raw)| RectangleTexture { clut, u: at.u, v: at.v, raw }),
        };
        let d = gpu().decode_gp0(&rectangle.packet());
        let (w, h) = rectangle.size.fixed().unwrap_or((width, height));
        let size = Field::Size { width: w.into(), height: h.into() };
        prop_assert!(d.fields.contains(&size));
        let uv = texture.map(|_| (at.u, at.v));
        let position = Field::Position { x: at.x.into(), y: at.y.into(), uv };
        prop_assert!(d.fields.contains(&position));
        prop_assert!(d.fields.contains(&Field::Color(at.color)));
    }
}

/// Fills, copies and transfers decode to their corners and sizes.
#[test]
fn transfers_decode_to_what_was_encoded() {
    let g = gpu();
    let d = g.decode_gp0(&gpu::encode::fill([1, 2, 3], 32, 100, 64, 20));
    assert_eq!(
        d.fields,
        [
            Field::Color([1, 2, 3]),
            Field::Position {
                x: 32,
                y: 100,
                uv: None
            },
            Field::Size {
                width: 64,
                height: 20
            },
        ]
    );
    let d = g.decode_gp0(&gpu::encode::copy((1, 2), (300, 400), 5, 6));
    assert_eq!(
        d.fields,
        [
            Field::Source { x: 1, y: 2 },
            Field::Destination { x: 300, y: 400 },
            Field::Size {
                width: 5,
                height: 6
            },
        ]
    );
    let mut words = gpu::encode::cpu_to_vram(640, 0, 3, 1).to_vec();
    words.extend(gpu::encode::pixel_words(&[1, 2, 3]));
    let d = g.decode_gp0(&words);
    assert!(d.fields.contains(&Field::DataWords(2)));
    assert!(d.truncated.is_none());
}
