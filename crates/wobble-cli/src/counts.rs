//! Counts in messages: "1 frame", "2 frames".

/// `n` and the noun, singular for exactly one.
pub fn count(n: usize, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_is_singular() {
        assert_eq!(count(0, "draw", "draws"), "0 draws");
        assert_eq!(count(1, "draw", "draws"), "1 draw");
        assert_eq!(count(2, "polygon", "polygons"), "2 polygons");
    }
}
