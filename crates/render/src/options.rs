//! [`RenderOptions`]: what the user asked for on top of the scene (the CLI's parsed form).

use std::path::{Path, PathBuf};

use crate::methods::{PatchMethod, RootMethods};
use crate::output::PngOptions;
use crate::scene::Scene;

/// Options that override or complete the scene's own settings. The command line is parsed into
/// a raw argument struct and then into this; library users fill it directly.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Output PNG; overrides the scene's `#save`. See [`RenderOptions::output_path`].
    pub output: Option<PathBuf>,
    /// Image size; overrides the scene's `#viewport Size`.
    pub size: Option<[u32; 2]>,
    /// Worker threads; `None` uses every core.
    pub threads: Option<usize>,
    /// `N` for `N × N` stratified samples per pixel (≥ 1).
    pub samples: u32,
    /// Where to write primary-hit distances as PFM, if anywhere.
    pub depth: Option<PathBuf>,
    /// PNG bit depth, alpha and gamma.
    pub png: PngOptions,
    /// Elimination method for every Bézier patch, overriding the scene's `Method`.
    pub patch_method: Option<PatchMethod>,
    /// Root finder of the implicit surfaces.
    pub roots: RootMethods,
}

impl Default for RenderOptions {
    /// Render the scene as written: its size and file name, one sample, all cores, 8-bit sRGB.
    fn default() -> Self {
        RenderOptions {
            output: None,
            size: None,
            threads: None,
            samples: 1,
            depth: None,
            png: PngOptions::default(),
            patch_method: None,
            roots: RootMethods::default(),
        }
    }
}

impl RenderOptions {
    /// The image size: `--size`, else the scene's viewport.
    pub fn image_size(&self, scene: &Scene) -> [u32; 2] {
        self.size.unwrap_or(scene.viewport.size)
    }

    /// Where the PNG goes: `-o`, else the scene's `#save File Name`, else the scene file's name
    /// with the extension `.png` in the current directory (`out.png` without a scene path).
    pub fn output_path(&self, scene: &Scene, scene_path: Option<&Path>) -> PathBuf {
        if let Some(o) = &self.output {
            return o.clone();
        }
        if let Some(o) = &scene.output {
            return o.clone();
        }
        match scene_path.and_then(Path::file_stem) {
            Some(stem) => PathBuf::from(stem).with_extension("png"),
            None => PathBuf::from("out.png"),
        }
    }
}
