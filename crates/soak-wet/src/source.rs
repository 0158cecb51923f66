//! Where liquid comes from besides the water a body sits in: rain over a
//! region, a splash at a point, and an artist-painted liquid texture.

use std::path::Path;

use nalgebra::Point3;
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::error::{WetError, non_negative, positive};

/// A region of the world (y up), m.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Region {
    /// All of space.
    #[default]
    Everywhere,
    /// A vertical cylinder: points whose horizontal distance to `center`
    /// (world x, z) is at most `radius`.
    Disc {
        /// World (x, z) of the axis, m.
        center: [f64; 2],
        /// Radius, m.
        radius: f64,
    },
    /// An axis-aligned box.
    Box {
        /// Lower corner, m.
        min: [f64; 3],
        /// Upper corner, m.
        max: [f64; 3],
    },
}

impl Region {
    /// Whether world point `p` lies in the region.
    #[inline]
    pub fn contains(&self, p: &Point3<f64>) -> bool {
        match *self {
            Region::Everywhere => true,
            Region::Disc { center, radius } => {
                let (dx, dz) = (p.x - center[0], p.z - center[1]);
                dx * dx + dz * dz <= radius * radius
            }
            Region::Box { min, max } => (0..3).all(|k| p[k] >= min[k] && p[k] <= max[k]),
        }
    }

    /// Checks the numbers are finite, radii non-negative and boxes not inverted.
    pub fn validate(&self) -> Result<(), WetError> {
        match *self {
            Region::Everywhere => Ok(()),
            Region::Disc { center, radius } => {
                for c in center {
                    if !c.is_finite() {
                        return Err(WetError::parameter("region.center", c, "finite"));
                    }
                }
                non_negative("region.radius", radius)
            }
            Region::Box { min, max } => {
                for k in 0..3 {
                    if !(min[k].is_finite() && max[k].is_finite() && min[k] <= max[k]) {
                        return Err(WetError::parameter(
                            "region.max",
                            max[k],
                            "finite and >= region.min",
                        ));
                    }
                }
                Ok(())
            }
        }
    }
}

/// Rain: liquid falling vertically at `rate` over `region`.
///
/// A dry (not submerged) texel in the region whose outward normal has a
/// world up component `n_y > 0` gains `rate · n_y · dt` of liquid per area
/// (its horizontal projection catches the rain), up to saturation. Other
/// bodies do not shelter it: there is no occlusion test.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rain {
    /// Precipitation rate as a depth per time on a horizontal surface, m/s
    /// (1 mm/h = 2.78e-7 m/s). Zero for no rain.
    pub rate: f64,
    /// Where it rains.
    #[serde(default)]
    pub region: Region,
}

impl Default for Rain {
    fn default() -> Self {
        Self::none()
    }
}

impl Rain {
    /// No rain.
    pub fn none() -> Self {
        Self {
            rate: 0.0,
            region: Region::Everywhere,
        }
    }

    /// Rain of `mm` millimetres an hour everywhere.
    pub fn mm_per_hour(mm: f64) -> Self {
        Self {
            rate: mm * 1e-3 / 3600.0,
            region: Region::Everywhere,
        }
    }

    /// The same rain over `region`.
    pub fn over(mut self, region: Region) -> Self {
        self.region = region;
        self
    }

    /// Checks the rate is finite and non-negative and the region valid.
    pub fn validate(&self) -> Result<(), WetError> {
        non_negative("rain.rate", self.rate)?;
        self.region.validate()
    }
}

/// A splash: `volume` of liquid landing around a world point.
///
/// Texels within `radius` of `center` share the volume with weights
/// `a_i (1 − r²/R²)²` (a smooth bump); what would exceed a texel's
/// saturation runs off and is lost.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Splash {
    /// World position, m.
    pub center: [f64; 3],
    /// Radius, m.
    pub radius: f64,
    /// Volume of liquid, m³.
    pub volume: f64,
}

impl Splash {
    /// Checks the centre is finite, the radius positive and the volume non-negative.
    pub fn validate(&self) -> Result<(), WetError> {
        for c in self.center {
            if !c.is_finite() {
                return Err(WetError::parameter("splash.center", c, "finite"));
            }
        }
        positive("splash.radius", self.radius)?;
        non_negative("splash.volume", self.volume)
    }
}

/// A single-channel image laid over the UV square: `width × height` values,
/// row `y` holding texels with `v·H` in `[y, y+1)` (the atlas' convention).
#[derive(Clone, Debug, PartialEq)]
pub struct LiquidImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Values row by row, dimensionless (usually in [0, 1]).
    pub values: Vec<f32>,
}

/// Widest and tallest image [`LiquidImage::decode`] reads, pixels.
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// Most memory one decode may allocate for pixels, bytes.
pub const MAX_IMAGE_BYTES: u64 = 1 << 30;
/// Largest OpenEXR block (a tile or a group of scan lines, all channels)
/// [`LiquidImage::decode`] accepts, bytes. The OpenEXR reader allocates a
/// block's worth of memory from the header alone, before reading pixels.
pub const MAX_EXR_BLOCK_BYTES: u64 = 64 << 20;

impl LiquidImage {
    /// Reads an image file (PNG or OpenEXR) as luminance in [0, 1]
    /// (colour images are converted to luma). See [`LiquidImage::decode`].
    pub fn open(path: &Path) -> Result<Self, WetError> {
        let bytes = std::fs::read(path).map_err(|e| WetError::Image {
            path: Some(path.to_path_buf()),
            reason: e.to_string(),
        })?;
        Self::decode(&bytes, Some(path))
    }

    /// Decodes PNG or OpenEXR bytes as luminance (colour images are
    /// converted to luma); `path` names the file in errors. Images over
    /// [`MAX_IMAGE_SIDE`] pixels a side or [`MAX_IMAGE_BYTES`] of pixels, and
    /// OpenEXR files whose blocks exceed [`MAX_EXR_BLOCK_BYTES`], are errors.
    pub fn decode(bytes: &[u8], path: Option<&Path>) -> Result<Self, WetError> {
        let err = |reason: String| WetError::Image {
            path: path.map(Path::to_path_buf),
            reason,
        };
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| err(e.to_string()))?;
        if reader.format() == Some(image::ImageFormat::OpenExr) {
            check_exr_blocks(bytes).map_err(err)?;
        }
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_IMAGE_SIDE);
        limits.max_image_height = Some(MAX_IMAGE_SIDE);
        limits.max_alloc = Some(MAX_IMAGE_BYTES);
        reader.limits(limits);
        let luma = reader.decode().map_err(|e| err(e.to_string()))?.to_luma32f();
        Ok(Self {
            width: luma.width(),
            height: luma.height(),
            values: luma.into_raw(),
        })
    }

    /// Per-texel liquid `h_i = scale · value` (m), sampled at each texel's
    /// centre (nearest pixel) and clamped to `[0, saturation]`. `scale` is
    /// the liquid (m³/m² = m) a value of 1 stands for, usually the saturation.
    pub fn sample(&self, atlas: &Atlas, scale: f64, saturation: f64) -> Result<Vec<f64>, WetError> {
        if self.width == 0
            || self.height == 0
            || self.values.len() != self.width as usize * self.height as usize
        {
            return Err(WetError::Image {
                path: None,
                reason: format!(
                    "{} values for a {}x{} image",
                    self.values.len(),
                    self.width,
                    self.height
                ),
            });
        }
        non_negative("image.scale", scale)?;
        non_negative("image.saturation", saturation)?;
        if let Some(i) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(WetError::ChannelValue {
                what: "liquid image pixel",
                texel: i,
                value: self.values[i] as f64,
                expected: "finite values",
            });
        }
        Ok(atlas
            .sample_image(&self.values, self.width, self.height)
            .into_iter()
            .map(|v| (v as f64 * scale).clamp(0.0, saturation))
            .collect())
    }
}

/// Rejects OpenEXR headers whose blocks would make the reader allocate more
/// than [`MAX_EXR_BLOCK_BYTES`] (a tiny file can declare 65,600 × 71 million
/// pixel tiles), naming the layer and the block.
fn check_exr_blocks(bytes: &[u8]) -> Result<(), String> {
    use exr::meta::BlockDescription;
    let meta = exr::meta::MetaData::read_from_buffered(bytes, false).map_err(|e| e.to_string())?;
    for (layer, header) in meta.headers.iter().enumerate() {
        let (what, w, h) = match header.blocks {
            BlockDescription::Tiles(tiles) => ("tile", tiles.tile_size.0, tiles.tile_size.1),
            BlockDescription::ScanLines => (
                "scan-line block",
                header.layer_size.0,
                header.compression.scan_lines_per_block(),
            ),
        };
        let size = (w as u64)
            .checked_mul(h as u64)
            .and_then(|px| px.checked_mul(header.channels.bytes_per_pixel as u64));
        if size.is_none_or(|b| b > MAX_EXR_BLOCK_BYTES) {
            return Err(format!(
                "OpenEXR layer {layer}: a {what} of {w}x{h} pixels and {} bytes per pixel exceeds {} MiB",
                header.channels.bytes_per_pixel,
                MAX_EXR_BLOCK_BYTES >> 20
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_contain_what_they_should() {
        let p = Point3::new(1.0, 5.0, 1.0);
        assert!(Region::Everywhere.contains(&p));
        assert!(
            Region::Disc {
                center: [0.0, 0.0],
                radius: 1.5
            }
            .contains(&p)
        );
        assert!(
            !Region::Disc {
                center: [0.0, 0.0],
                radius: 1.0
            }
            .contains(&p)
        );
        assert!(
            Region::Box {
                min: [0.0; 3],
                max: [2.0, 6.0, 2.0]
            }
            .contains(&p)
        );
        assert!(
            Region::Box {
                min: [1.0, 0.0, 0.0],
                max: [0.0, 1.0, 1.0]
            }
            .validate()
            .is_err()
        );
        assert!((Rain::mm_per_hour(3.6).rate - 1e-6).abs() < 1e-20);
    }
}
