//! `wobble render --zoom`: regions of the frame cropped and scaled up nearest-neighbour, so
//! that single pixels (dithering, a vertex snapped to a whole pixel, a one-pixel crack)
//! can be seen.

/// Most regions one command zooms.
pub const MAX_REGIONS: usize = 8;
/// Largest `--zoom-scale`.
pub const MAX_SCALE: u32 = 8;
/// Rows of background between two zoomed regions stacked in one image, and columns at the
/// right of the image (which part it from the reference's beside it with --compare).
pub const GAP: u32 = 4;

/// A rectangle of the screen in pixels: left, top, width, height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width in pixels (at least 1).
    pub w: u32,
    /// Height in pixels (at least 1).
    pub h: u32,
}

/// Parse `X,Y,W,H` (pixels of one screen, before any --compare doubling).
pub fn parse_region(text: &str) -> Result<Region, String> {
    let err = || format!("--zoom: expected X,Y,W,H in pixels (W and H at least 1), got `{text}`");
    let parts: Vec<u32> = text
        .split(',')
        .map(|p| p.trim().parse::<u32>().map_err(|_| err()))
        .collect::<Result<_, _>>()?;
    match parts[..] {
        [x, y, w, h] if w > 0 && h > 0 => Ok(Region { x, y, w, h }),
        _ => Err(err()),
    }
}

/// Refuse a region that does not lie wholly inside a `width` x `height` screen.
pub fn check_region(r: Region, width: u32, height: u32) -> Result<(), String> {
    let inside = r.x.checked_add(r.w).is_some_and(|right| right <= width)
        && r.y.checked_add(r.h).is_some_and(|bottom| bottom <= height);
    if inside {
        Ok(())
    } else {
        Err(format!(
            "--zoom {},{},{},{}: the region (columns {}..{}, rows {}..{}) is not inside the \
             {width}x{height} screen",
            r.x,
            r.y,
            r.w,
            r.h,
            r.x,
            u64::from(r.x) + u64::from(r.w),
            r.y,
            u64::from(r.y) + u64::from(r.h),
        ))
    }
}

/// Size of the image `zoom` makes of `regions` at `scale`: the widest region and `GAP`
/// columns, the regions stacked top to bottom with `GAP` rows between them.
pub fn zoomed_size(regions: &[Region], scale: u32) -> (u32, u32) {
    let w = regions.iter().map(|r| r.w * scale).max().unwrap_or(0) + GAP;
    let h = regions.iter().map(|r| r.h * scale).sum::<u32>()
        + GAP * u32::try_from(regions.len().saturating_sub(1)).unwrap_or(0);
    (w, h)
}

/// Each region of `img` scaled up `scale` times nearest-neighbour (output pixel (x, y) of a
/// region is its source pixel (x / scale, y / scale)), stacked top to bottom on black
/// (`zoomed_size`).
/// Regions must have passed `check_region` for `img`'s size; pixels outside it stay black.
pub fn zoom(img: &image::RgbImage, regions: &[Region], scale: u32) -> image::RgbImage {
    let (w, h) = zoomed_size(regions, scale);
    let mut out = image::RgbImage::from_pixel(w, h, image::Rgb([0, 0, 0]));
    let mut top = 0;
    for r in regions {
        for oy in 0..r.h * scale {
            for ox in 0..r.w * scale {
                if let Some(p) = img.get_pixel_checked(r.x + ox / scale, r.y + oy / scale) {
                    out.put_pixel(ox, top + oy, *p);
                }
            }
        }
        top += r.h * scale + GAP;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_parse_and_are_checked_against_the_screen() {
        assert_eq!(
            parse_region("1, 2,3,4"),
            Ok(Region {
                x: 1,
                y: 2,
                w: 3,
                h: 4
            })
        );
        for bad in ["1,2,3", "1,2,3,4,5", "1,2,0,4", "a,2,3,4", "-1,2,3,4", ""] {
            assert!(parse_region(bad).unwrap_err().contains("--zoom"), "{bad}");
        }
        let r = |x, y, w, h| Region { x, y, w, h };
        assert!(check_region(r(0, 0, 320, 240), 320, 240).is_ok());
        assert!(check_region(r(300, 0, 21, 10), 320, 240).is_err());
        assert!(check_region(r(0, 231, 10, 10), 320, 240).is_err());
        assert!(check_region(r(u32::MAX, 0, 1, 1), 320, 240).is_err());
        let msg = check_region(r(310, 5, 20, 10), 320, 240).unwrap_err();
        assert!(
            msg.contains("columns 310..330") && msg.contains("320x240"),
            "{msg}"
        );
    }
}
