//! The texel-error heat maps of the trade report: one colour per pixel from the error's size,
//! a colour bar under each map, and the caption's words for the colours, all taken from one
//! table ([`HEAT_STOPS`]) so the caption names the colours that are drawn.

use super::charts::{FAMILY, font_registered};
use super::texel_error::texel_error;
use crate::reference::ReferenceFrame;
use plotters::prelude::*;

/// The colour scale: (texel error, colour, its name), errors increasing; linear in between,
/// and the last colour for every larger error.
pub const HEAT_STOPS: [(f64, [u8; 3], &str); 3] = [
    (0.0, [0, 0, 0], "black"),
    (4.0, [255, 0, 0], "red"),
    (8.0, [255, 255, 0], "yellow"),
];

/// Pixels with no comparison (no textured surface in the hardware image or in the
/// reference), and the colour's name.
pub const NO_SURFACE: ([u8; 3], &str) = ([0, 70, 160], "blue");

/// Height of the colour bar under a heat map, in pixels.
pub const BAR_HEIGHT: u32 = 40;

/// The colour of a texel error of `e` texels (NaN as 0).
pub fn heat_colour(e: f64) -> [u8; 3] {
    let e = if e.is_nan() { 0.0 } else { e };
    let mut below = HEAT_STOPS[0];
    for stop in HEAT_STOPS {
        if e <= stop.0 {
            let span = stop.0 - below.0;
            let t = if span > 0.0 {
                (e - below.0) / span
            } else {
                1.0
            };
            return std::array::from_fn(|c| {
                let (a, b) = (f64::from(below.1[c]), f64::from(stop.1[c]));
                (a + (b - a) * t).round() as u8
            });
        }
        below = stop;
    }
    below.1
}

/// Per-pixel texel error image: [`heat_colour`] of the texel error where both images show
/// a textured surface, [`NO_SURFACE`] elsewhere.
pub fn heat_map(hw: &[u16], reference: &ReferenceFrame, scale: i32) -> image::RgbImage {
    image::RgbImage::from_fn(reference.width as u32, reference.height as u32, |x, y| {
        let i = y as usize * reference.width + x as usize;
        let error = hw.get(i).and_then(|&p| {
            let texel = reference.texel.get(i).copied().flatten();
            let size = reference.texture_size.get(i).copied().flatten();
            texel_error(p, texel, size, scale)
        });
        image::Rgb(error.map_or(NO_SURFACE.0, heat_colour))
    })
}

/// The caption's words for the colours: every stop by name and error, then the no-surface
/// colour.
pub fn colour_words() -> String {
    let last = HEAT_STOPS.len() - 1;
    let stops: Vec<String> = HEAT_STOPS
        .iter()
        .enumerate()
        .map(|(i, (e, _, name))| match i {
            0 => format!("{name}: exact"),
            i if i == last => format!("{name}: {e} texels and more"),
            _ => format!("{name}: {e} texels"),
        })
        .collect();
    format!(
        "{}, blended in between; {}: no textured surface in one of the two",
        stops.join(", "),
        NO_SURFACE.1
    )
}

/// First and one-past-last column of the gradient in a bar `width` pixels wide: its last
/// column is a multiple of 16 columns from its first, so that every stop falls on a column
/// (the no-surface swatch and its label take the right part).
pub fn bar_span(width: u32) -> (u32, u32) {
    let steps = (width.saturating_sub(128) / 16).max(1) * 16;
    (8, 8 + steps + 1)
}

/// The colour bar: the gradient from 0 to the last stop's error, ticks labelled at every
/// stop (the last with the unit), and the no-surface swatch, on white, `width` x
/// [`BAR_HEIGHT`].
pub fn colour_bar(width: u32) -> Result<image::RgbImage, String> {
    if !font_registered() {
        return Err("the bundled chart font (DejaVuSans.ttf) could not be read".into());
    }
    let width = width.max(160);
    let (x0, x1) = bar_span(width);
    let top_error = HEAT_STOPS[HEAT_STOPS.len() - 1].0;
    let mut img = image::RgbImage::from_pixel(width, BAR_HEIGHT, image::Rgb([255, 255, 255]));
    for x in x0..x1 {
        let e = f64::from(x - x0) / f64::from(x1 - x0 - 1).max(1.0) * top_error;
        for y in 4..16 {
            img.put_pixel(x, y, image::Rgb(heat_colour(e)));
        }
    }
    let swatch = x1 + 12;
    for x in swatch..(swatch + 12).min(width) {
        for y in 4..16 {
            img.put_pixel(x, y, image::Rgb(NO_SURFACE.0));
        }
    }
    let mut buffer = img.into_raw();
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (width, BAR_HEIGHT)).into_drawing_area();
        let style = TextStyle::from((FAMILY, 12).into_font()).color(&BLACK);
        let last = HEAT_STOPS.len() - 1;
        for (i, (e, _, _)) in HEAT_STOPS.iter().enumerate() {
            let x = x0 as f64 + e / top_error * f64::from(x1 - x0 - 1);
            let x = x as i32;
            root.draw(&PathElement::new(vec![(x, 16), (x, 20)], BLACK))
                .map_err(|e| e.to_string())?;
            let label = if i == last {
                format!("{e}+ texels")
            } else {
                format!("{e}")
            };
            root.draw(&Text::new(label, (x - 3, 22), style.clone()))
                .map_err(|e| e.to_string())?;
        }
        root.draw(&Text::new(
            "no surface".to_string(),
            (swatch as i32 + 16, 3),
            style,
        ))
        .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    image::RgbImage::from_raw(width, BAR_HEIGHT, buffer)
        .ok_or_else(|| "colour bar buffer does not match its size".to_string())
}

/// A heat map with its colour bar underneath.
pub fn with_colour_bar(map: &image::RgbImage) -> Result<image::RgbImage, String> {
    let bar = colour_bar(map.width())?;
    let (w, h) = (map.width().max(bar.width()), map.height() + bar.height());
    Ok(image::RgbImage::from_fn(w, h, |x, y| {
        if y < map.height() {
            map.get_pixel_checked(x, y).copied()
        } else {
            bar.get_pixel_checked(x, y - map.height()).copied()
        }
        .unwrap_or(image::Rgb([255, 255, 255]))
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The colour names mean what they say: black is 0,0,0, red 255,0,0, yellow 255,255,0,
    /// and blue has blue well above red and green.
    #[test]
    fn colour_names_match_their_colours() {
        let meaning = |name: &str| match name {
            "black" => Some([0, 0, 0]),
            "red" => Some([255, 0, 0]),
            "yellow" => Some([255, 255, 0]),
            _ => None,
        };
        for (_, rgb, name) in HEAT_STOPS {
            assert_eq!(meaning(name), Some(rgb), "{name}");
        }
        let [r, g, b] = NO_SURFACE.0;
        assert_eq!(NO_SURFACE.1, "blue");
        assert!(b > 2 * r.max(g), "{:?}", NO_SURFACE.0);
        let words = colour_words();
        assert_eq!(
            words,
            "black: exact, red: 4 texels, yellow: 8 texels and more, blended in between; \
             blue: no textured surface in one of the two"
        );
    }

    /// Errors map onto the stops exactly, halfway between two stops halfway between their
    /// colours, and past the last stop to the last colour.
    #[test]
    fn colours_follow_the_stops() {
        assert_eq!(heat_colour(0.0), [0, 0, 0]);
        assert_eq!(heat_colour(2.0), [128, 0, 0]);
        assert_eq!(heat_colour(4.0), [255, 0, 0]);
        assert_eq!(heat_colour(6.0), [255, 128, 0]);
        assert_eq!(heat_colour(8.0), [255, 255, 0]);
        assert_eq!(heat_colour(45.0), [255, 255, 0]);
        assert_eq!(heat_colour(f64::NAN), [0, 0, 0]);
    }

    /// The bar under a 320-pixel map: its gradient shows each stop's colour where its tick
    /// is, the no-surface swatch, and labels (dark pixels) under the gradient.
    #[test]
    fn colour_bar_shows_the_stops_and_the_swatch() {
        let bar = colour_bar(320).unwrap();
        assert_eq!(bar.dimensions(), (320, BAR_HEIGHT));
        let (x0, x1) = bar_span(320);
        assert_eq!(bar.get_pixel(x0, 10).0, HEAT_STOPS[0].1);
        assert_eq!(bar.get_pixel((x0 + x1 - 1) / 2, 10).0, HEAT_STOPS[1].1);
        assert_eq!(bar.get_pixel(x1 - 1, 10).0, HEAT_STOPS[2].1);
        assert_eq!(bar.get_pixel(x1 + 14, 10).0, NO_SURFACE.0);
        let dark = (20..BAR_HEIGHT)
            .flat_map(|y| (0..320).map(move |x| (x, y)))
            .filter(|&(x, y)| bar.get_pixel(x, y).0.iter().all(|&c| c < 100))
            .count();
        assert!(dark > 30, "tick labels: {dark} dark pixels");
        let map = image::RgbImage::from_pixel(320, 10, image::Rgb([1, 2, 3]));
        let both = with_colour_bar(&map).unwrap();
        assert_eq!(both.dimensions(), (320, 10 + BAR_HEIGHT));
        assert_eq!(both.get_pixel(5, 9).0, [1, 2, 3]);
        assert_eq!(both.get_pixel(x0, 10 + 10).0, HEAT_STOPS[0].1);
    }
}
