//! Where every command's output goes (docs/formats.md, "Output files").
//!
//! [`open`] opens one output for a path or `-` (standard output); [`OutputDir::open`] opens a
//! directory output (a report of several files). The rules:
//!
//! - A regular file, new or existing, is written to a temporary file beside it and renamed
//!   over it only when complete ([`Output::commit`]), so an interrupted or failed run never
//!   leaves a partial file under its name. A symbolic link is followed: the file it points to
//!   is replaced (the temporary file goes beside that file) and the link stays a link. An
//!   existing file keeps its permission bits.
//! - A FIFO or a character device (`/dev/null`, a terminal) is written through, never
//!   replaced; so is anything under `/dev` or `/proc` (`/dev/stdout`, `/dev/fd/N`). A block
//!   device or a socket is refused.
//! - `-` is standard output (refused when it is a terminal: the outputs are binary).
//! - A directory output is built in a temporary directory (beside it when it does not exist
//!   yet, inside it when it does) and moved into place when complete, the report's index last.
//! - Temporary files and directories are removed on any error and, through
//!   [`remove_unfinished_on_interrupt`], on Ctrl-C, SIGTERM and SIGHUP.

use std::fs::{File, Permissions};
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Image formats `-o` accepts, by extension.
pub const IMAGE_EXTENSIONS: [(&str, image::ImageFormat); 6] = [
    ("png", image::ImageFormat::Png),
    ("gif", image::ImageFormat::Gif),
    ("bmp", image::ImageFormat::Bmp),
    ("tga", image::ImageFormat::Tga),
    ("ppm", image::ImageFormat::Pnm),
    ("pnm", image::ImageFormat::Pnm),
];

/// An image format named on the command line (`--format`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    /// PNG.
    Png,
    /// GIF (a single frame, or the animation where a command writes one).
    Gif,
    /// BMP.
    Bmp,
    /// TGA.
    Tga,
    /// Binary PPM (no alpha).
    Ppm,
}

impl From<FormatArg> for image::ImageFormat {
    fn from(f: FormatArg) -> image::ImageFormat {
        match f {
            FormatArg::Png => image::ImageFormat::Png,
            FormatArg::Gif => image::ImageFormat::Gif,
            FormatArg::Bmp => image::ImageFormat::Bmp,
            FormatArg::Tga => image::ImageFormat::Tga,
            FormatArg::Ppm => image::ImageFormat::Pnm,
        }
    }
}

/// Whether `path` names standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// Whether `path` is an existing FIFO or character device: written through, with no name to
/// tell a format from.
fn is_stream(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::metadata(path).is_ok_and(|m| {
        let t = m.file_type();
        t.is_fifo() || t.is_char_device()
    })
}

/// The list of extensions, for messages.
fn extension_list() -> String {
    IMAGE_EXTENSIONS
        .iter()
        .map(|(e, _)| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The image format named by `path`'s extension (case-insensitive): `None` without an
/// extension, `Some(Err(extension))` for one that names no format.
fn extension_format(path: &Path) -> Option<Result<image::ImageFormat, String>> {
    let ext = path.extension()?.to_string_lossy().to_ascii_lowercase();
    Some(
        IMAGE_EXTENSIONS
            .iter()
            .find(|(name, _)| *name == ext)
            .map(|(_, f)| *f)
            .ok_or(ext),
    )
}

/// The image format for output `path`: `given` (`--format`) when present, refused when the
/// extension names another format; else the extension's. Standard output needs `--format`;
/// a FIFO or device without a known extension is PNG.
pub fn image_format(path: &Path, given: Option<FormatArg>) -> Result<image::ImageFormat, String> {
    let from_ext = if is_stdout(path) {
        None
    } else {
        extension_format(path)
    };
    match (given.map(image::ImageFormat::from), from_ext) {
        (Some(g), Some(Ok(f))) if f != g => Err(format!(
            "{}: the extension names {f:?} but --format says {g:?}",
            path.display()
        )),
        (Some(g), _) => Ok(g),
        (None, Some(Ok(f))) => Ok(f),
        (None, _) if is_stdout(path) => Err(format!(
            "-: standard output has no file name to tell the image format from; add --format \
             (png, gif, bmp, tga or ppm), e.g. `-o - --format png`; accepted file names end \
             in {}",
            extension_list()
        )),
        (None, None | Some(Err(_))) if is_stream(path) => Ok(image::ImageFormat::Png),
        (None, ext) => Err(format!(
            "{}: cannot tell the image format from {}; use one of {} (or --format)",
            path.display(),
            match ext {
                Some(Err(e)) => format!("the extension `.{e}`"),
                _ => "a name without an extension".to_string(),
            },
            extension_list()
        )),
    }
}

/// Whether `path` is a file to be named (new, or an existing regular file outside `/dev` and
/// `/proc`), not standard output, a FIFO or a device: only such a name can have a sibling
/// output derived from it (the GIF beside an image).
pub fn is_file_target(path: &Path) -> bool {
    !is_stdout(path)
        && !path.starts_with("/dev")
        && !path.starts_with("/proc")
        && std::fs::metadata(path).map_or(true, |m| m.is_file())
}

/// Refuse a `--gif` file whose extension is not `.gif` (`--gif x.png` would put GIF bytes in
/// a file named as a PNG); standard output, FIFOs and devices take any name.
pub fn check_gif_name(path: &Path) -> Result<(), String> {
    if !is_file_target(path) {
        return Ok(());
    }
    match path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
    {
        Some(e) if e == "gif" => Ok(()),
        ext => Err(format!(
            "{}: --gif writes a GIF animation, so its file name must end in .gif (it {}); \
             -o writes the last frame in the format its extension names",
            path.display(),
            match ext {
                Some(e) => format!("ends in .{e}"),
                None => "has no extension".into(),
            }
        )),
    }
}

/// Temporary files and directories not yet renamed into place: removed on an interrupt.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Set once an output on standard output is open: summaries then go to stderr.
static STDOUT_TAKEN: AtomicBool = AtomicBool::new(false);

/// Numbers the temporary names of one process.
static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// Times the main thread asked for [`UNFINISHED`]: the interrupt handler, holding it, sees the
/// main thread stop (blocked on it, after a write into a removed directory failed).
static ASKED: AtomicUsize = AtomicUsize::new(0);

fn unfinished() -> MutexGuard<'static, Vec<PathBuf>> {
    ASKED.fetch_add(1, Ordering::SeqCst);
    UNFINISHED.lock().unwrap_or_else(PoisonError::into_inner)
}

fn forget(list: &mut Vec<PathBuf>, path: &Path) {
    list.retain(|p| p != path);
}

/// Remove a temporary file or directory (nothing if it is gone).
fn remove(path: &Path) {
    if path.is_dir() {
        let _ = std::fs::remove_dir_all(path);
    } else {
        let _ = std::fs::remove_file(path);
    }
}

/// Remove the temporary files and directories of `list` while the main thread may still be
/// writing into them. A directory is renamed and a placeholder file takes its name, so that
/// no file or directory can be created under that name any more (the main thread's next
/// write fails, and it then waits on the lock the caller holds); the renamed directory is
/// removed, and the placeholder once the main thread waits (or after half a second of work
/// that writes nothing).
fn remove_under_way(list: &[PathBuf]) {
    let asked = ASKED.load(Ordering::SeqCst);
    let mut placeholders = Vec::new();
    for path in list {
        if !path.is_dir() {
            let _ = std::fs::remove_file(path);
            continue;
        }
        let mut doomed = path.as_os_str().to_owned();
        doomed.push(".removing");
        let doomed = PathBuf::from(doomed);
        let at = if std::fs::rename(path, &doomed).is_ok() {
            if File::create_new(path).is_ok() {
                placeholders.push(path.clone());
            }
            doomed
        } else {
            path.clone()
        };
        for _ in 0..100 {
            if std::fs::remove_dir_all(&at).is_ok() || !at.exists() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
    }
    if !placeholders.is_empty() {
        for _ in 0..50 {
            if ASKED.load(Ordering::SeqCst) != asked {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        for path in &placeholders {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// On SIGINT (Ctrl-C), SIGTERM and SIGHUP: remove every unfinished temporary file and
/// directory, say so, and exit with status 130. A rename into place in progress finishes
/// first (both hold the same lock), so an output is either complete or absent.
pub fn remove_unfinished_on_interrupt() -> Result<(), String> {
    ctrlc::set_handler(|| {
        let list = UNFINISHED.lock().unwrap_or_else(PoisonError::into_inner);
        remove_under_way(&list);
        if list.is_empty() {
            eprintln!("interrupted");
        } else {
            eprintln!("interrupted: unfinished output removed");
        }
        // The lock is held to the end: no rename into place can start after the removal.
        std::process::exit(130);
    })
    .map_err(|e| format!("cannot install the interrupt handler: {e}"))
}

/// Print a command's closing summary: on stdout, or on stderr when an output went to stdout.
pub fn say(line: &str) {
    if STDOUT_TAKEN.load(Ordering::Relaxed) {
        eprintln!("{line}");
    } else {
        println!("{line}");
    }
}

/// A unique hidden temporary name beside `target` in `dir`.
fn temporary_name(dir: &Path, target: &Path) -> PathBuf {
    let name = target
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    dir.join(format!(".{name}.wobble-{}-{n}.tmp", std::process::id()))
}

/// The directory a path's file lives in (`.` for a bare name).
fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Follow a chain of symbolic links whose last target does not exist yet; the path the file
/// will be created at.
fn dangling_target(path: &Path) -> Result<PathBuf, String> {
    let mut at = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = std::fs::read_link(&at).map_err(|e| format!("{}: {e}", at.display()))?;
                at = parent_dir(&at).join(link);
            }
            _ => return Ok(at),
        }
    }
    Err(format!(
        "{}: too many levels of symbolic links",
        path.display()
    ))
}

/// Where an [`Output`]'s bytes go.
enum Sink {
    /// Standard output.
    Stdout(BufWriter<std::io::Stdout>),
    /// An existing FIFO, device or `/dev`, `/proc` path, written in place.
    Through(BufWriter<File>),
    /// A temporary file renamed over `target` by [`Output::commit`].
    Replace {
        file: BufWriter<File>,
        temp: PathBuf,
        target: PathBuf,
        permissions: Option<Permissions>,
    },
    /// Committed or failed.
    Closed,
}

/// One output being written: see the module documentation for where its bytes go.
pub struct Output {
    name: String,
    sink: Sink,
    written: u64,
}

/// Open the output `path` names (`-`: standard output). Fails at once, before any work, when
/// the output cannot be written: a missing or read-only directory, a directory, a block
/// device or socket, standard output on a terminal.
pub fn open(path: &Path) -> Result<Output, String> {
    let shown = path.display().to_string();
    let err = |e: &dyn std::fmt::Display| format!("{shown}: {e}");
    if is_stdout(path) {
        let stdout = std::io::stdout();
        if stdout.is_terminal() {
            return Err(
                "-: standard output is a terminal; redirect it to a file or a pipe (the \
                 output is binary)"
                    .into(),
            );
        }
        if STDOUT_TAKEN.swap(true, Ordering::Relaxed) {
            return Err("-: only one output can go to standard output".into());
        }
        return Ok(Output {
            name: "standard output".into(),
            sink: Sink::Stdout(BufWriter::new(stdout)),
            written: 0,
        });
    }
    let system = path.starts_with("/dev") || path.starts_with("/proc");
    match std::fs::metadata(path) {
        Ok(m) => {
            use std::os::unix::fs::FileTypeExt;
            let t = m.file_type();
            if t.is_dir() {
                return Err(err(&"is a directory"));
            }
            if t.is_block_device() {
                return Err(err(
                    &"is a block device; refusing to write an image over it",
                ));
            }
            if t.is_socket() {
                return Err(err(&"is a socket, which cannot be opened as a file"));
            }
            if !t.is_file() || system {
                let file = std::fs::OpenOptions::new()
                    .write(true)
                    .truncate(t.is_file())
                    .open(path)
                    .map_err(|e| err(&e))?;
                return Ok(Output {
                    name: shown,
                    sink: Sink::Through(BufWriter::new(file)),
                    written: 0,
                });
            }
            // A regular file, maybe through symbolic links: replace the file itself.
            let target = std::fs::canonicalize(path).map_err(|e| err(&e))?;
            replace(shown, target, Some(m.permissions()))
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let target = dangling_target(path)?;
            let dir = parent_dir(&target);
            if !dir.is_dir() {
                return Err(err(&format!("directory {} does not exist", dir.display())));
            }
            replace(shown, target, None)
        }
        Err(e) => Err(err(&e)),
    }
}

/// An output written to a temporary file beside `target`.
fn replace(
    shown: String,
    target: PathBuf,
    permissions: Option<Permissions>,
) -> Result<Output, String> {
    let dir = parent_dir(&target);
    let temp = temporary_name(&dir, &target);
    let mut list = unfinished();
    list.push(temp.clone());
    let file = match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temp)
    {
        Ok(f) => f,
        Err(e) => {
            forget(&mut list, &temp);
            return Err(format!(
                "{shown}: cannot create a temporary file in {} to write it through: {e}",
                dir.display()
            ));
        }
    };
    Ok(Output {
        name: shown,
        sink: Sink::Replace {
            file: BufWriter::new(file),
            temp,
            target,
            permissions,
        },
        written: 0,
    })
}

impl Output {
    /// The output's name for messages: the path as given, or "standard output".
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Bytes written so far.
    pub fn written(&self) -> u64 {
        self.written
    }

    fn writer(&mut self) -> std::io::Result<&mut dyn Write> {
        match &mut self.sink {
            Sink::Stdout(w) => Ok(w),
            Sink::Through(w) => Ok(w),
            Sink::Replace { file, .. } => Ok(file),
            Sink::Closed => Err(std::io::Error::other("output already closed")),
        }
    }

    /// Finish: flush, and for a replaced file sync it and rename it into place.
    pub fn commit(mut self) -> Result<(), String> {
        let name = self.name.clone();
        let err = |e: &dyn std::fmt::Display| format!("{name}: {e}");
        match std::mem::replace(&mut self.sink, Sink::Closed) {
            Sink::Stdout(mut w) => w.flush().map_err(|e| err(&e)),
            Sink::Through(mut w) => w.flush().map_err(|e| err(&e)),
            Sink::Replace {
                file,
                temp,
                target,
                permissions,
            } => {
                let result = (|| {
                    let file = file.into_inner().map_err(|e| err(e.error()))?;
                    if let Some(p) = permissions {
                        file.set_permissions(p).map_err(|e| err(&e))?;
                    }
                    file.sync_all().map_err(|e| err(&e))?;
                    drop(file);
                    let mut list = unfinished();
                    let renamed = std::fs::rename(&temp, &target);
                    if renamed.is_ok() {
                        forget(&mut list, &temp);
                    }
                    renamed.map_err(|e| err(&e))
                })();
                if result.is_err() {
                    let mut list = unfinished();
                    let _ = std::fs::remove_file(&temp);
                    forget(&mut list, &temp);
                }
                result
            }
            Sink::Closed => Err(err(&"already closed")),
        }
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.writer()?.write(buf)?;
        self.written += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.writer()?.flush()
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if let Sink::Replace { temp, .. } = std::mem::replace(&mut self.sink, Sink::Closed) {
            let mut list = unfinished();
            let _ = std::fs::remove_file(&temp);
            forget(&mut list, &temp);
        }
    }
}

/// Encode `img` into `out` in `format` and commit it (PPM has no alpha: an RGBA image is
/// written without it).
pub fn write_image(
    img: impl Into<image::DynamicImage>,
    mut out: Output,
    format: image::ImageFormat,
) -> Result<(), String> {
    let mut img: image::DynamicImage = img.into();
    if format == image::ImageFormat::Pnm && img.color().has_alpha() {
        img = image::DynamicImage::ImageRgb8(img.to_rgb8());
    }
    // The encoders need to seek; the image is encoded in memory, then written.
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, format)
        .map_err(|e| format!("{}: {e}", out.name()))?;
    out.write_all(bytes.get_ref())
        .map_err(|e| format!("{}: {e}", out.name()))?;
    out.commit()
}

/// A directory output (a report of several files) being built: the files are written under
/// [`OutputDir::path`], a temporary directory, and moved into place by [`OutputDir::commit`];
/// dropped uncommitted, the temporary directory is removed.
pub struct OutputDir {
    target: PathBuf,
    staging: PathBuf,
    /// The target exists: the staging directory is inside it and its entries move one by one.
    into_existing: bool,
    committed: bool,
}

impl OutputDir {
    /// Start building directory `target`: an existing directory (its other files are left
    /// alone), or a new one in an existing directory. Fails at once when neither holds or the
    /// place is not writable.
    pub fn open(target: &Path) -> Result<OutputDir, String> {
        let shown = target.display();
        if is_stdout(target) {
            return Err(
                "-: this output is a directory of files; it cannot go to standard \
                        output"
                    .into(),
            );
        }
        let (staging, into_existing) = match std::fs::metadata(target) {
            Ok(m) if m.is_dir() => (temporary_name(target, Path::new("report")), true),
            Ok(_) => return Err(format!("{shown}: exists and is not a directory")),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                if std::fs::symlink_metadata(target).is_ok() {
                    return Err(format!(
                        "{shown}: is a symbolic link to a directory that does not exist"
                    ));
                }
                let dir = parent_dir(target);
                if !dir.is_dir() {
                    return Err(format!(
                        "{shown}: directory {} does not exist",
                        dir.display()
                    ));
                }
                (temporary_name(&dir, target), false)
            }
            Err(e) => return Err(format!("{shown}: {e}")),
        };
        let mut list = unfinished();
        list.push(staging.clone());
        if let Err(e) = std::fs::create_dir(&staging) {
            forget(&mut list, &staging);
            return Err(format!(
                "{shown}: cannot create a temporary directory in {}: {e}",
                parent_dir(&staging).display()
            ));
        }
        Ok(OutputDir {
            target: target.to_path_buf(),
            staging,
            into_existing,
            committed: false,
        })
    }

    /// Where to write the files (the temporary directory).
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The directory as given.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Move the files into place, `last` (the report's index) after every other entry.
    pub fn commit(mut self, last: &str) -> Result<(), String> {
        let mut list = unfinished();
        let result = if self.into_existing {
            self.move_entries(last)
        } else {
            std::fs::rename(&self.staging, &self.target)
                .map_err(|e| format!("{}: {e}", self.target.display()))
        };
        if result.is_ok() {
            if self.into_existing {
                remove(&self.staging);
            }
            forget(&mut list, &self.staging);
            self.committed = true;
        }
        result
    }

    /// Move each entry of the staging directory over the same name in the target; an entry
    /// it replaces goes into the staging directory, removed afterwards.
    fn move_entries(&self, last: &str) -> Result<(), String> {
        let read = std::fs::read_dir(&self.staging)
            .map_err(|e| format!("{}: {e}", self.staging.display()))?;
        let mut names: Vec<_> = read.filter_map(|e| e.ok().map(|e| e.file_name())).collect();
        names.sort_by_key(|n| n.as_os_str() == last);
        for (i, name) in names.iter().enumerate() {
            let from = self.staging.join(name);
            let to = self.target.join(name);
            let err = |e: std::io::Error| format!("{}: {e}", to.display());
            let replaced_is_dir = std::fs::symlink_metadata(&to).is_ok_and(|m| m.is_dir());
            if replaced_is_dir || from.is_dir() && to.exists() {
                std::fs::rename(&to, self.staging.join(format!(".replaced-{i}"))).map_err(err)?;
            }
            std::fs::rename(&from, &to).map_err(err)?;
        }
        Ok(())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed {
            let mut list = unfinished();
            remove(&self.staging);
            forget(&mut list, &self.staging);
        }
    }
}
