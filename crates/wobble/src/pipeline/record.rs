//! Recording the frames the pipeline draws as a GPU dump (`wobble render --record`): each
//! frame is traced (`trace`), its GP0 packets and display word go to a [`Recorder`] in the
//! order the GPU received them, and a VSync ends it, so the dump replays to the frames
//! rendered.

use super::{FrameStats, Renderer, TraceError};
use gpu::dump::{RecordError, RecordInfo, Recorder, Sink, VsyncTime};

impl Renderer {
    /// Start a dump of what this renderer sends its GPU, from the GPU's state now
    /// (textures uploaded, display set up, the frames drawn so far in VRAM).
    pub fn start_recording<S: Sink>(
        &self,
        sink: S,
        info: &RecordInfo<'_>,
    ) -> Result<Recorder<S>, RecordError<S::Error>> {
        Recorder::start(sink, &self.gpu, info)
    }

    /// Render frame `frame` like [`Renderer::render_frame`], recording the GPU stage's port
    /// writes (one GP0 packet per packet sent, then the GP1 display word) and a VSync
    /// without timestamp. The stage times include the tracing. Only the hardware path can
    /// be recorded: the precise path draws nothing a GPU port receives.
    pub fn render_frame_recorded<S: Sink>(
        &mut self,
        frame: u32,
        recorder: &mut Recorder<S>,
    ) -> Result<FrameStats, TraceError> {
        let (stats, trace) = self.render_frame_traced(frame)?;
        for packet in &trace.packets {
            recorder.record_gp0(&packet.words);
        }
        recorder.record_gp1(trace.display_word);
        recorder.vsync(VsyncTime::None);
        Ok(stats)
    }
}
