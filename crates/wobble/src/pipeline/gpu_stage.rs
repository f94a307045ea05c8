//! GPU submission (docs/pipeline.md step 7): the drawing environment and the background
//! fill for the back buffer, the ordering-table walk into GP0 (`OrderingTable::walk`, the
//! DMA2 linked-list walk, docs/hardware/gpu.md §2), the display flip (GP1(05h)); and the
//! display set-up when the renderer starts (docs/hardware/gpu.md §9).

use super::trace::{FrameRecorder, PacketOrigin};
use crate::scene::Screen;
use gpu::encode::{self, ENVIRONMENT_WORDS};
use gpu::gp1::Gp1;
use gpu::{DisplayArea, Gpu, OrderingTable};

/// GP1(08h) for a screen `width` pixels wide: the width by bits 0-1 (256, 320, 512, 640)
/// or bit 6 (368, also taken for any other width, which `Scene::validate` refuses), 240
/// lines, NTSC, 15-bit colour, no interlace (docs/hardware/timing.md §4, §7).
fn gp1_display_mode(width: u16) -> u32 {
    let mode = match width {
        256 => 0,
        320 => 1,
        512 => 2,
        640 => 3,
        _ => 0x40,
    };
    Gp1::DisplayMode(mode).word()
}

/// GP1(05h): display the VRAM area starting at line `y`.
fn gp1_display_start(y: u16) -> u32 {
    Gp1::DisplayStart { x: 0, y }.word()
}

/// Turn the display on for `screen`: its width's display mode, then display enable. The
/// display area the renderer reads out (`Renderer::image`), at the screen's size.
pub(super) fn start_display(gpu: &mut Gpu, screen: &Screen) -> DisplayArea {
    gpu.gp1(gp1_display_mode(screen.width));
    gpu.gp1(Gp1::DisplayEnabled(true).word());
    DisplayArea {
        x: 0,
        y: 0,
        width: screen.width,
        height: screen.height,
        color_24bit: false,
    }
}

/// What starts and ends frame `frame` in its back buffer (the buffers at lines 0 and
/// `height` alternate): the drawing environment, a fill with the background colour, and the
/// GP1 word that displays it.
pub(super) struct FrameEnvironment {
    /// Draw mode (E1h, with the dither bit), texture window (E2h), drawing area (E3h, E4h),
    /// drawing offset (E5h), mask (E6h).
    environment: [u32; ENVIRONMENT_WORDS],
    /// GP0(02h): fill the back buffer with the background colour.
    fill: [u32; 3],
    /// GP1(05h): display the back buffer.
    display: u32,
}

impl FrameEnvironment {
    pub(super) fn new(screen: &Screen, frame: u32, dither: bool) -> Self {
        let buffer_y = (frame % 2) * u32::from(screen.height);
        let (w, h, y) = (screen.width, screen.height, buffer_y as u16);
        Self {
            environment: encode::environment(&gpu::DrawState {
                mode: gpu::DrawMode {
                    dither,
                    ..gpu::DrawMode::default()
                },
                area: gpu::DrawingArea {
                    left: 0,
                    top: y,
                    right: w - 1,
                    bottom: y + h - 1,
                },
                offset_y: y as i16,
                ..gpu::DrawState::default()
            }),
            fill: encode::fill(screen.background, 0, y, w, h),
            display: gp1_display_start(y),
        }
    }

    /// The set-up's GP0 packets in the order they are sent: the environment words, then
    /// the fill.
    fn packets(&self) -> impl Iterator<Item = &[u32]> {
        self.environment
            .chunks(1)
            .chain(std::iter::once(&self.fill[..]))
    }
}

/// Start the frame: its drawing environment and background fill into GP0.
pub(super) fn begin_frame(
    gpu: &mut Gpu,
    frame: &FrameEnvironment,
    mut trace: Option<&mut FrameRecorder>,
) {
    for packet in frame.packets() {
        if let Some(t) = trace.as_deref_mut() {
            t.sent(packet, PacketOrigin::Environment);
        }
        gpu.gp0_words(packet);
    }
}

/// Walk the ordering table into GP0, far entries first. Bad links cannot occur in a table
/// the OT stage built; a walk error would leave the frame partly drawn rather than stop
/// the renderer.
pub(super) fn walk(gpu: &mut Gpu, ot: &OrderingTable, trace: Option<&mut FrameRecorder>) {
    match trace {
        None => {
            let _ = ot.walk_into(gpu);
        }
        Some(t) => {
            let base = ot.ram().as_ptr() as usize;
            let _ = ot.walk(|words| {
                // A packet's words follow its node's header in the table's RAM image.
                let node = ((words.as_ptr() as usize).saturating_sub(base) / 4).saturating_sub(1);
                t.walked(node, words);
                gpu.gp0_words(words);
            });
        }
    }
}

/// Display the frame just drawn (GP1(05h)): the display area it shows, at the screen's
/// size.
pub(super) fn show_frame(
    gpu: &mut Gpu,
    frame: &FrameEnvironment,
    screen: &Screen,
    trace: Option<&mut FrameRecorder>,
) -> DisplayArea {
    if let Some(t) = trace {
        t.displayed(frame.display);
    }
    gpu.gp1(frame.display);
    DisplayArea {
        width: screen.width,
        height: screen.height,
        ..gpu.display_area()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The display mode selects each width through GP1(08h) bits 0-1 and 6, which GPUSTAT
    /// mirrors in bits 17-18 and 16 (docs/hardware/timing.md §7).
    #[test]
    fn display_mode_selects_each_width() {
        for (width, bits_17_18, bit_16) in [
            (256, 0, 0),
            (320, 1, 0),
            (512, 2, 0),
            (640, 3, 0),
            (368, 0, 1),
        ] {
            let mut gpu = Gpu::new();
            gpu.gp1(gp1_display_mode(width));
            let stat = gpu.gpustat();
            assert_eq!(
                (stat >> 17 & 3, stat >> 16 & 1),
                (bits_17_18, bit_16),
                "{width}"
            );
            // 240 lines (bit 19), NTSC (20), 15-bit (21), no interlace (22).
            assert_eq!(stat >> 19 & 0xF, 0, "{width}");
        }
    }
}
