//! Output files for every command. The image format comes from the file name's extension
//! (or is refused with the list); every file is written to a temporary file in the same
//! directory and renamed over the target only when complete, so an interrupted or failed
//! run never leaves a partial file under the target name. Opening an [`OutputFile`] creates
//! its temporary file, so opening all outputs before the work checks that each directory
//! exists and is writable.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Image formats `-o` accepts, by extension.
pub const IMAGE_EXTENSIONS: [(&str, image::ImageFormat); 6] = [
    ("png", image::ImageFormat::Png),
    ("gif", image::ImageFormat::Gif),
    ("bmp", image::ImageFormat::Bmp),
    ("tga", image::ImageFormat::Tga),
    ("ppm", image::ImageFormat::Pnm),
    ("pnm", image::ImageFormat::Pnm),
];

/// The image format for `path`, from its extension (case-insensitive); an error naming the
/// accepted extensions otherwise.
pub fn image_format(path: &Path) -> Result<image::ImageFormat, String> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let found = ext
        .as_deref()
        .and_then(|e| IMAGE_EXTENSIONS.iter().find(|(name, _)| *name == e));
    match found {
        Some((_, format)) => Ok(*format),
        None => {
            let list: Vec<String> = IMAGE_EXTENSIONS
                .iter()
                .map(|(e, _)| format!(".{e}"))
                .collect();
            Err(format!(
                "{}: cannot tell the image format from {}; use one of {}",
                path.display(),
                match &ext {
                    Some(e) => format!("the extension `.{e}`"),
                    None => "a name without an extension".to_string(),
                },
                list.join(", ")
            ))
        }
    }
}

/// A file being written: a temporary file beside `path`, renamed to `path` by
/// [`OutputFile::commit`] and removed if dropped uncommitted.
pub struct OutputFile {
    path: PathBuf,
    temp: PathBuf,
    writer: Option<BufWriter<File>>,
}

static COUNTER: AtomicUsize = AtomicUsize::new(0);

impl OutputFile {
    /// Start writing `path`: fails at once when its directory is missing or not writable,
    /// or when `path` is a directory.
    pub fn create(path: &Path) -> Result<OutputFile, String> {
        let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
        if path.is_dir() {
            return Err(err(&"is a directory"));
        }
        let name = path
            .file_name()
            .ok_or_else(|| err(&"not a file name"))?
            .to_string_lossy();
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dir.is_dir() {
            return Err(err(&format!("directory {} does not exist", dir.display())));
        }
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{name}.{}-{n}.tmp", std::process::id()));
        let file = File::create(&temp).map_err(|e| err(&e))?;
        Ok(OutputFile {
            path: path.to_path_buf(),
            temp,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The writer for the contents.
    pub fn writer(&mut self) -> Result<&mut BufWriter<File>, String> {
        let path = self.path.display().to_string();
        self.writer
            .as_mut()
            .ok_or_else(|| format!("{path}: already committed"))
    }

    /// Finish: flush and rename the temporary file to the target.
    pub fn commit(mut self) -> Result<(), String> {
        let err = |e: std::io::Error| format!("{}: {e}", self.path.display());
        if let Some(mut w) = self.writer.take() {
            w.flush().map_err(err)?;
            let file = w.into_inner().map_err(|e| err(e.into_error()))?;
            file.sync_all().map_err(err)?;
        }
        std::fs::rename(&self.temp, &self.path).map_err(err)?;
        self.temp = PathBuf::new();
        Ok(())
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        self.writer = None;
        if !self.temp.as_os_str().is_empty() {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Check that `dir` is a writable directory (by creating and removing a temporary file).
pub fn check_dir(dir: &Path) -> Result<(), String> {
    OutputFile::create(&dir.join("probe")).map(drop)
}

/// Encode `img` into `out` in the format `out`'s extension names (PPM has no alpha: an
/// RGBA image is written without it).
pub fn write_image(img: impl Into<image::DynamicImage>, mut out: OutputFile) -> Result<(), String> {
    let format = image_format(out.path())?;
    let mut img: image::DynamicImage = img.into();
    if format == image::ImageFormat::Pnm && img.color().has_alpha() {
        img = image::DynamicImage::ImageRgb8(img.to_rgb8());
    }
    let path = out.path().display().to_string();
    img.write_to(out.writer()?, format)
        .map_err(|e| format!("{path}: {e}"))?;
    out.commit()
}

/// Write `img` to `path` (temporary file, then rename) in the format of its extension.
pub fn save_image(img: impl Into<image::DynamicImage>, path: &Path) -> Result<(), String> {
    image_format(path)?;
    write_image(img, OutputFile::create(path)?)
}
