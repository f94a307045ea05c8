//! `wobble render --compare`: the hardware pipeline and the reference renderer side by side,
//! each half labelled in the image with the public-domain 8x8 bitmap font of `font8x8`.

use font8x8::legacy::BASIC_LEGACY;

/// Label of the left half (the hardware pipeline).
pub const LEFT_LABEL: &str = "PS1: GTE + GPU";
/// Label of the right half (the f64 reference renderer).
pub const RIGHT_LABEL: &str = "reference: perspective, sub-pixel";

/// Glyph size in pixels.
pub const GLYPH: u32 = 8;
/// Margin around a label, inside its dark box.
pub const LABEL_MARGIN: u32 = 2;
/// Label text colour.
pub const LABEL_INK: [u8; 3] = [255, 255, 255];
/// Label box colour.
pub const LABEL_BOX: [u8; 3] = [0, 0, 0];

/// Draw `text` at (`x`, `y`) (top-left of its box) on a dark box: ASCII only (other
/// characters draw as `?`), clipped to the image.
pub fn label(img: &mut image::RgbImage, x: u32, y: u32, text: &str) {
    let chars = u32::try_from(text.chars().count()).unwrap_or(u32::MAX);
    let box_w = chars.saturating_mul(GLYPH).saturating_add(2 * LABEL_MARGIN);
    let box_h = GLYPH + 2 * LABEL_MARGIN;
    for by in y..y.saturating_add(box_h).min(img.height()) {
        for bx in x..x.saturating_add(box_w).min(img.width()) {
            img.put_pixel(bx, by, image::Rgb(LABEL_BOX));
        }
    }
    for (i, ch) in text.chars().enumerate() {
        let code = if ch.is_ascii() {
            ch as usize
        } else {
            b'?' as usize
        };
        let Some(glyph) = BASIC_LEGACY.get(code) else {
            continue;
        };
        let gx = x + LABEL_MARGIN + GLYPH * u32::try_from(i).unwrap_or(u32::MAX / GLYPH);
        for (row, bits) in (0u32..).zip(glyph) {
            for col in 0..GLYPH {
                // Bit 0 is the leftmost pixel of a row.
                if bits >> col & 1 == 1 {
                    let (px, py) = (gx.saturating_add(col), y + LABEL_MARGIN + row);
                    if px < img.width() && py < img.height() {
                        img.put_pixel(px, py, image::Rgb(LABEL_INK));
                    }
                }
            }
        }
    }
}

/// The hardware frame on the left, the reference frame on the right (same height), each
/// with its label in the top-left corner.
pub fn side_by_side(left: &image::RgbImage, right: &image::RgbImage) -> image::RgbImage {
    let (lw, h) = left.dimensions();
    let w = lw + right.width();
    let h = h.max(right.height());
    let mut out = image::RgbImage::from_pixel(w, h, image::Rgb([0, 0, 0]));
    for (x, y, p) in left.enumerate_pixels() {
        out.put_pixel(x, y, *p);
    }
    for (x, y, p) in right.enumerate_pixels() {
        out.put_pixel(lw + x, y, *p);
    }
    label(&mut out, 0, 0, LEFT_LABEL);
    label(&mut out, lw, 0, RIGHT_LABEL);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 'A' in the font: row 0 is 0x0C (pixels 2 and 3 set, bit 0 leftmost).
    #[test]
    fn label_draws_glyph_bits() {
        let mut img = image::RgbImage::from_pixel(40, 20, image::Rgb([9, 9, 9]));
        label(&mut img, 0, 0, "A");
        let ink = |x, y| img.get_pixel(x, y).0 == LABEL_INK;
        let (ox, oy) = (LABEL_MARGIN, LABEL_MARGIN);
        assert_eq!(BASIC_LEGACY[b'A' as usize][0], 0x0C);
        assert!(ink(ox + 2, oy) && ink(ox + 3, oy));
        assert!(!ink(ox, oy) && !ink(ox + 1, oy) && !ink(ox + 4, oy));
        // The box covers one glyph and its margins, and no more.
        let end = GLYPH + 2 * LABEL_MARGIN;
        assert_eq!(img.get_pixel(end - 1, end - 1).0, LABEL_BOX);
        assert_eq!(img.get_pixel(end, 0).0, [9, 9, 9]);
        assert_eq!(img.get_pixel(0, end).0, [9, 9, 9]);
    }
}
