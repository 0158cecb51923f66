//! Writing the atlas' position and area-vector textures as images (the
//! formats are described on [`Atlas::write_image`]).

use std::path::Path;

use image::{ImageBuffer, Rgba, Rgba32FImage};

use crate::atlas::Atlas;
use crate::error::ExportError;

/// Which per-texel quantity to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AtlasImage {
    /// Object-space position (the thesis' TP).
    Position,
    /// Oriented area `A_i` (the thesis' TVA).
    AreaVector,
}

impl Atlas {
    /// The chosen texture as W×H RGBA f32 (alpha 1 on covered texels), raw values.
    pub fn image_f32(&self, which: AtlasImage) -> Rgba32FImage {
        let mut img = Rgba32FImage::new(self.width, self.height);
        for i in 0..self.len() {
            let [x, y] = self.texels[i];
            let v = match which {
                AtlasImage::Position => {
                    let p = self.position(i);
                    [p.x as f32, p.y as f32, p.z as f32]
                }
                AtlasImage::AreaVector => self.area_vectors.get(i),
            };
            img.put_pixel(x as u32, y as u32, Rgba([v[0], v[1], v[2], 1.0]));
        }
        img
    }

    /// Writes the chosen texture to `path` (`.exr`: raw f32; `.png`: 16-bit, normalised).
    ///
    /// `.exr` files hold the raw f32 values (object space, m and m²); `.png`
    /// files are 16-bit and normalised for looking at: positions mapped from
    /// the bounding box to [0, 1], area vectors as `n·½ + ½` with the
    /// relative texel area in alpha. Uncovered texels are zero (transparent
    /// in PNG).
    pub fn write_image(&self, which: AtlasImage, path: &Path) -> Result<(), ExportError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let img_err = |source| ExportError::Image {
            path: path.to_path_buf(),
            source,
        };
        match ext.as_deref() {
            Some("exr") => self.image_f32(which).save(path).map_err(img_err),
            Some("png") => {
                let mut img: ImageBuffer<Rgba<u16>, Vec<u16>> = ImageBuffer::new(self.width, self.height);
                let q = |v: f64| (v.clamp(0.0, 1.0) * 65535.0).round() as u16;
                let r = self.bounding_radius.max(1e-300);
                let amax = self
                    .area_vectors
                    .iter()
                    .map(|a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt())
                    .fold(0.0f32, f32::max)
                    .max(f32::MIN_POSITIVE) as f64;
                for i in 0..self.len() {
                    let [x, y] = self.texels[i];
                    let px = match which {
                        AtlasImage::Position => {
                            let p = self.local_positions.get(i).map(|c| c as f64 / (2.0 * r) + 0.5);
                            [q(p[0]), q(p[1]), q(p[2]), 65535]
                        }
                        AtlasImage::AreaVector => {
                            let a = self.area_vectors.get(i).map(|c| c as f64);
                            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(1e-300);
                            [
                                q(a[0] / n * 0.5 + 0.5),
                                q(a[1] / n * 0.5 + 0.5),
                                q(a[2] / n * 0.5 + 0.5),
                                q(n / amax),
                            ]
                        }
                    };
                    img.put_pixel(x as u32, y as u32, Rgba(px));
                }
                img.save(path).map_err(img_err)
            }
            _ => Err(ExportError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

impl crate::mesh::Mesh {
    /// The mesh as Wavefront OBJ text (`v`, `vt` with OBJ's upward `v`, `f`).
    pub fn to_obj(&self) -> String {
        use std::fmt::Write;
        let mut s = String::with_capacity(self.positions.len() * 64 + self.triangles.len() * 32);
        let _ = writeln!(s, "# {}", self.name);
        for p in &self.positions {
            let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
        }
        if let Some(uvs) = &self.uvs {
            for uv in uvs {
                let _ = writeln!(s, "vt {} {}", uv.x, 1.0 - uv.y);
            }
        }
        for t in &self.triangles {
            let [a, b, c] = t.map(|v| v + 1);
            if self.uvs.is_some() {
                let _ = writeln!(s, "f {a}/{a} {b}/{b} {c}/{c}");
            } else {
                let _ = writeln!(s, "f {a} {b} {c}");
            }
        }
        s
    }
}
