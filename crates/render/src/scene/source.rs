//! Bounded reads of the files a scene names: the scene itself, image textures and Bézier
//! control points.
//!
//! Only regular files are read: a FIFO would block the program forever when nothing writes
//! to it, and a device such as `/dev/zero` never ends. A regular file is read up to its
//! limit and refused beyond it, so a huge file costs at most the limit in memory and never
//! blocks; there is no timeout to tune.

use std::io::Read;
use std::path::Path;

/// The largest scene file read, in bytes (16 MiB): hand-written scenes are a few kilobytes,
/// and 16 MiB holds an `Equation` of degree 128 written out term by term (at most 366 145
/// terms of about 25 characters: 9 MB).
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// The largest texture file read, in bytes (64 MiB): a raw RGB texture of 4096 × 4096
/// texels is 48 MiB. Decoded PNG textures are further bounded by [`MAX_TEXTURE_TEXELS`].
pub const MAX_TEXTURE_BYTES: u64 = 64 << 20;

/// The most texels of a decoded texture (2²⁴ = 4096 × 4096): the scene keeps 24 bytes per
/// texel (three `f64`), 384 MiB at the limit.
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 24;

/// The largest `.bpt` or control-point file read, in bytes (64 MiB): the Utah teapot's 32
/// bicubic patches take 15 kB, so this is thousands of such models.
pub const MAX_CONTROL_POINT_BYTES: u64 = 64 << 20;

/// The largest OBJ mesh file read, in bytes (256 MiB): about four million triangles with
/// normals; the prepared mesh keeps a few hundred bytes per triangle.
pub const MAX_MESH_BYTES: u64 = 256 << 20;

/// Reads all of `path`, a regular file of at most `limit` bytes.
///
/// # Errors
/// The I/O error, or `InvalidInput` for a file that is not regular (directory, FIFO,
/// device, socket) or longer than `limit`; each says which.
pub(crate) fn read_bounded(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::{Error, ErrorKind};
    // `metadata` follows symbolic links; opening a FIFO would block, so check first.
    let meta = std::fs::metadata(path)?;
    if meta.is_dir() {
        return Err(Error::new(ErrorKind::InvalidInput, "is a directory"));
    }
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (a FIFO, device or socket is not read)",
        ));
    }
    let too_long = || {
        Error::new(
            ErrorKind::InvalidInput,
            format!("longer than the limit of {limit} bytes"),
        )
    };
    if meta.len() > limit {
        return Err(too_long());
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // The cap also holds when the file grows between `metadata` and the read.
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_long());
    }
    Ok(bytes)
}
