//! Procedural textures for demos, tests and the material sweep: value
//! noise, blotchy liquid textures, speckled and planked albedos.
//! Deterministic for a given seed.

use super::colour::linear_to_pixel;
use super::scene::LiquidImage;

fn hash(ix: i64, iy: i64, seed: u64) -> f64 {
    let mut h = (ix as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (iy as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ seed.wrapping_mul(0x1656_67B1_9E37_79F9);
    h ^= h >> 33;
    h = h.wrapping_mul(0xFF51_AFD7_ED55_8CCD);
    h ^= h >> 33;
    h = h.wrapping_mul(0xC4CE_B9FE_1A85_EC53);
    h ^= h >> 33;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// Smooth value noise in `[0, 1]` on a unit lattice.
pub fn value_noise(x: f64, y: f64, seed: u64) -> f64 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i64, fy as i64);
    let (tx, ty) = (x - fx, y - fy);
    let s = |t: f64| t * t * (3.0 - 2.0 * t);
    let (sx, sy) = (s(tx), s(ty));
    let a = hash(ix, iy, seed);
    let b = hash(ix + 1, iy, seed);
    let c = hash(ix, iy + 1, seed);
    let d = hash(ix + 1, iy + 1, seed);
    let top = a + (b - a) * sx;
    let bottom = c + (d - c) * sx;
    top + (bottom - top) * sy
}

/// Fractal sum of `octaves` value noises (each twice the frequency and
/// half the amplitude of the last), normalised to `[0, 1]`.
pub fn fractal_noise(x: f64, y: f64, octaves: u32, seed: u64) -> f64 {
    let (mut sum, mut norm, mut amp, mut freq) = (0.0, 0.0, 1.0, 1.0);
    for o in 0..octaves.max(1) {
        sum += amp * value_noise(x * freq, y * freq, seed.wrapping_add(u64::from(o) * 7919));
        norm += amp;
        amp *= 0.5;
        freq *= 2.0;
    }
    sum / norm
}

/// A liquid texture of wet blotches: fractal noise of `features` blobs
/// across the image, thresholded so that a fraction `coverage` (in
/// `[0, 1]`) of the texels is wet, with soft edges (saturation ramps over
/// ±`softness` of the noise value, e.g. 0.04).
pub fn blotches(
    width: u32,
    height: u32,
    features: f64,
    coverage: f64,
    softness: f64,
    seed: u64,
) -> LiquidImage {
    let (w, h) = (width.max(1), height.max(1));
    let noise: Vec<f64> = (0..w * h)
        .map(|i| {
            let (x, y) = (f64::from(i % w) / f64::from(w), f64::from(i / w) / f64::from(h));
            fractal_noise(x * features, y * features, 5, seed)
        })
        .collect();
    let mut sorted = noise.clone();
    sorted.sort_by(f64::total_cmp);
    let c = coverage.clamp(0.0, 1.0);
    let k = (((1.0 - c) * sorted.len() as f64) as usize).min(sorted.len() - 1);
    let threshold = if c <= 0.0 {
        f64::INFINITY
    } else if c >= 1.0 {
        f64::NEG_INFINITY
    } else {
        sorted[k]
    };
    let soft = softness.max(1e-6);
    let data = noise
        .iter()
        .map(|&v| {
            let t = ((v - threshold + soft) / (2.0 * soft)).clamp(0.0, 1.0);
            (t * t * (3.0 - 2.0 * t)) as f32
        })
        .collect();
    LiquidImage::from_raw(w, h, data).expect("sized by construction")
}

/// An sRGB albedo texture: linear `colour` modulated by fractal noise of
/// relative amplitude `contrast` (e.g. 0.25), with `features` blobs across.
pub fn speckled(
    width: u32,
    height: u32,
    colour: [f64; 3],
    contrast: f64,
    features: f64,
    seed: u64,
) -> image::RgbaImage {
    image::RgbaImage::from_fn(width.max(1), height.max(1), |x, y| {
        let (u, v) = (f64::from(x) / f64::from(width), f64::from(y) / f64::from(height));
        let n = fractal_noise(u * features, v * features, 6, seed) - 0.5;
        let f = 1.0 + 2.0 * contrast * n;
        linear_to_pixel(colour.map(|c| (c * f).clamp(0.0, 1.0)))
    })
}

/// An sRGB albedo texture of `planks` wooden planks along u, with grain,
/// seams and per-plank tone: for hulls and decks.
pub fn wood_planks(width: u32, height: u32, planks: u32, base: [f64; 3], seed: u64) -> image::RgbaImage {
    let planks = planks.max(1);
    image::RgbaImage::from_fn(width.max(1), height.max(1), |x, y| {
        let (u, v) = (f64::from(x) / f64::from(width), f64::from(y) / f64::from(height));
        let p = v * f64::from(planks);
        let row = p.floor() as i64;
        let across = p - p.floor();
        // Planks are staggered: each row has its own butt joint.
        let joint = hash(row, 7, seed);
        let along = (u + joint).fract();
        let tone = 0.8 + 0.4 * hash(row, (along * 3.0).floor() as i64, seed);
        let grain = fractal_noise(u * 60.0, p * 4.0 + 13.0 * joint, 4, seed ^ 0x55);
        let stripes = 0.5 + 0.5 * (u * 90.0 + 6.0 * grain + 3.0 * joint).sin();
        let mut f = tone * (0.82 + 0.18 * stripes) * (0.9 + 0.2 * grain);
        let seam = across.min(1.0 - across) * f64::from(height) / f64::from(planks);
        if seam < 1.0 {
            f *= 0.45;
        }
        let butt = (along * 3.0).fract();
        if !(0.004..=0.996).contains(&butt) {
            f *= 0.5;
        }
        linear_to_pixel(base.map(|c| (c * f).clamp(0.0, 1.0)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blotches_cover_what_was_asked() {
        for coverage in [0.0, 0.3, 0.7, 1.0] {
            let img = blotches(64, 64, 4.0, coverage, 0.01, 3);
            let wet = img.as_raw().iter().filter(|v| **v > 0.5).count() as f64 / 4096.0;
            assert!((wet - coverage).abs() < 0.05, "{coverage}: {wet}");
        }
    }

    #[test]
    fn noise_is_in_range_and_deterministic() {
        for i in 0..1000 {
            let (x, y) = (f64::from(i) * 0.37, f64::from(i) * 0.11);
            let v = fractal_noise(x, y, 5, 9);
            assert!((0.0..=1.0).contains(&v));
            assert_eq!(v, fractal_noise(x, y, 5, 9));
        }
    }
}
