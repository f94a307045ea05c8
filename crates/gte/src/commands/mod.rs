//! The 22 GTE commands, grouped by what they compute (docs/hardware/gte.md §5, §7, §8).
//!
//! Why this shape: an emulator calls a command and at once reads its results, so a call's
//! time is its dependency chain and its instruction count; each command reads its operands
//! once, keeps MAC/IR in locals, comes in one copy per sf and lm (the macro below), and tests
//! saturation in whichever form measured faster for it (docs/performance.md, "GTE commands",
//! "Saturation tests", "Straight paths and tests folded into others").

/// Evaluate `$body` with `$shift` (0 or 12, from sf) and `$lm` rebound to constants, one copy
/// per combination: the shifts by sf are then by a constant and the IR saturation bounds are
/// constants, which removes a variable shift or a select from every step of a command.
macro_rules! with_constant_sf_lm {
    ($shift:ident, $lm:ident, $body:expr) => {
        match ($shift, $lm) {
            (0, false) => {
                let ($shift, $lm) = (0u32, false);
                $body
            }
            (0, true) => {
                let ($shift, $lm) = (0u32, true);
                $body
            }
            (_, false) => {
                let ($shift, $lm) = (12u32, false);
                $body
            }
            (_, true) => {
                let ($shift, $lm) = (12u32, true);
                $body
            }
        }
    };
}

mod depth_cue;
mod light;
mod matrix;
mod rtp;
mod screen;
