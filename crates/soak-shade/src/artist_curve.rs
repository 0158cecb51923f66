//! A Γ curve drawn by an artist: a 1-D table, read piecewise linearly.

use crate::error::CurveError;
use crate::fresnel::unit;

/// Number of samples an [`ArtistCurveGpu`] holds.
pub const ARTIST_CURVE_GPU_SAMPLES: usize = 64;

/// A non-decreasing 1-D table `s₀ = 0 ≤ s₁ ≤ … ≤ s_{N−1} = 1` with sample
/// `i` at saturation `h = i/(N − 1)`, read by linear interpolation: a Γ
/// curve an artist paints (e.g. one row of a greyscale image).
///
/// Input is validated, not repaired: a decreasing step, a sample that is
/// not finite, or ends other than exactly 0 and 1 are errors naming the
/// sample. [`ArtistCurve::normalized`] rescales a monotone table whose ends
/// are off (a gradient painted from 12 to 240) instead.
///
/// # Example
/// ```
/// use soak_shade::ArtistCurve;
/// let curve = ArtistCurve::new(vec![0.0, 0.7, 0.9, 1.0]).unwrap();
/// assert_eq!(curve.eval(1.0 / 3.0), 0.7);
/// assert!((curve.eval(1.0 / 6.0) - 0.35).abs() < 1e-12);
/// assert!(ArtistCurve::new(vec![0.0, 0.6, 0.5, 1.0]).is_err()); // not monotone
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "Vec<f64>", into = "Vec<f64>")]
pub struct ArtistCurve {
    samples: Vec<f64>,
}

impl ArtistCurve {
    /// A curve through `samples`, uniformly spaced over `h ∈ [0, 1]`.
    ///
    /// # Errors
    /// [`CurveError`] if there are fewer than 2 samples, a sample is not
    /// finite, a sample is below its predecessor, or the first sample is not
    /// exactly 0 or the last not exactly 1.
    pub fn new(samples: Vec<f64>) -> Result<Self, CurveError> {
        check_monotone(&samples)?;
        let (first, last) = (samples[0], samples[samples.len() - 1]);
        if first != 0.0 || last != 1.0 {
            return Err(CurveError::Ends { first, last });
        }
        Ok(Self { samples })
    }

    /// A curve through `samples` after the affine rescaling
    /// `(s − s₀)/(s_{N−1} − s₀)` that pins the ends to 0 and 1.
    ///
    /// # Errors
    /// As [`ArtistCurve::new`] for length, finiteness and monotonicity;
    /// [`CurveError::Flat`] if all samples are equal.
    pub fn normalized(samples: Vec<f64>) -> Result<Self, CurveError> {
        check_monotone(&samples)?;
        let (first, last) = (samples[0], samples[samples.len() - 1]);
        if last <= first {
            return Err(CurveError::Flat { value: first });
        }
        let span = last - first;
        let mut s: Vec<f64> = samples.iter().map(|v| (v - first) / span).collect();
        let n = s.len();
        s[0] = 0.0;
        s[n - 1] = 1.0;
        // Rescaling is monotone, but rounding may overshoot 1 just before the end.
        for v in &mut s[1..n - 1] {
            *v = v.min(1.0);
        }
        Self::new(s)
    }

    /// A curve from 8-bit samples (e.g. one row of an L8 image), `v/255`.
    ///
    /// # Errors
    /// As [`ArtistCurve::new`]: the row must rise from 0 to 255.
    pub fn from_u8(row: &[u8]) -> Result<Self, CurveError> {
        Self::new(row.iter().map(|&v| f64::from(v) / 255.0).collect())
    }

    /// A curve from 16-bit samples (e.g. one row of an L16 image), `v/65535`.
    ///
    /// # Errors
    /// As [`ArtistCurve::new`]: the row must rise from 0 to 65535.
    pub fn from_u16(row: &[u16]) -> Result<Self, CurveError> {
        Self::new(row.iter().map(|&v| f64::from(v) / 65535.0).collect())
    }

    /// A curve from row `row` (0 = top) of an image, one sample per pixel,
    /// left to right, reading the first channel (grey, or red for colour
    /// images) as stored, normalised to `[0, 1]` (no sRGB decoding: paint the
    /// curve in a linear greyscale image).
    ///
    /// # Errors
    /// [`CurveError::RowOutOfBounds`] for a missing row, otherwise as
    /// [`ArtistCurve::new`].
    pub fn from_image_row(image: &image::DynamicImage, row: u32) -> Result<Self, CurveError> {
        let height = image.height();
        if row >= height {
            return Err(CurveError::RowOutOfBounds { row, height });
        }
        match image {
            image::DynamicImage::ImageLuma8(img) => {
                let row: Vec<u8> = (0..img.width()).map(|x| img.get_pixel(x, row).0[0]).collect();
                Self::from_u8(&row)
            }
            image::DynamicImage::ImageLuma16(img) => {
                let row: Vec<u16> = (0..img.width()).map(|x| img.get_pixel(x, row).0[0]).collect();
                Self::from_u16(&row)
            }
            other => {
                let rgba = other.to_rgba32f();
                let samples = (0..rgba.width())
                    .map(|x| f64::from(rgba.get_pixel(x, row).0[0]))
                    .collect();
                Self::new(samples)
            }
        }
    }

    /// The samples, `s₀ = 0 … s_{N−1} = 1`.
    pub fn samples(&self) -> &[f64] {
        &self.samples
    }

    /// Γ(h): linear interpolation between the samples around `h·(N − 1)`.
    /// `h` is clamped to `[0, 1]` (NaN counts as 0). Exact at the ends,
    /// non-decreasing, and within each segment never outside its two samples.
    pub fn eval(&self, h: f64) -> f64 {
        let h = unit(h);
        let n = self.samples.len();
        if h <= 0.0 {
            return 0.0;
        }
        if h >= 1.0 {
            return 1.0;
        }
        let x = h * (n - 1) as f64;
        // x ∈ [0, n − 1); truncation is floor here.
        let i = (x as usize).min(n - 2);
        let t = x - i as f64;
        let (a, b) = (self.samples[i], self.samples[i + 1]);
        // Never outside [a, b]: keeps Γ monotone across segment joins.
        (a + (b - a) * t).max(a).min(b)
    }

    /// The curve for the GPU: [`ARTIST_CURVE_GPU_SAMPLES`] slots; a curve of
    /// at most that many samples is copied exactly, a longer one is
    /// resampled uniformly (which may round off its corners).
    pub fn to_gpu(&self) -> ArtistCurveGpu {
        let mut samples = [0.0f32; ARTIST_CURVE_GPU_SAMPLES];
        let len = if self.samples.len() <= ARTIST_CURVE_GPU_SAMPLES {
            for (d, s) in samples.iter_mut().zip(&self.samples) {
                *d = *s as f32;
            }
            self.samples.len()
        } else {
            let last = (ARTIST_CURVE_GPU_SAMPLES - 1) as f64;
            for (i, d) in samples.iter_mut().enumerate() {
                *d = self.eval(i as f64 / last) as f32;
            }
            ARTIST_CURVE_GPU_SAMPLES
        };
        ArtistCurveGpu {
            samples,
            len: len as u32,
            _pad: [0; 3],
        }
    }
}

impl TryFrom<Vec<f64>> for ArtistCurve {
    type Error = CurveError;
    fn try_from(samples: Vec<f64>) -> Result<Self, CurveError> {
        Self::new(samples)
    }
}

impl From<ArtistCurve> for Vec<f64> {
    fn from(curve: ArtistCurve) -> Self {
        curve.samples
    }
}

fn check_monotone(samples: &[f64]) -> Result<(), CurveError> {
    if samples.len() < 2 {
        return Err(CurveError::TooShort { len: samples.len() });
    }
    for (index, &value) in samples.iter().enumerate() {
        if !value.is_finite() {
            return Err(CurveError::NotFinite { index, value });
        }
        if index > 0 && value < samples[index - 1] {
            return Err(CurveError::Decreasing {
                index,
                value,
                previous: samples[index - 1],
            });
        }
    }
    Ok(())
}

/// An [`ArtistCurve`] laid out for a WGSL uniform or storage buffer,
/// mirrored field by field by `ArtistCurveGpu` in
/// [`WET_OPTICS_WGSL`](crate::WET_OPTICS_WGSL) (there `samples` is
/// `array<vec4<f32>, 16>`; 272 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ArtistCurveGpu {
    /// The first `len` slots hold the curve's samples, uniformly spaced over
    /// `h ∈ [0, 1]`; the rest are unused.
    pub samples: [f32; ARTIST_CURVE_GPU_SAMPLES],
    /// Number of samples in use, in `2..=64`.
    pub len: u32,
    /// Padding to a 16-byte multiple.
    pub _pad: [u32; 3],
}

impl ArtistCurveGpu {
    /// Γ(h) as the WGSL `gamma_artist` computes it, in f32 (reference for
    /// GPU parity tests). A `len` outside `2..=64` is clamped into it.
    pub fn eval(&self, h: f32) -> f32 {
        #[allow(clippy::manual_clamp)] // NaN → 0, as on the CPU side
        let h = h.max(0.0).min(1.0);
        if h <= 0.0 {
            return 0.0;
        }
        if h >= 1.0 {
            return 1.0;
        }
        let n = (self.len as usize).clamp(2, ARTIST_CURVE_GPU_SAMPLES);
        let x = h * (n - 1) as f32;
        let i = (x as usize).min(n - 2);
        let t = x - i as f32;
        let (a, b) = (self.samples[i], self.samples[i + 1]);
        (a + (b - a) * t).max(a).min(b)
    }
}
