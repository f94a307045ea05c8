//! The trade report's images that are not renders: the error-against-cost chart of the
//! tessellation levels, drawn with plotters and labelled in DejaVu Sans (the font's bytes
//! and licence are in crates/wobble/assets/, so drawing never looks for a system font).

use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::sync::OnceLock;

/// DejaVu Sans 2.37 (Bitstream Vera licence, crates/wobble/assets/DejaVuSans-LICENSE.txt).
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// The family name the charts ask plotters for; the bundled font is registered under it.
pub(crate) const FAMILY: &str = "sans-serif";

/// Chart size in pixels.
const SIZE: (u32, u32) = (640, 420);

/// Register the bundled font with plotters once per process; `false` when the font bytes
/// cannot be parsed.
pub(crate) fn font_registered() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, FONT).is_ok())
}

/// The error-against-cost chart of the tessellation levels: one dot per `(level, frame ms,
/// mean texel error)` point, joined in the given order, each labelled with its level number; both
/// axes start at zero and carry their quantity and unit. The error is the charting
/// library's message.
pub fn curve_image(points: &[(u8, f64, f64)]) -> Result<image::RgbImage, String> {
    if !font_registered() {
        return Err("the bundled chart font (DejaVuSans.ttf) could not be read".into());
    }
    let finite = |v: f64| if v.is_finite() { v } else { 0.0 };
    let max_x = points.iter().map(|p| finite(p.1)).fold(1e-9, f64::max) * 1.15;
    let max_y = points.iter().map(|p| finite(p.2)).fold(1e-9, f64::max) * 1.15;
    let (w, h) = SIZE;
    let mut buffer = vec![255u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Error against cost, by tessellation level",
                (FAMILY, 22).into_font(),
            )
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(0.0..max_x, 0.0..max_y)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("frame time (ms per frame)")
            .y_desc("mean texel error (texels)")
            .label_style((FAMILY, 15).into_font())
            .axis_desc_style((FAMILY, 17).into_font())
            .x_label_formatter(&|v| format!("{v:.2}"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .draw()
            .map_err(|e| e.to_string())?;
        let xy: Vec<(f64, f64)> = points.iter().map(|p| (finite(p.1), finite(p.2))).collect();
        chart
            .draw_series(LineSeries::new(
                xy.iter().copied(),
                RGBColor(40, 90, 200).stroke_width(2),
            ))
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(
                xy.iter()
                    .map(|&p| Circle::new(p, 5, RGBColor(200, 40, 40).filled())),
            )
            .map_err(|e| e.to_string())?;
        let label_style = TextStyle::from((FAMILY, 15).into_font()).color(&BLACK);
        chart
            .draw_series(points.iter().zip(&xy).map(|(p, &at)| {
                EmptyElement::at(at) + Text::new(p.0.to_string(), (7, -20), label_style.clone())
            }))
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    image::RgbImage::from_raw(w, h, buffer)
        .ok_or_else(|| "chart buffer does not match its size".to_string())
}

/// Height of the label strip above [`side_by_side`]'s images.
pub const LABEL_STRIP: u32 = 24;

/// Two images next to each other with an 8-pixel white gap, each under its label (black text
/// on a white strip [`LABEL_STRIP`] pixels high); pixels outside either image are white.
pub(crate) fn side_by_side(
    a: &image::RgbImage,
    b: &image::RgbImage,
    labels: [&str; 2],
) -> Result<image::RgbImage, String> {
    if !font_registered() {
        return Err("the bundled chart font (DejaVuSans.ttf) could not be read".into());
    }
    let white = image::Rgb([255, 255, 255]);
    let (w, h) = a.dimensions();
    let top = LABEL_STRIP;
    let size = (w * 2 + 8, h.max(b.height()) + top);
    let img = image::RgbImage::from_fn(size.0, size.1, |x, y| {
        let pixel = if y < top {
            None
        } else if x < w {
            a.get_pixel_checked(x, y - top)
        } else if x < w + 8 {
            None
        } else {
            b.get_pixel_checked(x - w - 8, y - top)
        };
        pixel.copied().unwrap_or(white)
    });
    let mut buffer = img.into_raw();
    {
        let root = BitMapBackend::with_buffer(&mut buffer, size).into_drawing_area();
        let style = TextStyle::from((FAMILY, 15).into_font()).color(&BLACK);
        for (label, x) in labels.iter().zip([4, w as i32 + 12]) {
            root.draw(&Text::new(label.to_string(), (x, 4), style.clone()))
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    image::RgbImage::from_raw(size.0, size.1, buffer)
        .ok_or_else(|| "side-by-side buffer does not match its size".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chart is drawn at its size, and the labels put dark pixels to the left of the
    /// y axis and below the x axis (the hand-made plotter it replaces drew only digits).
    #[test]
    fn chart_has_labelled_axes() {
        let img = curve_image(&[(0, 0.27, 6.3), (1, 0.31, 2.6), (2, 0.35, 2.0)]).unwrap();
        assert_eq!(img.dimensions(), SIZE);
        let dark = |x0: u32, x1: u32, y0: u32, y1: u32| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| img.get_pixel(x, y).0.iter().all(|&c| c < 100))
                .count()
        };
        // The y-axis description runs vertically along the left edge.
        assert!(dark(0, 30, 100, 350) > 50, "y-axis description");
        // The x-axis description sits along the bottom edge.
        assert!(dark(150, 500, 390, 420) > 50, "x-axis description");
        // The caption is along the top.
        assert!(dark(100, 540, 0, 40) > 100, "caption");
    }

    #[test]
    fn empty_and_non_finite_points_still_draw() {
        assert!(curve_image(&[]).is_ok());
        assert!(curve_image(&[(0, f64::NAN, f64::INFINITY)]).is_ok());
    }

    /// Both images under the label strip with a white gap between, and each label's text
    /// (dark pixels) above its own image only.
    #[test]
    fn side_by_side_labels_each_half() {
        let a = image::RgbImage::from_pixel(200, 20, image::Rgb([1, 2, 3]));
        let b = image::RgbImage::from_pixel(200, 30, image::Rgb([4, 5, 6]));
        let s = side_by_side(&a, &b, ["left half", "right half"]).unwrap();
        let top = LABEL_STRIP;
        assert_eq!(s.dimensions(), (408, 30 + top));
        assert_eq!(s.get_pixel(2, top + 1).0, [1, 2, 3]);
        assert_eq!(s.get_pixel(203, top + 1).0, [255, 255, 255]);
        assert_eq!(s.get_pixel(300, top + 2).0, [4, 5, 6]);
        assert_eq!(
            s.get_pixel(0, top + 25).0,
            [255, 255, 255],
            "below the shorter"
        );
        let dark = |x0: u32, x1: u32| {
            (0..top)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| s.get_pixel(x, y).0.iter().all(|&c| c < 100))
                .count()
        };
        assert!(dark(0, 100) > 40, "left label");
        assert!(dark(208, 308) > 40, "right label");
        assert_eq!(dark(100, 208), 0, "the left label stays over its half");
    }
}
