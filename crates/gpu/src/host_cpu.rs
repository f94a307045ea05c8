//! The host CPU the GPU is emulated on: whether it has the x86-64 AVX2 instructions (with
//! BMI1, BMI2, FMA, LZCNT and POPCNT, the x86-64-v3 level), so that the textured triangles'
//! span loops can run in their build for them. Nothing of the console depends on it: both
//! builds are the same source, giving the same pixels, misses and drawing times; only the
//! host's time differs (docs/performance.md, "The AVX2 build chosen at run time").

/// Which build of the textured triangles' span loops runs. AVX2 is chosen only where the
/// host has been seen to have the instructions, with the `std` feature on x86-64: elsewhere
/// the baseline build runs.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct HostCpu {
    /// Set only when [`avx2_detected`] said so in this process.
    avx2: bool,
}

/// Not the chip's state: two GPUs are equal whichever build they draw with.
impl PartialEq for HostCpu {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Eq for HostCpu {}

impl HostCpu {
    /// The AVX2 build where the host has the instructions, else the baseline one.
    pub(crate) fn detect() -> Self {
        Self {
            avx2: avx2_detected(),
        }
    }

    /// Ask for the AVX2 build (`true`) or the baseline one; returns whether the AVX2 build
    /// now runs, which it does only where the host has the instructions.
    pub(crate) fn set_avx2(&mut self, on: bool) -> bool {
        self.avx2 = on && avx2_detected();
        self.avx2
    }

    /// Whether the AVX2 build runs: only ever `true` on a host that has the instructions.
    #[inline(always)]
    pub(crate) fn avx2(self) -> bool {
        self.avx2
    }
}

/// Whether this host has every instruction set the AVX2 build is compiled for (the
/// `target_feature` list of the rasterizer's `_avx2` routines), as the standard library
/// finds them (CPUID, and the OS's saving of the YMM registers for AVX).
#[cfg(all(feature = "std", target_arch = "x86_64"))]
fn avx2_detected() -> bool {
    std::is_x86_feature_detected!("avx2")
        && std::is_x86_feature_detected!("bmi1")
        && std::is_x86_feature_detected!("bmi2")
        && std::is_x86_feature_detected!("fma")
        && std::is_x86_feature_detected!("lzcnt")
        && std::is_x86_feature_detected!("popcnt")
}

/// Without the standard library's detection, or off x86-64: never.
#[cfg(not(all(feature = "std", target_arch = "x86_64")))]
fn avx2_detected() -> bool {
    false
}
