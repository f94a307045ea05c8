//! The console side of the GPU's bus, for timing command streams (docs/formats.md, "Timed
//! streams"): a CPU storing to GP0 and GP1, loading GPUREAD and polling GPUSTAT, the DMA
//! controller moving DMA2 blocks (slice or burst mode), and timer 1 counting hblanks. A timed stream
//! says what the CPU does between its GPU accesses; [`run`] plays it on a [`Gpu`] through
//! the public API an emulator uses ([`Gpu::gp0`], [`Gpu::gp1`], [`Gpu::gpustat`],
//! [`Gpu::gpuread_timed`], [`Gpu::dma_block_write`], [`Gpu::dma_block_read`], [`Gpu::run`])
//! and reports what the console's clock and timer 1 would show.
//!
//! ```
//! // Two 64x64 rectangles, each sent as PSn00bSDK's DrawPrim sends it, then timer 1 read.
//! let text = "gp0 e3000000 e407ffff\ntimer\nrepeat 2\n  wait 28\n  gp1 04000000\n  \
//!             gp0 60000000 0 00400040\n  wait 28\nend\nreport two tiles\n";
//! let stream = gpu::bus::parse(text).unwrap();
//! let mut gpu = gpu::Gpu::new();
//! let timed = gpu::bus::run(&mut gpu, &stream).unwrap();
//! let report = &timed.reports[0];
//! assert_eq!(report.name, "two tiles");
//! // The second tile waited for the first (4096 pixels at about half a cycle each); the GPU
//! // drew the second after the report.
//! assert!(report.cycles > 4096 / 2 && timed.gpu_cycles > 2 * 4096 / 2);
//! ```

use alloc::string::{String, ToString};
use alloc::vec::Vec;

use crate::Gpu;
use crate::command_stream::{StreamError, TIMED_DIRECTIVES, Unfinished, parse_word};

/// CPU cycles of a store to GP0 or GP1 (a store instruction; the write queue absorbs it).
pub const STORE_CYCLES: u32 = 1;
/// CPU cycles of a load from GPUREAD: the time ps1-tests `cpu/access-time` measures for a
/// 32-bit load from the GPU's ports (3.8 cycles, docs/hardware/timing.md §12).
pub const LOAD_CYCLES: u32 = 4;
/// CPU cycles of one turn of a GPUSTAT polling loop: PSn00bSDK's `DrawSync` loop, ten
/// instructions around a GPUSTAT load (docs/hardware/timing.md §12).
pub const POLL_CYCLES: u32 = 12;
/// Words of a DMA2 block in slice mode until a `dma-block` line says otherwise (BCR block
/// size 10h, the GPU FIFO's size).
pub const DMA_BLOCK_WORDS: u32 = 16;
/// CPU cycles the DMA controller spends per block in slice mode besides moving the words
/// (ps1-tests `dma/chopping`, docs/hardware/dma.md §10).
pub const DMA_BLOCK_CYCLES: u32 = 10;
/// CPU cycles a wait may poll a GPU that has nothing left to draw before the stream is
/// declared stuck: two NTSC frames, enough for any bit that follows the video timing.
const IDLE_WAIT_LIMIT: u64 = 2 * 571_212;

/// Words, as runs of one word repeated.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Words {
    runs: Vec<(u32, u32)>,
}

impl Words {
    /// The words in order.
    pub fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        self.runs
            .iter()
            .flat_map(|&(word, n)| core::iter::repeat_n(word, n as usize))
    }

    /// How many words there are.
    pub fn len(&self) -> u64 {
        self.runs.iter().map(|&(_, n)| n as u64).sum()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Bits of GPUSTAT a `wait` polls for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StatusWait {
    /// Bits that must read 1.
    pub set: u32,
    /// Bits that must read 0.
    pub clear: u32,
}

impl StatusWait {
    /// Whether `stat` satisfies the wait.
    pub fn met(&self, stat: u32) -> bool {
        stat & self.set == self.set && stat & self.clear == 0
    }
}

/// What one line of a timed stream does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Op {
    /// `gp0 W...`: CPU stores to GP0, one a word.
    Gp0(Words),
    /// `gp1 W`: a CPU store to GP1.
    Gp1(u32),
    /// `dma W...`: DMA2 to GP0: in slice mode blocks of the current size, each waiting for
    /// GPUSTAT.25; in burst mode all at once.
    Dma(Words),
    /// `dma-read N`: DMA2 from GPUREAD, N words, in blocks as `dma`.
    DmaRead(u32),
    /// `dma-block N` / `dma-block burst`: the block size of later DMA2 lines (sync mode 1,
    /// BCR bits 0-15), or sync mode 0 (one burst, no requests).
    DmaBlock(Option<u32>),
    /// `read N`: N CPU loads from GPUREAD.
    Read(u32),
    /// `wait B...`: poll GPUSTAT until the bits read as listed.
    Wait(StatusWait),
    /// `cpu N`: N CPU cycles of other work.
    Cpu(u32),
    /// `timer`: timer 1 restarts from 0.
    Timer,
    /// `report NAME`: note timer 1 (hblanks since `timer`) under NAME.
    Report(String),
    /// `repeat N` ... `end`: the lines between, N times.
    Repeat(u32, Vec<TimedCommand>),
}

/// One line of a timed stream and its 1-based line number.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TimedCommand {
    /// Line in the source text.
    pub line: usize,
    /// What it does.
    pub op: Op,
}

/// A decimal count.
fn count(field: Option<&str>, what: &str) -> Result<u32, String> {
    let field = field.ok_or_else(|| alloc::format!("{what}: missing count"))?;
    field
        .parse::<u32>()
        .map_err(|_| alloc::format!("{what}: `{field}` is not a count (decimal, 0-4294967295)"))
}

/// Words of a `gp0` or `dma` line: hex words, `W*N` for N copies of W.
fn words<'a>(fields: impl Iterator<Item = &'a str>) -> Result<Words, String> {
    let mut runs = Vec::new();
    for field in fields {
        let (word, n) = match field.split_once('*') {
            Some((w, n)) => (parse_word(w)?, count(Some(n), "repeated word")?),
            None => (parse_word(field)?, 1),
        };
        if n > 0 {
            runs.push((word, n));
        }
    }
    if runs.is_empty() {
        return Err("missing word".to_string());
    }
    Ok(Words { runs })
}

/// Bits of a `wait` line: decimal bit numbers 0-31, `!` before those that must read 0.
fn status_wait<'a>(fields: impl Iterator<Item = &'a str>) -> Result<StatusWait, String> {
    let mut wait = StatusWait::default();
    for field in fields {
        let (clear, number) = match field.strip_prefix('!') {
            Some(n) => (true, n),
            None => (false, field),
        };
        let bit = number
            .parse::<u32>()
            .ok()
            .filter(|&b| b < 32)
            .ok_or_else(|| alloc::format!("wait: `{field}` is not a GPUSTAT bit (0-31)"))?;
        if clear {
            wait.clear |= 1 << bit;
        } else {
            wait.set |= 1 << bit;
        }
    }
    if wait.set & wait.clear != 0 {
        return Err("wait: a bit cannot read both 1 and 0".to_string());
    }
    if wait == StatusWait::default() {
        return Err("wait: missing GPUSTAT bit".to_string());
    }
    Ok(wait)
}

/// Parse a timed stream (docs/formats.md, "Timed streams"): the command-stream format's
/// `gp0`/`gp1` lines plus the directives `dma`, `dma-read`, `read`, `wait`, `cpu`,
/// `timer`, `report` and `repeat` ... `end`. The first malformed line is reported with its
/// number.
pub fn parse(text: &str) -> Result<Vec<TimedCommand>, StreamError> {
    let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
    // Open `repeat` blocks: their line, count and the lines gathered so far.
    let mut open: Vec<(usize, u32, Vec<TimedCommand>)> = Vec::new();
    let mut top = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("");
        let mut fields = content.split_whitespace();
        let Some(head) = fields.next() else {
            continue;
        };
        let err = |message: String| StreamError { line, message };
        let op = match head.to_ascii_lowercase().as_str() {
            "gp0" => Op::Gp0(words(fields).map_err(err)?),
            "gp1" => {
                let w = fields
                    .next()
                    .ok_or_else(|| err("missing word after the port".to_string()))?;
                let word = parse_word(w).map_err(err)?;
                if fields.next().is_some() {
                    return Err(err("gp1 takes exactly one word".to_string()));
                }
                Op::Gp1(word)
            }
            "dma" => Op::Dma(words(fields).map_err(err)?),
            "dma-read" => Op::DmaRead(count(fields.next(), "dma-read").map_err(err)?),
            "dma-block" => match fields.next() {
                Some("burst") => Op::DmaBlock(None),
                field => {
                    let n = count(field, "dma-block").map_err(err)?;
                    if !(1..=0x1_0000).contains(&n) {
                        return Err(err(alloc::format!(
                            "dma-block: {n} words is not a block size (1-65536, or burst)"
                        )));
                    }
                    Op::DmaBlock(Some(n))
                }
            },
            "read" => Op::Read(count(fields.next(), "read").map_err(err)?),
            "wait" => Op::Wait(status_wait(fields).map_err(err)?),
            "cpu" => Op::Cpu(count(fields.next(), "cpu").map_err(err)?),
            "timer" => Op::Timer,
            "report" => {
                let name: Vec<&str> = fields.collect();
                Op::Report(name.join(" "))
            }
            "repeat" => {
                let n = count(fields.next(), "repeat").map_err(err)?;
                open.push((line, n, Vec::new()));
                continue;
            }
            "end" => {
                let (start, n, body) = open
                    .pop()
                    .ok_or_else(|| err("`end` without `repeat`".to_string()))?;
                let cmd = TimedCommand {
                    line: start,
                    op: Op::Repeat(n, body),
                };
                match open.last_mut() {
                    Some((_, _, outer)) => outer.push(cmd),
                    None => top.push(cmd),
                }
                continue;
            }
            other => {
                return Err(err(alloc::format!(
                    "unknown line `{other}` (expected gp0, gp1 or a timing directive: {})",
                    TIMED_DIRECTIVES.join(", ")
                )));
            }
        };
        let cmd = TimedCommand { line, op };
        match open.last_mut() {
            Some((_, _, body)) => body.push(cmd),
            None => top.push(cmd),
        }
    }
    if let Some((line, _, _)) = open.pop() {
        return Err(StreamError {
            line,
            message: "`repeat` without `end`".to_string(),
        });
    }
    Ok(top)
}

/// What `report` noted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Report {
    /// The `report` line.
    pub line: usize,
    /// Its text.
    pub name: String,
    /// Hblanks timer 1 counted since the last `timer` (or the start).
    pub hblanks: u64,
    /// CPU cycles since then.
    pub cycles: u64,
}

/// The time a timed stream took.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TimedRun {
    /// CPU cycles from the first line to the end of the last.
    pub stream_cycles: u64,
    /// CPU cycles from the first line until the GPU had finished everything it was sent
    /// (at least `stream_cycles`).
    pub gpu_cycles: u64,
    /// Hblanks in `gpu_cycles` (the count timer 1 would reach in that time).
    pub hblanks: u64,
    /// CPU cycles of `gpu_cycles` that stores, loads and DMA blocks spent waiting on the GPU.
    pub stall_cycles: u64,
    /// What the `report` lines noted, in order.
    pub reports: Vec<Report>,
    /// `Some` when the stream ended mid-packet, mid CPU-to-VRAM transfer or inside an
    /// unterminated polyline, with the line of the word that started it.
    pub unfinished: Option<Unfinished>,
}

/// The clock of a run.
struct Player<'a> {
    gpu: &'a mut Gpu,
    now: u64,
    hblanks: u64,
    stalls: u64,
    timer_at: (u64, u64),
    /// Slice-mode block size; `None` for burst mode.
    block_size: Option<u32>,
    block: Vec<u32>,
    reports: Vec<Report>,
    /// Line of the GP0 word that started the input in progress.
    input_line: usize,
}

impl Player<'_> {
    /// `n` CPU cycles pass.
    fn advance(&mut self, n: u32) {
        if n == 0 {
            return;
        }
        let ev = self.gpu.run(n);
        self.now += n as u64;
        self.hblanks += ev.hblanks as u64;
    }

    /// The CPU waited `n` cycles on the GPU.
    fn stall(&mut self, n: u32) {
        self.stalls += n as u64;
        self.advance(n);
    }

    /// Poll until `wait` holds, `step` CPU cycles a turn (the status read at the end of
    /// each); an error when the GPU has nothing left to draw and the bits stay wrong.
    fn poll(&mut self, line: usize, wait: StatusWait, step: u32) -> Result<(), StreamError> {
        let mut idle_for = 0u64;
        loop {
            if wait.met(self.gpu.gpustat()) {
                return Ok(());
            }
            if self.gpu.drawing_cycles_left() == 0 {
                idle_for += step as u64;
                if idle_for > IDLE_WAIT_LIMIT {
                    return Err(StreamError {
                        line,
                        message: alloc::format!(
                            "GPUSTAT {:08X} never matches the wait (set {:08X}, clear {:08X})",
                            self.gpu.gpustat(),
                            wait.set,
                            wait.clear
                        ),
                    });
                }
            }
            self.advance(step);
        }
    }

    /// One DMA2 block of the `n` words in `self.block`: in slice mode after its request and
    /// the controller's own time.
    fn dma_block(&mut self, line: usize, read: bool) -> Result<(), StreamError> {
        if self.block_size.is_some() {
            let request = StatusWait {
                set: 1 << 25,
                clear: 0,
            };
            self.poll(line, request, 1)?;
            self.advance(DMA_BLOCK_CYCLES);
        }
        if !read && self.gpu.pending_input().is_none() {
            self.input_line = line;
        }
        let n = u32::try_from(self.block.len()).unwrap_or(u32::MAX);
        let cycles = if read {
            self.gpu.dma_block_read(&mut self.block)
        } else {
            self.gpu.dma_block_write(&self.block)
        };
        self.stalls += cycles.saturating_sub(n.saturating_add(n / 16)) as u64;
        self.advance(cycles);
        self.block.clear();
        Ok(())
    }

    /// Words a block holds: the slice size, or all of them in burst mode.
    fn block_limit(&self) -> usize {
        self.block_size.map_or(usize::MAX, |n| n as usize)
    }

    fn play(&mut self, commands: &[TimedCommand]) -> Result<(), StreamError> {
        for c in commands {
            match &c.op {
                Op::Gp0(words) => {
                    for w in words.iter() {
                        if self.gpu.pending_input().is_none() {
                            self.input_line = c.line;
                        }
                        self.advance(STORE_CYCLES);
                        let stall = self.gpu.gp0(w);
                        self.stall(stall);
                    }
                }
                Op::Gp1(w) => {
                    self.advance(STORE_CYCLES);
                    self.gpu.gp1(*w);
                }
                Op::Dma(words) => {
                    self.block.clear();
                    for w in words.iter() {
                        self.block.push(w);
                        if self.block.len() >= self.block_limit() {
                            self.dma_block(c.line, false)?;
                        }
                    }
                    if !self.block.is_empty() {
                        self.dma_block(c.line, false)?;
                    }
                }
                Op::DmaRead(words) => {
                    let mut left = *words as usize;
                    while left > 0 {
                        let n = left.min(self.block_limit());
                        self.block.clear();
                        self.block.resize(n, 0);
                        self.dma_block(c.line, true)?;
                        left -= n;
                    }
                }
                Op::DmaBlock(size) => self.block_size = *size,
                Op::Read(words) => {
                    for _ in 0..*words {
                        self.advance(LOAD_CYCLES);
                        let (_, stall) = self.gpu.gpuread_timed();
                        self.stall(stall);
                    }
                }
                Op::Wait(wait) => self.poll(c.line, *wait, POLL_CYCLES)?,
                Op::Cpu(n) => self.advance(*n),
                Op::Timer => self.timer_at = (self.now, self.hblanks),
                Op::Report(name) => self.reports.push(Report {
                    line: c.line,
                    name: name.clone(),
                    hblanks: self.hblanks - self.timer_at.1,
                    cycles: self.now - self.timer_at.0,
                }),
                Op::Repeat(n, body) => {
                    for _ in 0..*n {
                        self.play(body)?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// Play a timed stream on `gpu`, then run until the GPU has finished what it was sent.
/// Errors name the line of a `wait` (or DMA) that can never end: its bits stay wrong while
/// the GPU has nothing left to draw.
pub fn run(gpu: &mut Gpu, commands: &[TimedCommand]) -> Result<TimedRun, StreamError> {
    let mut p = Player {
        gpu,
        now: 0,
        hblanks: 0,
        stalls: 0,
        timer_at: (0, 0),
        block_size: Some(DMA_BLOCK_WORDS),
        block: Vec::new(),
        reports: Vec::new(),
        input_line: 0,
    };
    p.play(commands)?;
    let stream_cycles = p.now;
    loop {
        let left = p.gpu.drawing_cycles_left();
        if left == 0 {
            break;
        }
        p.advance(left);
    }
    let unfinished = p.gpu.pending_input().map(|pending| Unfinished {
        pending,
        line: p.input_line,
    });
    Ok(TimedRun {
        stream_cycles,
        gpu_cycles: p.now,
        hblanks: p.hblanks,
        stall_cycles: p.stalls,
        reports: p.reports,
        unfinished,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_directives_and_nested_repeats() {
        let text = "gp0 02000000*3 1\ndma 0*40\nrepeat 2\n repeat 3\n  cpu 5\n end\n \
                    wait 26 !27\nend\ntimer\nreport a b\ndma-read 7\nread 2\n";
        let s = parse(text).unwrap();
        assert_eq!(s.len(), 7);
        match &s[0].op {
            Op::Gp0(w) => assert_eq!(
                w.iter().collect::<Vec<_>>(),
                [0x0200_0000; 3]
                    .iter()
                    .copied()
                    .chain([1])
                    .collect::<Vec<_>>()
            ),
            other => panic!("{other:?}"),
        }
        match &s[1].op {
            Op::Dma(w) => assert_eq!(w.len(), 40),
            other => panic!("{other:?}"),
        }
        match &s[2].op {
            Op::Repeat(2, body) => {
                assert_eq!(body.len(), 2);
                assert_eq!(
                    body[0].op,
                    Op::Repeat(
                        3,
                        alloc::vec![TimedCommand {
                            line: 5,
                            op: Op::Cpu(5)
                        }]
                    )
                );
                assert_eq!(
                    body[1].op,
                    Op::Wait(StatusWait {
                        set: 1 << 26,
                        clear: 1 << 27
                    })
                );
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(s[4].op, Op::Report("a b".to_string()));
        assert_eq!(s[5].op, Op::DmaRead(7));
        assert_eq!(s[6].op, Op::Read(2));
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(parse("cpu 1\nrepeat 2\ncpu 3\n").unwrap_err().line, 2);
        assert_eq!(parse("end\n").unwrap_err().line, 1);
        assert_eq!(parse("gp0 1\nwait 32\n").unwrap_err().line, 2);
        assert_eq!(parse("wait 26 !26\n").unwrap_err().line, 1);
        assert_eq!(parse("cpu -1\n").unwrap_err().line, 1);
        assert_eq!(parse("dma 1*x\n").unwrap_err().line, 1);
        assert_eq!(parse("gp1 1 2\n").unwrap_err().line, 1);
        assert_eq!(parse("\n\nfoo 1\n").unwrap_err().line, 3);
    }

    #[test]
    fn a_wait_that_cannot_end_is_an_error() {
        let mut gpu = Gpu::new();
        // Bit 27 needs a VRAM-to-CPU transfer; none comes.
        let s = parse("cpu 1\nwait 27\n").unwrap();
        assert_eq!(run(&mut gpu, &s).unwrap_err().line, 2);
        // A DMA with direction 0 never gets its request.
        let s = parse("dma 0\n").unwrap();
        assert_eq!(run(&mut gpu, &s).unwrap_err().line, 1);
    }

    #[test]
    fn cpu_time_and_timer() {
        let mut gpu = Gpu::new();
        // 2172 CPU cycles hold one NTSC line of 3413 GPU cycles (11/7): one hblank each.
        let s = parse("cpu 100\ntimer\ncpu 21720\nreport ten lines\n").unwrap();
        let r = run(&mut gpu, &s).unwrap();
        assert_eq!(r.stream_cycles, 21_820);
        assert_eq!(r.gpu_cycles, 21_820);
        assert_eq!(r.reports[0].cycles, 21_720);
        assert!((9..=10).contains(&r.reports[0].hblanks));
    }
}
