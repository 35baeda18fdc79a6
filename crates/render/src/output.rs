//! Image files: PNG (8 or 16 bits, gamma-encoded, optional alpha) and PFM depth maps, both
//! written atomically (temporary file in the same directory, then rename).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

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
}

/// Writes `path` atomically: `write` fills a temporary file next to it, which then replaces
/// `path` by a rename. On any failure the temporary file is removed and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), OutputError>,
) -> Result<(), OutputError> {
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().ok_or_else(|| {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "the path names no file",
        ))
    })?;
    let tmp = dir.join(format!(
        ".{}.{}.tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let file = File::create(&tmp).map_err(io)?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| io(e.into_error()))?;
        file.sync_all().map_err(io)?;
        std::fs::rename(&tmp, path).map_err(io)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Quantises encoded channel values to 8 bits through the decision thresholds of the
/// transfer function: code `k` is chosen for linear `a` when
/// `decode((k − ½)/255) ≤ a < decode((k + ½)/255)`, which is `round(255·encode(a))` computed
/// with 8 comparisons instead of a `powf` per channel.
struct Quantizer8 {
    /// `thresholds[k]` is the smallest linear value that encodes to code `k + 1`.
    thresholds: [f64; 255],
}

impl Quantizer8 {
    fn new(gamma: Gamma) -> Self {
        let mut thresholds = [0.0; 255];
        for (k, t) in thresholds.iter_mut().enumerate() {
            *t = gamma.decode((k as f64 + 0.5) / 255.0);
        }
        Quantizer8 { thresholds }
    }

    fn quantize(&self, a: f32) -> u8 {
        let a = f64::from(a);
        if a.is_nan() {
            return 0;
        }
        self.thresholds.partition_point(|&t| t <= a) as u8
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
    out: &mut impl Write,
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
        for px in &film.pixels {
            bytes.extend([q.quantize(px[0]), q.quantize(px[1]), q.quantize(px[2])]);
            if opts.alpha {
                bytes.push((f64::from(px[3]).clamp(0.0, 1.0) * 255.0).round() as u8);
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
    let depth = film.depth.as_ref().ok_or(OutputError::NoDepth)?;
    let (w, h) = (film.width as usize, film.height as usize);
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    write_atomically(path, |out| {
        write!(out, "Pf\n{w} {h}\n-1.0\n").map_err(io)?;
        for row in (0..h).rev() {
            for d in &depth[row * w..(row + 1) * w] {
                out.write_all(&d.to_le_bytes()).map_err(io)?;
            }
        }
        Ok(())
    })
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
