//! Image files: PNG (8 or 16 bits, gamma-encoded, optional alpha) and PFM depth maps, both
//! written atomically (temporary file in the same directory, then rename).

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, PoisonError};

use image::ImageEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

use crate::film::Film;

/// The transfer function applied to clamped linear values before quantisation (seed
/// `002_…` §3.2.2: `a' = a^(1/γ)` corrects for the display's `a^γ`).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Gamma {
    /// The sRGB curve (IEC 61966-2-1): linear below 0.0031308, else `1.055·a^(1/2.4) − 0.055`;
    /// close to γ = 2.2 overall. The default, and what PNG viewers assume.
    #[default]
    Srgb,
    /// A pure power law `a^(1/γ)`; `Power(1.0)` writes linear values.
    Power(f64),
}

impl Gamma {
    /// Encodes a linear value, first clamped to `[0, 1]` (NaN becomes 0).
    pub fn encode(self, a: f64) -> f64 {
        let a = if a.is_nan() { 0.0 } else { a.clamp(0.0, 1.0) };
        match self {
            Gamma::Srgb => {
                if a <= 0.003_130_8 {
                    12.92 * a
                } else {
                    1.055 * a.powf(1.0 / 2.4) - 0.055
                }
            }
            Gamma::Power(g) => a.powf(1.0 / g),
        }
    }

    /// The inverse of [`Gamma::encode`] on `[0, 1]`.
    pub fn decode(self, e: f64) -> f64 {
        let e = e.clamp(0.0, 1.0);
        match self {
            Gamma::Srgb => {
                if e <= 0.040_45 {
                    e / 12.92
                } else {
                    ((e + 0.055) / 1.055).powf(2.4)
                }
            }
            Gamma::Power(g) => e.powf(g),
        }
    }
}

/// How to write the PNG.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PngOptions {
    /// 8 or 16 bits per channel.
    pub bits: u8,
    /// Write an alpha channel: 0 where no sample hit an object (background), else the
    /// coverage (seed `002_…` §3.4). Colours are not premultiplied.
    pub alpha: bool,
    /// Transfer function.
    pub gamma: Gamma,
}

impl Default for PngOptions {
    /// 8-bit sRGB without alpha.
    fn default() -> Self {
        PngOptions {
            bits: 8,
            alpha: false,
            gamma: Gamma::Srgb,
        }
    }
}

/// Errors writing an output file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// Creating, writing or renaming the file failed.
    #[error("cannot write {}", path.display())]
    Io {
        /// The destination.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// PNG encoding failed.
    #[error("cannot encode {}", path.display())]
    Encode {
        /// The destination.
        path: PathBuf,
        /// The cause.
        #[source]
        source: image::ImageError,
    },
    /// Unsupported option.
    #[error("unsupported PNG bit depth {0} (use 8 or 16)")]
    BitDepth(u8),
    /// The film has no depth channel.
    #[error("the render kept no depth values")]
    NoDepth,
    /// An output names the same file as an input or another output.
    #[error("the output {} is the same file as the {what} {}", output.display(), other.display())]
    SameFile {
        /// The output.
        output: PathBuf,
        /// The input or earlier output it coincides with.
        other: PathBuf,
        /// "input" or "output".
        what: &'static str,
    },
    /// [`PendingOutputs::commit`] before every output was written.
    #[error("{} was not written", .0.display())]
    NotWritten(PathBuf),
    /// The outputs were abandoned by [`abandon_pending_outputs`] (a signal).
    #[error("the outputs were abandoned (interrupted)")]
    Abandoned,
}

/// The most symbolic links followed when resolving an output path (Linux's `MAXSYMLINKS`):
/// a longer chain is a loop for every practical purpose and is refused.
const MAX_SYMLINKS: usize = 40;

/// Where an output's bytes go once the render is done.
#[derive(Debug)]
enum Sink {
    /// A regular file (existing or not): bytes go to `tmp` in the same directory as `dest`,
    /// which the commit renames onto `dest`.
    Replace {
        /// The temporary, created (empty) by [`PendingOutputs::prepare`].
        tmp: PathBuf,
        /// The open temporary.
        file: Option<File>,
        /// The destination after following symbolic links.
        dest: PathBuf,
    },
    /// A device, FIFO or socket (`/dev/null`, `/dev/stdout`, a named pipe): it cannot be
    /// replaced, so the commit opens it and writes the bytes kept in memory.
    Special {
        /// The node, after following symbolic links.
        node: PathBuf,
        /// The encoded bytes.
        bytes: Vec<u8>,
    },
}

/// One output file.
#[derive(Debug)]
struct Pending {
    /// The path as the caller named it (for messages).
    path: PathBuf,
    sink: Sink,
    written: bool,
}

/// Output files of one render, validated before it starts and committed together after.
///
/// [`PendingOutputs::prepare`] checks every path up front — no two outputs and no input name
/// the same file (compared after following symbolic links, and by device and inode on Unix),
/// the directory exists, and a temporary file can be created there — so a run that would
/// fail to write its results fails before tracing a ray. [`PendingOutputs::commit`] renames
/// all temporaries onto their destinations only when every output was written: a failed run
/// leaves every existing file as it was.
///
/// - A symbolic link is followed: its target is replaced (atomically, by a temporary in the
///   target's directory), the link stays a link.
/// - A device, FIFO or socket is written directly at commit time and never replaced.
/// - Dropping a `PendingOutputs` without committing removes its temporaries, and
///   [`abandon_pending_outputs`] removes every process's pending temporaries from a signal
///   handler. Only `SIGKILL` or a crash can leave an (empty or partial) `.NAME.PID.N.tmp`.
#[derive(Debug)]
pub struct PendingOutputs {
    outputs: Vec<Pending>,
}

/// Temporaries not yet committed or removed, for [`abandon_pending_outputs`]; `closed` once
/// that was called, after which nothing new may be created or committed.
struct Registry {
    files: Vec<PathBuf>,
    closed: bool,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    files: Vec::new(),
    closed: false,
});

/// Distinguishes temporaries of the same name created by one process (several renders in one
/// server process).
static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

fn registry() -> std::sync::MutexGuard<'static, Registry> {
    // The registry's data stays consistent even if a thread panicked holding the lock.
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes the temporary file of every output not yet committed, in every thread, and makes
/// every later [`PendingOutputs::prepare`] and [`PendingOutputs::commit`] fail with
/// [`OutputError::Abandoned`]. For a signal handler (SIGINT, SIGTERM) before the process
/// exits; a commit in progress finishes first (it holds the same lock), so each output is
/// either fully replaced or untouched.
pub fn abandon_pending_outputs() {
    let mut reg = registry();
    reg.closed = true;
    for f in reg.files.drain(..) {
        let _ = std::fs::remove_file(f);
    }
}

fn io_error(path: &Path, source: std::io::Error) -> OutputError {
    OutputError::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn invalid(path: &Path, reason: &str) -> OutputError {
    io_error(
        path,
        std::io::Error::new(std::io::ErrorKind::InvalidInput, reason.to_string()),
    )
}

/// Follows symbolic links from `path` to the node they finally name (which may not exist).
fn follow_links(path: &Path) -> Result<PathBuf, OutputError> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_SYMLINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let target = std::fs::read_link(&p).map_err(|e| io_error(path, e))?;
                p = match p.parent() {
                    Some(dir) if target.is_relative() => dir.join(target),
                    _ => target,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(invalid(path, "too many levels of symbolic links"))
}

/// The directory a file lives in (`.` for a bare name).
fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// What makes two paths the same file: the canonical path (of the file, or of its directory
/// joined with its name when it does not exist yet), and on Unix the device and inode of an
/// existing file, which also catches hard links.
#[derive(Debug, PartialEq)]
struct Identity {
    canonical: Option<PathBuf>,
    inode: Option<(u64, u64)>,
}

impl Identity {
    fn of(path: &Path) -> Identity {
        let canonical = std::fs::canonicalize(path).ok().or_else(|| {
            let dir = std::fs::canonicalize(directory_of(path)).ok()?;
            Some(dir.join(path.file_name()?))
        });
        Identity {
            canonical,
            inode: inode(path),
        }
    }

    fn same(&self, other: &Identity) -> bool {
        match (self.inode, other.inode) {
            (Some(a), Some(b)) => a == b,
            _ => self.canonical.is_some() && self.canonical == other.canonical,
        }
    }
}

#[cfg(unix)]
fn inode(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn inode(_path: &Path) -> Option<(u64, u64)> {
    None
}

impl PendingOutputs {
    /// Checks `outputs` (in the order their bytes will be given to [`PendingOutputs::write`])
    /// against each other and against `inputs` (files the render reads, such as the scene),
    /// and creates a temporary file for each regular output.
    ///
    /// # Errors
    /// [`OutputError::SameFile`] when two outputs, or an output and an input, are one file;
    /// [`OutputError::Io`] when a directory is missing, a path names a directory, a link
    /// chain loops, or a temporary cannot be created (no write permission, read-only file
    /// system); [`OutputError::Abandoned`] after [`abandon_pending_outputs`].
    pub fn prepare(outputs: &[&Path], inputs: &[&Path]) -> Result<PendingOutputs, OutputError> {
        let ids: Vec<Identity> = outputs.iter().map(|p| Identity::of(p)).collect();
        for (i, (path, id)) in outputs.iter().zip(&ids).enumerate() {
            if let Some(input) = inputs.iter().find(|q| id.same(&Identity::of(q))) {
                return Err(OutputError::SameFile {
                    output: path.to_path_buf(),
                    other: input.to_path_buf(),
                    what: "input",
                });
            }
            if let Some(j) = (0..i).find(|&j| ids[j].same(id)) {
                return Err(OutputError::SameFile {
                    output: path.to_path_buf(),
                    other: outputs[j].to_path_buf(),
                    what: "output",
                });
            }
        }
        let mut pending = PendingOutputs {
            outputs: Vec::with_capacity(outputs.len()),
        };
        for path in outputs {
            let sink = Self::sink(path)?;
            pending.outputs.push(Pending {
                path: path.to_path_buf(),
                sink,
                written: false,
            });
        }
        Ok(pending)
    }

    fn sink(path: &Path) -> Result<Sink, OutputError> {
        let dest = follow_links(path)?;
        match std::fs::metadata(&dest) {
            Ok(m) if m.is_dir() => return Err(invalid(path, "is a directory")),
            Ok(m) if !m.is_file() => {
                if m.permissions().readonly() {
                    return Err(invalid(path, "the device or FIFO is not writable"));
                }
                return Ok(Sink::Special {
                    node: dest,
                    bytes: Vec::new(),
                });
            }
            Ok(_) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(io_error(path, e)),
        }
        let name = dest
            .file_name()
            .ok_or_else(|| invalid(path, "the path names no file"))?;
        let dir = directory_of(&dest);
        match std::fs::metadata(&dir) {
            Ok(m) if m.is_dir() => {}
            Ok(_) => return Err(invalid(path, "its directory is not a directory")),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Err(invalid(path, "its directory does not exist"));
            }
            Err(e) => return Err(io_error(path, e)),
        }
        let n = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(
            ".{}.{}.{n}.tmp",
            name.to_string_lossy(),
            std::process::id()
        ));
        let mut reg = registry();
        if reg.closed {
            return Err(OutputError::Abandoned);
        }
        // `create_new`: never truncate a file that happens to have the temporary's name.
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| io_error(path, e))?;
        reg.files.push(tmp.clone());
        Ok(Sink::Replace {
            tmp,
            file: Some(file),
            dest,
        })
    }

    /// Fills output `index` (its position in `prepare`'s list) through `write`.
    ///
    /// # Errors
    /// [`OutputError::Io`] when writing fails, or `write`'s own error.
    ///
    /// # Panics
    /// If `index` is not below the number of outputs prepared.
    pub fn write(
        &mut self,
        index: usize,
        write: impl FnOnce(&mut dyn Write) -> Result<(), OutputError>,
    ) -> Result<(), OutputError> {
        let out = &mut self.outputs[index];
        let path = out.path.clone();
        match &mut out.sink {
            Sink::Replace { file, .. } => {
                let file = file.as_mut().ok_or(OutputError::Abandoned)?;
                let mut w = BufWriter::new(file);
                write(&mut w)?;
                let file = w
                    .into_inner()
                    .map_err(|e| io_error(&path, e.into_error()))?;
                file.sync_all().map_err(|e| io_error(&path, e))?;
            }
            Sink::Special { bytes, .. } => {
                bytes.clear();
                write(bytes)?;
            }
        }
        out.written = true;
        Ok(())
    }

    /// Replaces every destination by its temporary and writes the special files, once every
    /// output was written.
    ///
    /// # Errors
    /// [`OutputError::NotWritten`] if an output was not written (nothing is replaced),
    /// [`OutputError::Abandoned`] after [`abandon_pending_outputs`], [`OutputError::Io`]
    /// when a rename or a device write fails (the outputs before it are already replaced:
    /// a rename within one directory fails only for reasons outside the program, such as a
    /// file system gone read-only).
    pub fn commit(mut self) -> Result<(), OutputError> {
        if let Some(o) = self.outputs.iter().find(|o| !o.written) {
            return Err(OutputError::NotWritten(o.path.clone()));
        }
        let mut reg = registry();
        if reg.closed {
            return Err(OutputError::Abandoned);
        }
        for out in &mut self.outputs {
            match &mut out.sink {
                Sink::Replace { tmp, file, dest } => {
                    drop(file.take());
                    std::fs::rename(&*tmp, &*dest).map_err(|e| io_error(&out.path, e))?;
                    reg.files.retain(|f| f != tmp);
                }
                Sink::Special { node, bytes } => {
                    let mut f = OpenOptions::new()
                        .write(true)
                        .open(&*node)
                        .map_err(|e| io_error(&out.path, e))?;
                    f.write_all(bytes).map_err(|e| io_error(&out.path, e))?;
                }
            }
        }
        Ok(())
    }
}

impl Drop for PendingOutputs {
    /// Removes the temporaries that were not committed.
    fn drop(&mut self) {
        let mut reg = registry();
        for out in &mut self.outputs {
            if let Sink::Replace { tmp, file, .. } = &mut out.sink
                && (file.take().is_some() || reg.files.contains(tmp))
            {
                let _ = std::fs::remove_file(&*tmp);
                reg.files.retain(|f| f != tmp);
            }
        }
    }
}

/// Writes `path` atomically: `write` fills a temporary file next to it (next to a symbolic
/// link's target), which then replaces it by a rename; a device or FIFO is written directly.
/// On any failure the temporary file is removed and `path` is untouched. One output of
/// [`PendingOutputs`].
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), OutputError>,
) -> Result<(), OutputError> {
    let mut pending = PendingOutputs::prepare(&[path], &[])?;
    pending.write(0, write)?;
    pending.commit()
}

/// Quantises encoded channel values to 8 bits through the decision thresholds of the
/// transfer function: code `k` is chosen for linear `a` when
/// `decode((k − ½)/255) ≤ a < decode((k + ½)/255)`, which is `round(255·encode(a))` computed
/// by comparisons instead of a `powf` per channel.
///
/// The code is the number of thresholds `≤ a`. A binary search over the 255 thresholds (eight
/// steps a channel) was most of the PNG encoding, which runs on one thread after the render
/// (`docs/speed.md`, SPD "Eighth pass"); instead a table indexed by the top
/// [`QUANTIZER_BUCKET_BITS`] bits of the `f32` gives that count at the least value of `a`'s
/// bucket (for non-negative `f32`s the bit patterns are in the order of the values), and the
/// count is finished by stepping over the thresholds between that value and `a`: the same
/// count, so the same code (test `bucketed_quantizer_is_the_binary_search`).
struct Quantizer8 {
    /// `thresholds[k]` is the smallest linear value that encodes to code `k + 1`.
    thresholds: [f64; 255],
    /// `start[b]`: how many thresholds are `≤` the least non-negative `f32` of bucket `b` (its
    /// bits `b << (32 − QUANTIZER_BUCKET_BITS)`), for the buckets up to that of `1.0`.
    start: Vec<u8>,
}

/// The top bits of an `f32` that name its bucket in [`Quantizer8`]'s table: sign, exponent
/// and seven mantissa bits, so a normal bucket spans a relative width of at most `2⁻⁷`; the
/// sRGB thresholds are farther apart than that (by 0.9 % of their value at the narrowest,
/// near 1), so at most two are stepped over. `1.0`'s bucket is `0x3F80`: a table of 16 K
/// bytes, one entry a bucket up to `1.0`.
const QUANTIZER_BUCKET_BITS: u32 = 16;

impl Quantizer8 {
    fn new(gamma: Gamma) -> Self {
        let mut thresholds = [0.0; 255];
        for (k, t) in thresholds.iter_mut().enumerate() {
            *t = gamma.decode((k as f64 + 0.5) / 255.0);
        }
        let shift = 32 - QUANTIZER_BUCKET_BITS;
        let last = 1.0f32.to_bits() >> shift;
        let start = (0..=last)
            .map(|b| {
                let least = f64::from(f32::from_bits(b << shift));
                thresholds.partition_point(|&t| t <= least) as u8
            })
            .collect();
        Quantizer8 { thresholds, start }
    }

    fn quantize(&self, a: f32) -> u8 {
        let bits = a.to_bits();
        let a = f64::from(a);
        if a.is_nan() {
            return 0;
        }
        // A negative `a` (sign bit set) starts from no threshold; one above `1.0` from the
        // last bucket's count, which is still at most its own.
        let mut code = if bits >> 31 == 1 {
            0
        } else {
            let bucket = (bits >> (32 - QUANTIZER_BUCKET_BITS)) as usize;
            usize::from(self.start[bucket.min(self.start.len() - 1)])
        };
        while code < self.thresholds.len() && self.thresholds[code] <= a {
            code += 1;
        }
        code as u8
    }
}

/// Encodes `film` as a PNG at `path` (atomically).
pub fn write_png(film: &Film, path: &Path, opts: &PngOptions) -> Result<(), OutputError> {
    write_atomically(path, |out| encode_png(film, out, opts, path))
}

/// Encodes `film` as a PNG into `out`: the bytes [`write_png`] writes (`path` only names
/// the destination in errors). The `render serve` explorer sends these bytes.
pub fn encode_png(
    film: &Film,
    out: &mut dyn Write,
    opts: &PngOptions,
    path: &Path,
) -> Result<(), OutputError> {
    let (w, h) = (film.width, film.height);
    let color_type = match (opts.bits, opts.alpha) {
        (8, false) => image::ExtendedColorType::Rgb8,
        (8, true) => image::ExtendedColorType::Rgba8,
        (16, false) => image::ExtendedColorType::Rgb16,
        (16, true) => image::ExtendedColorType::Rgba16,
        (b, _) => return Err(OutputError::BitDepth(b)),
    };
    let channels = if opts.alpha { 4 } else { 3 };
    let mut bytes = Vec::with_capacity(film.pixels.len() * channels * usize::from(opts.bits / 8));
    if opts.bits == 8 {
        let q = Quantizer8::new(opts.gamma);
        bytes.resize(film.pixels.len() * channels, 0);
        for (px, out) in film.pixels.iter().zip(bytes.chunks_exact_mut(channels)) {
            for c in 0..3 {
                out[c] = q.quantize(px[c]);
            }
            if opts.alpha {
                out[3] = (f64::from(px[3]).clamp(0.0, 1.0) * 255.0).round() as u8;
            }
        }
    } else {
        // PNG stores 16-bit samples big-endian; the encoder takes them in that order.
        for px in &film.pixels {
            for c in 0..channels {
                let v = if c == 3 {
                    f64::from(px[3]).clamp(0.0, 1.0)
                } else {
                    opts.gamma.encode(f64::from(px[c]))
                };
                bytes.extend(((v * 65535.0).round() as u16).to_be_bytes());
            }
        }
    }
    // Fast deflate: a render is written once and viewed; file size matters less than the
    // tens of milliseconds the default level costs at 840².
    PngEncoder::new_with_quality(out, CompressionType::Fast, FilterType::Adaptive)
        .write_image(&bytes, w, h, color_type)
        .map_err(|source| OutputError::Encode {
            path: path.to_path_buf(),
            source,
        })
}

/// Writes the film's depths as a single-channel PFM (`Pf`, little-endian, rows bottom to top
/// as the format requires; `+∞` for a miss), atomically.
pub fn write_pfm(film: &Film, path: &Path) -> Result<(), OutputError> {
    write_atomically(path, |out| encode_pfm(film, path, out))
}

/// Encodes the film's depths as PFM into `out`; `path` names it in errors.
pub(crate) fn encode_pfm(film: &Film, path: &Path, out: &mut dyn Write) -> Result<(), OutputError> {
    let depth = film.depth.as_ref().ok_or(OutputError::NoDepth)?;
    let (w, h) = (film.width as usize, film.height as usize);
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    write!(out, "Pf\n{w} {h}\n-1.0\n").map_err(io)?;
    for row in (0..h).rev() {
        for d in &depth[row * w..(row + 1) * w] {
            out.write_all(&d.to_le_bytes()).map_err(io)?;
        }
    }
    Ok(())
}

/// Reads a single-channel PFM written by [`write_pfm`]: `(width, height, rows top to bottom)`.
/// `None` if the bytes are not such a file.
pub fn read_pfm(bytes: &[u8]) -> Option<(usize, usize, Vec<f32>)> {
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        fields.push(std::str::from_utf8(&bytes[start..pos]).ok()?.to_string());
    }
    pos += 1; // the single whitespace after the scale
    if fields[0] != "Pf" {
        return None;
    }
    let w: usize = fields[1].parse().ok()?;
    let h: usize = fields[2].parse().ok()?;
    let scale: f64 = fields[3].parse().ok()?;
    let data = bytes.get(pos..pos + 4 * w * h)?;
    let vals: Vec<f32> = data
        .chunks_exact(4)
        .map(|c| {
            let b = [c[0], c[1], c[2], c[3]];
            if scale < 0.0 {
                f32::from_le_bytes(b)
            } else {
                f32::from_be_bytes(b)
            }
        })
        .collect();
    let mut rows = Vec::with_capacity(w * h);
    for r in (0..h).rev() {
        rows.extend_from_slice(&vals[r * w..(r + 1) * w]);
    }
    Some((w, h, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_endpoints_and_midpoint() {
        assert_eq!(Gamma::Srgb.encode(0.0), 0.0, "black");
        assert!((Gamma::Srgb.encode(1.0) - 1.0).abs() < 1e-12, "white");
        // Linear 0.5 encodes to about 0.735 (sRGB), i.e. 188 in 8 bits.
        assert_eq!((Gamma::Srgb.encode(0.5) * 255.0).round(), 188.0, "mid grey");
        assert_eq!(
            Gamma::Srgb.encode(2.0),
            Gamma::Srgb.encode(1.0),
            "clamped before encoding"
        );
        assert_eq!(Gamma::Power(1.0).encode(0.25), 0.25, "linear");
        // The threshold quantiser agrees with rounding the encoded value, away from ties.
        for gamma in [Gamma::Srgb, Gamma::Power(2.2)] {
            let q = Quantizer8::new(gamma);
            for i in 0..=2000 {
                let a = i as f64 / 2000.0;
                let direct = (gamma.encode(a) * 255.0).round() as u8;
                let fast = q.quantize(a as f32);
                let tie = ((gamma.encode(f64::from(a as f32)) * 255.0).fract() - 0.5).abs() < 1e-6;
                assert!(
                    fast == direct || tie,
                    "{gamma:?} a = {a}: {fast} vs {direct}"
                );
            }
            assert_eq!(q.quantize(-1.0), 0, "clamped below");
            assert_eq!(q.quantize(7.0), 255, "clamped above");
            assert_eq!(q.quantize(f32::NAN), 0, "NaN is black");
        }
    }

    #[test]
    fn bucketed_quantizer_is_the_binary_search() {
        // Every code boundary's neighbouring f32s, every bucket's edges, and a sweep of
        // [0, 1.5], for sRGB and two power laws: the count of thresholds ≤ a, as the binary
        // search over all 255 found it.
        for gamma in [Gamma::Srgb, Gamma::Power(2.2), Gamma::Power(0.45)] {
            let q = Quantizer8::new(gamma);
            let search = |a: f32| {
                if a.is_nan() {
                    0
                } else {
                    q.thresholds.partition_point(|&t| t <= f64::from(a)) as u8
                }
            };
            let mut values: Vec<f32> = Vec::new();
            for &t in &q.thresholds {
                let t = t as f32;
                values.extend([t, t.next_down(), t.next_up()]);
            }
            for b in 0..=0x3F81u32 {
                let least = f32::from_bits(b << 16);
                values.extend([least, least.next_down(), f32::from_bits((b << 16) | 0xFFFF)]);
            }
            values.extend((0..=150_000).map(|k| k as f32 * 1e-5));
            values.extend([
                0.0,
                -0.0,
                -1e-30,
                -1.0,
                1.0,
                7.0,
                f32::MIN_POSITIVE,
                f32::from_bits(1),
                f32::MAX,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::NAN,
            ]);
            for a in values {
                assert_eq!(q.quantize(a), search(a), "{gamma:?} at {a:e}");
            }
        }
    }

    #[test]
    fn pfm_round_trip_and_atomic_failure_keeps_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let film = Film {
            width: 2,
            height: 2,
            pixels: vec![[0.0; 4]; 4],
            depth: Some(vec![1.0, 2.0, 3.0, f32::INFINITY]),
        };
        let path = dir.path().join("d.pfm");
        write_pfm(&film, &path).unwrap();
        let (w, h, d) = read_pfm(&std::fs::read(&path).unwrap()).unwrap();
        assert_eq!((w, h), (2, 2), "size");
        assert_eq!(
            d,
            vec![1.0, 2.0, 3.0, f32::INFINITY],
            "top-to-bottom rows, +inf kept"
        );

        let png = dir.path().join("keep.png");
        std::fs::write(&png, b"old").unwrap();
        let err = write_png(
            &film,
            &png,
            &PngOptions {
                bits: 12,
                ..PngOptions::default()
            },
        );
        assert!(err.is_err(), "12-bit is refused");
        let failing = write_atomically(&png, |_| Err(OutputError::NoDepth));
        assert!(failing.is_err(), "writer error propagates");
        assert_eq!(
            std::fs::read(&png).unwrap(),
            b"old",
            "the old file survives"
        );
        let leftovers = std::fs::read_dir(dir.path()).unwrap().count();
        assert_eq!(leftovers, 2, "no temporary file left behind");
    }
}
