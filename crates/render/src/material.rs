//! Surface colour lookup: `C_s` from the material or its texture (Stam Annexe B `ColTexture`).

use glam::DVec2;

use crate::scene::{Material, Rgb, Texture};

/// The surface colour `C_s` at surface parameters `uv` (Stam eq. 2.7–2.8): the colour of the
/// material's texture where it has one and the shape defines `uv`, else `material.cs`.
///
/// Stam textures only `TEXTURE` objects; here any illumination level may carry a texture (a
/// checkered mirror floor), and `TEXTURE` without one is refused by validation.
pub(crate) fn surface_color(material: &Material, textures: &[Texture], uv: Option<DVec2>) -> Rgb {
    match (material.texture.and_then(|i| textures.get(i)), uv) {
        (Some(tex), Some(uv)) => texture_color(tex, uv),
        _ => material.cs,
    }
}

/// The colour of `tex` at plane coordinates `uv`.
///
/// Image textures tile the plane as Stam's `ColTexture` does: one copy per `unit` of length,
/// indexed by `|u|` and `|v|` (so the image is mirrored across the plane's axes, as in his
/// program). Checkers alternate with period `2·unit`.
pub(crate) fn texture_color(tex: &Texture, uv: DVec2) -> Rgb {
    match tex {
        Texture::Image(img) => {
            let (w, h) = (img.width as usize, img.height as usize);
            if w == 0 || h == 0 || img.texels.len() < w * h {
                return Rgb::ZERO;
            }
            let fx = (uv.x.abs() / img.unit * w as f64) as usize % w;
            let fy = (uv.y.abs() / img.unit * h as f64) as usize % h;
            img.texels[fy * w + fx]
        }
        Texture::Checker(c) => {
            let i = (uv.x / c.unit).floor() as i64 + (uv.y / c.unit).floor() as i64;
            c.colors[i.rem_euclid(2) as usize]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::CheckerTexture;

    #[test]
    fn checker_alternates() {
        let t = Texture::Checker(CheckerTexture {
            unit: 1.0,
            colors: [Rgb::ZERO, Rgb::ONE],
        });
        assert_eq!(
            texture_color(&t, DVec2::new(0.5, 0.5)),
            Rgb::ZERO,
            "origin square"
        );
        assert_eq!(
            texture_color(&t, DVec2::new(1.5, 0.5)),
            Rgb::ONE,
            "neighbour"
        );
        assert_eq!(
            texture_color(&t, DVec2::new(-0.5, 0.5)),
            Rgb::ONE,
            "negative side"
        );
        assert_eq!(
            texture_color(&t, DVec2::new(-0.5, -0.5)),
            Rgb::ZERO,
            "diagonal"
        );
    }
}
