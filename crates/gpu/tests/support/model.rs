//! A per-pixel model of docs/hardware/gpu.md §3 for the property tests (`rasterizer.rs`,
//! `fast_paths.rs`), written from the fact sheet's rules rather than from the rasterizer's
//! edge walk: every pixel of the bounding box is tested on its own against the three edge
//! functions, in exact i64 arithmetic, and its attributes are evaluated directly from the
//! plane equation.
//!
//! Coverage (§3.4, §3.5): pixel (x, y) is sampled at the integer point (x, y). The walk's
//! 32.32 edges start at x + 1 - 2^-21 and step by at most 2^-32 away from the exact slope per
//! row, an error below 2^-22 over 511 rows, while a non-integer edge crossing is at least
//! 1/511 from an integer: so `int(edge)` is exactly `ceil(exact edge)`, and the span rule
//! `int(left) <= x < int(right)` on rows `y0 <= y < y2` is the top-left rule on the exact
//! triangle: a point inside is drawn; a point on an edge is drawn when that edge is a left
//! edge (the inside lies to its right) or a horizontal top edge (the inside lies below it).
//!
//! Attributes (§3.6): the 8.24 value at pixel (x, y) is `core + d/dx (x - x_core) + d/dy
//! (y - y_core)` with 32-bit wrap-around; adding d/dx once per pixel along the span gives the
//! same sum modulo 2^32. The gradient quotients do not depend on the vertex order (numerator
//! and `den` change sign together under a swap, and truncating division is odd), so the
//! vertices are used as given; the core vertex follows the §3.3 rule on X alone.

pub struct V {
    pub x: i64,
    pub y: i64,
    /// R, G, B, U, V.
    pub a: [i64; 5],
}

const DITHER: [[i64; 4]; 4] = [
    [-4, 0, -3, 1],
    [2, -2, 3, -1],
    [-3, 1, -4, 0],
    [3, -1, 2, -2],
];

/// Positions wrap to signed 11 bits (§3.5).
fn sext11(v: i64) -> i64 {
    let v = v.rem_euclid(2048);
    if v >= 1024 { v - 2048 } else { v }
}

/// What one pixel receives: colour attributes and the UV pair (8-bit each).
pub struct Px {
    pub x: i64,
    pub y: i64,
    pub attr: [u32; 5],
}

/// Twice the signed area of (p, q, r): positive when r lies clockwise of p -> q on a
/// y-down screen.
fn edge(p: (i64, i64), q: (i64, i64), r: (i64, i64)) -> i64 {
    (q.0 - p.0) * (r.1 - p.1) - (q.1 - p.1) * (r.0 - p.0)
}

/// The rows a triangle walks inside `clip` (x0, y0, x1, y1 inclusive), for the drawing
/// time (docs/emulator.md, "Drawing time"): those from its top vertex down to, not
/// including, its bottom vertex, inside the clip's rows and kept by `keep`; none when it is
/// dropped (size limit, zero area, or a bounding box outside the clip; §3.2, §3.6).
#[allow(dead_code)]
pub fn rows(input: &[V; 3], clip: (i64, i64, i64, i64), keep: impl Fn(i64) -> bool) -> u32 {
    let v = [0, 1, 2].map(|i| (sext11(input[i].x), sext11(input[i].y)));
    let xs = v.map(|p| p.0);
    let ys = v.map(|p| p.1);
    let (min_x, max_x) = (*xs.iter().min().unwrap(), *xs.iter().max().unwrap());
    let (min_y, max_y) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
    let outside = max_x < clip.0 || min_x > clip.2 || max_y < clip.1 || min_y > clip.3;
    let empty = clip.0 > clip.2 || clip.1 > clip.3;
    if max_x - min_x >= 1024
        || max_y - min_y >= 512
        || edge(v[0], v[1], v[2]) == 0
        || outside
        || empty
    {
        return 0;
    }
    (min_y.max(clip.1)..max_y.min(clip.3 + 1))
        .filter(|&y| keep(y))
        .count() as u32
}

/// Every pixel the triangle draws inside `clip` (x0, y0, x1, y1 inclusive).
pub fn triangle(input: [V; 3], clip: (i64, i64, i64, i64)) -> Vec<Px> {
    let v: Vec<V> = input
        .into_iter()
        .map(|p| V {
            x: sext11(p.x),
            y: sext11(p.y),
            a: p.a,
        })
        .collect();
    let mut out = Vec::new();
    let xs = [v[0].x, v[1].x, v[2].x];
    let ys = [v[0].y, v[1].y, v[2].y];
    let (min_x, max_x) = (*xs.iter().min().unwrap(), *xs.iter().max().unwrap());
    let (min_y, max_y) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
    // §3.2: any two vertices 1024 or more apart in X, or 512 in Y.
    if max_x - min_x >= 1024 || max_y - min_y >= 512 {
        return out;
    }
    let p: [(i64, i64); 3] = [(v[0].x, v[0].y), (v[1].x, v[1].y), (v[2].x, v[2].y)];
    let area = edge(p[0], p[1], p[2]);
    if area == 0 {
        return out;
    }
    let sign = area.signum();
    // For each edge a -> b (the third vertex c opposite): whether a point on it is drawn.
    let edges = [(0, 1, 2), (1, 2, 0), (2, 0, 1)].map(|(i, j, k)| {
        let (a, b, c) = (p[i], p[j], p[k]);
        let inclusive = if a.1 == b.1 {
            c.1 > a.1 // horizontal: a top edge when the triangle lies below it
        } else {
            // The inside lies to the right of the edge: the point one pixel to the
            // right of a is on c's side.
            edge(a, b, (a.0 + 1, a.1)) * edge(a, b, c) > 0
        };
        (a, b, inclusive)
    });
    let inside = |q: (i64, i64)| {
        edges.iter().all(|&(a, b, inclusive)| {
            let w = edge(a, b, q) * sign;
            w > 0 || (w == 0 && inclusive)
        })
    };

    // §3.3: the core vertex, from X alone.
    let core = if xs[1] <= xs[0] {
        if xs[2] <= xs[1] { 2 } else { 1 }
    } else if xs[2] < xs[0] {
        2
    } else {
        0
    };
    // §3.6 gradients in 32-bit signed arithmetic, truncating division.
    let (a, b, c) = (&v[0], &v[1], &v[2]);
    let den = (b.x - a.x) * (c.y - b.y) - (c.x - b.x) * (b.y - a.y);
    let mut at = [(0u32, 0u32, 0u32); 5];
    for (i, slot) in at.iter_mut().enumerate() {
        let nx = (b.a[i] - a.a[i]) * (c.y - b.y) - (c.a[i] - b.a[i]) * (b.y - a.y);
        let ny = (b.x - a.x) * (c.a[i] - b.a[i]) - (c.x - b.x) * (b.a[i] - a.a[i]);
        let nx = i32::try_from(nx * 4096).unwrap();
        let ny = i32::try_from(ny * 4096).unwrap();
        let den = i32::try_from(den).unwrap();
        let ddx = ((nx / den) as u32) << 12;
        let ddy = ((ny / den) as u32) << 12;
        let start = (((v[core].a[i] as u32) << 12) + (1 << 11)) << 12;
        *slot = (start, ddx, ddy);
    }

    for y in min_y.max(clip.1)..=max_y.min(clip.3) {
        for x in min_x.max(clip.0)..=max_x.min(clip.2) {
            if !inside((x, y)) {
                continue;
            }
            let attr = at.map(|(start, ddx, ddy)| {
                let off_x = (x - v[core].x) as i32 as u32;
                let off_y = (y - v[core].y) as i32 as u32;
                start
                    .wrapping_add(ddx.wrapping_mul(off_x))
                    .wrapping_add(ddy.wrapping_mul(off_y))
                    >> 24
            });
            out.push(Px { x, y, attr });
        }
    }
    out
}

/// 5-bit channel of an 8-bit value with optional dither at (x, y) (docs/hardware/gpu.md §6).
pub fn channel(c: u32, x: i64, y: i64, dither: bool) -> u16 {
    let d = if dither {
        DITHER[(y & 3) as usize][(x & 3) as usize]
    } else {
        0
    };
    ((c as i64 + d).clamp(0, 255) >> 3) as u16
}
