// soak-shade: wet-surface optics in WGSL (f32, WebGPU baseline: no f64, no
// extensions). Lekner & Dorf (1988) extended to coloured liquids, after
// J. M. Bajo's thesis, Ch. 6. An entry-point-free library: prepend it to a
// shader that calls these functions. Every function mirrors the f64 CPU
// reference of the same name in the `soak-shade` crate; the structs mirror
// `OpticsInput`, `OpticsOutput` and `ArtistCurveGpu` field by field.
//
// Conventions: `n` is the liquid's refractive index relative to air (> 1);
// fractions are in [0, 1]; angles are given as cosines; roughness is GGX
// alpha in the lobe functions and perceptual (alpha = r^2) in the structs.
// Unlike the CPU reference, NaN inputs are undefined behaviour here (WGSL
// lets implementations assume there are no NaNs).
//
// Helpers prefixed `soak_` are private to the library.

const SOAK_PI: f32 = 3.14159265358979;
const SOAK_HALF_PI: f32 = 1.57079632679490;
const SOAK_MIN_ALPHA: f32 = 0.002;
const SOAK_MIN_POSITIVE: f32 = 1.17549435e-38;

// Γ families, as `Gamma::gpu_code` numbers them (unknown codes are linear).
const GAMMA_LINEAR: u32 = 0u;
const GAMMA_LOG: u32 = 1u;
const GAMMA_POWER: u32 = 2u;
const GAMMA_ARCTAN: u32 = 3u;

// ---------------------------------------------------------------- helpers

fn soak_unit(x: f32) -> f32 {
    return clamp(x, 0.0, 1.0);
}

// 2·atanh(u) = ln((1 + u)/(1 − u)) by its odd series, for |u| ≤ 1/3
// (truncation < 2e-9 relative).
fn soak_two_atanh(u: f32) -> f32 {
    let u2 = u * u;
    var s = 1.0 / 15.0;
    s = s * u2 + 1.0 / 13.0;
    s = s * u2 + 1.0 / 11.0;
    s = s * u2 + 1.0 / 9.0;
    s = s * u2 + 1.0 / 7.0;
    s = s * u2 + 1.0 / 5.0;
    s = s * u2 + 1.0 / 3.0;
    s = s * u2 + 1.0;
    return 2.0 * u * s;
}

// ln(1 + x) for x ≥ 0, accurate to a few ulp relative. WGSL's log() only
// promises 2^-21 *absolute* error on [0.5, 2], too coarse near 1.
fn soak_ln1p(x: f32) -> f32 {
    if (x > 1.0) {
        return log(1.0 + x);
    }
    return soak_two_atanh(x / (2.0 + x));
}

// ln(x) for x > 0, accurate to a few ulp relative also near x = 1.
fn soak_ln(x: f32) -> f32 {
    if (x >= 0.5 && x <= 2.0) {
        // x − 1 is exact on [0.5, 2] (Sterbenz).
        let d = x - 1.0;
        return soak_two_atanh(d / (2.0 + d));
    }
    return log(x);
}

// atan(x) for x ≥ 0 to a few ulp: WGSL's atan() may be 4096 ulp off.
// Reduces to |y| ≤ tan(π/12) and sums the odd series to y^15.
fn soak_atan_pos(x: f32) -> f32 {
    var base = 0.0;
    var sign = 1.0;
    var t = x;
    if (t > 1.0) {
        // atan(x) = π/2 − atan(1/x)
        t = 1.0 / t;
        base = SOAK_HALF_PI;
        sign = -1.0;
    }
    var offset = 0.0;
    if (t > 0.26794919243112) {
        // atan(t) = π/6 + atan((√3 t − 1)/(t + √3))
        t = (1.73205080756888 * t - 1.0) / (t + 1.73205080756888);
        offset = 0.52359877559830;
    }
    let t2 = t * t;
    var s = -1.0 / 15.0;
    s = s * t2 + 1.0 / 13.0;
    s = s * t2 - 1.0 / 11.0;
    s = s * t2 + 1.0 / 9.0;
    s = s * t2 - 1.0 / 7.0;
    s = s * t2 + 1.0 / 5.0;
    s = s * t2 - 1.0 / 3.0;
    s = s * t2 + 1.0;
    return base + sign * (offset + t * s);
}

fn soak_atan(x: f32) -> f32 {
    if (x < 0.0) {
        return -soak_atan_pos(-x);
    }
    return soak_atan_pos(x);
}

// ------------------------------------------------ Stern mean reflectance

// Series of Stern's closed form in ε = n − 1 (16 terms, coefficients
// b_k + a_k ln ε, as in the CPU reference); used for ε < 0.3, where the
// closed form cancels in f32. Truncation error < 3e-10 there.
fn soak_stern_series(eps: f32) -> f32 {
    let l = soak_ln(eps);
    var acc = 0.1346598864 + 0.14453125 * l;
    acc = acc * eps + (0.1991225971 - 0.1875 * l);
    acc = acc * eps + (-0.5431129216 + 0.09765625 * l);
    acc = acc * eps + (0.6141414015 + 0.1171875 * l);
    acc = acc * eps + (-0.222522544 - 0.3359375 * l);
    acc = acc * eps + (-0.5110077393 + 0.375 * l);
    acc = acc * eps + (1.114439424 - 0.125 * l);
    acc = acc * eps + (-1.034787159 - 0.3125 * l);
    acc = acc * eps + (0.1171054328 + 0.625 * l);
    acc = acc * eps + (1.08516486 - 0.5 * l);
    acc = acc * eps + (-1.580487825 - 0.0625 * l);
    acc = acc * eps + (0.7944615836 + 0.625 * l);
    acc = acc * eps + (0.6644669878 - 0.625 * l);
    acc = acc * eps - 1.316666667;
    acc = acc * eps + (0.4450930764 + 0.5 * l);
    acc = acc * eps + 0.3333333333;
    return acc * eps;
}

// Stern (1964), thesis Eq. 6.7, for n − 1 ≥ 0.3.
fn soak_stern_closed_form(n: f32) -> f32 {
    let n2 = n * n;
    let np1 = n + 1.0;
    let n2p1 = n2 + 1.0;
    let n2m1 = n2 - 1.0;
    return (3.0 * n2 + 2.0 * n + 1.0) / (3.0 * np1 * np1)
        - 2.0 * n2 * n * (n2 + 2.0 * n - 1.0) / (n2p1 * n2p1 * n2m1)
        + n2 * n2p1 / (n2m1 * n2m1) * soak_ln(n)
        - n2 * n2m1 * n2m1 / (n2p1 * n2p1 * n2p1) * (soak_ln(n) + soak_ln(np1 / (n - 1.0)));
}

// Mean reflectance R̄(n) of a flat interface under diffuse (isotropic)
// illumination, unpolarised, entering a medium of relative index n > 1.
// R̄(1.333) ≈ 0.066406. Returns 0 for n ≤ 1 (the CPU reference also handles
// n < 1; the GPU version does not).
fn stern_mean_reflectance(n: f32) -> f32 {
    if (n <= 1.0) {
        return 0.0;
    }
    let eps = n - 1.0;
    var r: f32;
    if (eps < 0.3) {
        r = soak_stern_series(eps);
    } else {
        r = soak_stern_closed_form(n);
    }
    return soak_unit(r);
}

// Internal diffuse reflectance p = 1 − (1 − R̄(n))/n² of the liquid–air
// interface for Lambertian light inside the liquid. p(1.333) ≈ 0.474591.
// Returns 0 for n ≤ 1.
fn internal_reflectance(n: f32) -> f32 {
    if (n <= 1.0) {
        return 0.0;
    }
    return soak_unit(1.0 - (1.0 - stern_mean_reflectance(n)) / (n * n));
}

// ---------------------------------------------------------------- Fresnel

// Normal-incidence reflectance ((n − 1)/(n + 1))².
fn fresnel_f0(n: f32) -> f32 {
    let r = (n - 1.0) / (n + 1.0);
    return r * r;
}

// Schlick's Fresnel F0 + (1 − F0)(1 − cos θ)^5, cos θ clamped to [0, 1].
fn schlick(cos_theta: f32, f0: f32) -> f32 {
    let m = 1.0 - soak_unit(cos_theta);
    let m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

// ------------------------------------------------------ Lekner–Dorf albedo

fn soak_bounce_denominator(a: vec3<f32>, s: vec3<f32>, p: f32) -> vec3<f32> {
    return max(vec3<f32>(1.0) - p * a * s * s, vec3<f32>(SOAK_MIN_POSITIVE));
}

// Wet albedo (1 − R_spec) σ² a (1 − p) / (1 − p a σ²) per channel: dry
// albedo a, liquid transmittance σ per pass, specular reflectance R_spec,
// internal reflectance p. Inputs clamped to [0, 1].
fn wet_albedo(albedo: vec3<f32>, transmittance: vec3<f32>, r_spec: f32, p: f32) -> vec3<f32> {
    let a = clamp(albedo, vec3<f32>(0.0), vec3<f32>(1.0));
    let s = clamp(transmittance, vec3<f32>(0.0), vec3<f32>(1.0));
    let r = soak_unit(r_spec);
    let q = soak_unit(p);
    return (1.0 - r) * s * s * a * (1.0 - q) / soak_bounce_denominator(a, s, q);
}

// Fraction absorbed by the surface (thesis Eq. 6.1):
// (1 − R_spec)(1 − a) σ / (1 − p a σ²).
fn absorbed_fraction(albedo: vec3<f32>, transmittance: vec3<f32>, r_spec: f32, p: f32) -> vec3<f32> {
    let a = clamp(albedo, vec3<f32>(0.0), vec3<f32>(1.0));
    let s = clamp(transmittance, vec3<f32>(0.0), vec3<f32>(1.0));
    let r = soak_unit(r_spec);
    let q = soak_unit(p);
    return (1.0 - r) * (vec3<f32>(1.0) - a) * s / soak_bounce_denominator(a, s, q);
}

// Beer–Lambert transmittance exp(−α h) of one pass: absorption α in 1/m,
// thickness h in m.
fn beer_lambert(absorption: vec3<f32>, thickness: f32) -> vec3<f32> {
    return exp(-max(absorption * thickness, vec3<f32>(0.0)));
}

// ------------------------------------------------------------------- Γ(h)

fn soak_gamma_finish(h: f32, g: f32) -> f32 {
    if (h <= 0.0) {
        return 0.0;
    }
    if (h >= 1.0) {
        return 1.0;
    }
    return soak_unit(g);
}

fn gamma_linear(h: f32) -> f32 {
    return soak_unit(h);
}

// ln(1 + k h)/ln(1 + k), k > 0.
fn gamma_log(h_in: f32, k: f32) -> f32 {
    let h = soak_unit(h_in);
    var g = h;
    if (k > 1e-9) {
        g = soak_ln1p(k * h) / soak_ln1p(k);
    }
    return soak_gamma_finish(h, g);
}

// h^γ, γ > 0.
fn gamma_power(h_in: f32, exponent: f32) -> f32 {
    let h = soak_unit(h_in);
    var g = 1.0;
    if (h > 0.0) {
        g = pow(h, exponent);
    }
    return soak_gamma_finish(h, g);
}

// ½(atan(r(h − ½))/atan(r/2) + 1), roughness r > 0.
fn gamma_arctan(h_in: f32, roughness: f32) -> f32 {
    let h = soak_unit(h_in);
    let r = abs(roughness);
    var g = h;
    if (r > 1e-9) {
        g = 0.5 * (soak_atan(r * (h - 0.5)) / soak_atan(0.5 * r) + 1.0);
    }
    return soak_gamma_finish(h, g);
}

// Γ by family code (GAMMA_*); unknown codes are linear.
fn gamma_eval(kind: u32, parameter: f32, h: f32) -> f32 {
    switch kind {
        case 1u: {
            return gamma_log(h, parameter);
        }
        case 2u: {
            return gamma_power(h, parameter);
        }
        case 3u: {
            return gamma_arctan(h, parameter);
        }
        default: {
            return gamma_linear(h);
        }
    }
}

// A 1-D artist curve: `len` samples (2..64) uniformly spaced over [0, 1],
// packed four per vec4. Mirrors `ArtistCurveGpu`.
struct ArtistCurveGpu {
    samples: array<vec4<f32>, 16>,
    len: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

fn gamma_artist(h_in: f32, curve: ArtistCurveGpu) -> f32 {
    let h = soak_unit(h_in);
    if (h <= 0.0) {
        return 0.0;
    }
    if (h >= 1.0) {
        return 1.0;
    }
    var c = curve;
    let n = clamp(c.len, 2u, 64u);
    let x = h * f32(n - 1u);
    let i = min(u32(x), n - 2u);
    let t = x - f32(i);
    let j = i + 1u;
    let a = c.samples[i >> 2u][i & 3u];
    let b = c.samples[j >> 2u][j & 3u];
    return min(max(a + (b - a) * t, a), b);
}

// (1 − Γ)·dry + Γ·wet, exactly dry at Γ = 0 and wet at Γ = 1.
fn blend(dry: vec3<f32>, wet: vec3<f32>, gamma: f32) -> vec3<f32> {
    let g = soak_unit(gamma);
    if (g >= 1.0) {
        return wet;
    }
    return (1.0 - g) * dry + g * wet;
}

// ------------------------------------------------------- specular film lobe

fn alpha_from_roughness(roughness: f32) -> f32 {
    let r = soak_unit(roughness);
    return max(r * r, SOAK_MIN_ALPHA);
}

// GGX / Trowbridge–Reitz NDF α² / (π ((n·h)²(α² − 1) + 1)²), in 1/sr.
fn ggx_distribution(n_dot_h: f32, alpha: f32) -> f32 {
    let c = soak_unit(n_dot_h);
    let a = clamp(alpha, SOAK_MIN_ALPHA, 1.0);
    let a2 = a * a;
    let d = c * c * (a2 - 1.0) + 1.0;
    return a2 / (SOAK_PI * d * d);
}

// Height-correlated Smith visibility G₂/(4 (n·l)(n·v)).
fn smith_visibility(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let l = soak_unit(n_dot_l);
    let v = soak_unit(n_dot_v);
    let a = clamp(alpha, SOAK_MIN_ALPHA, 1.0);
    let a2 = a * a;
    let gv = l * sqrt(v * v * (1.0 - a2) + a2);
    let gl = v * sqrt(l * l * (1.0 - a2) + a2);
    let s = gv + gl;
    if (s > 0.0) {
        return 0.5 / s;
    }
    return 0.0;
}

// The liquid film's specular BRDF D·V·F in 1/sr (F: Schlick with the
// liquid's F0 at v·h). 0 when light or eye is below the horizon.
fn film_specular(n_dot_l: f32, n_dot_v: f32, n_dot_h: f32, v_dot_h: f32, alpha: f32, f0: f32) -> f32 {
    if (!(n_dot_l > 0.0 && n_dot_v > 0.0)) {
        return 0.0;
    }
    return ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha) * schlick(v_dot_h, f0);
}

// Perceptual roughness of a wetting surface: lerp(dry, min(dry, film), Γ).
fn wet_roughness(dry_roughness: f32, film_roughness: f32, wetness: f32) -> f32 {
    let dry = soak_unit(dry_roughness);
    let film = min(soak_unit(film_roughness), dry);
    return blend(vec3<f32>(dry), vec3<f32>(film), wetness).x;
}

// --------------------------------------- Lagarde's shortcut (comparison)

fn lagarde_factor(porosity: f32) -> f32 {
    return mix(1.0, 0.2, soak_unit(porosity));
}

fn lagarde_wet_diffuse(dry: vec3<f32>, porosity: f32, wetness: f32) -> vec3<f32> {
    return dry * mix(1.0, lagarde_factor(porosity), soak_unit(wetness));
}

fn lagarde_wet_gloss(gloss: f32, porosity: f32, wetness: f32) -> f32 {
    let f = lagarde_factor(porosity);
    return mix(1.0, soak_unit(gloss), mix(1.0, f, 0.5 * soak_unit(wetness)));
}

// ------------------------------------------------- table evaluation (tests)

// One row of the CPU/GPU parity table; mirrors `OpticsInput` (80 bytes).
struct OpticsInput {
    albedo: vec4<f32>,
    transmittance: vec4<f32>,
    refractive_index: f32,
    n_dot_l: f32,
    n_dot_v: f32,
    n_dot_h: f32,
    v_dot_h: f32,
    saturation: f32,
    gamma_kind: u32,
    gamma_param: f32,
    dry_roughness: f32,
    film_roughness: f32,
    porosity: f32,
    _pad: f32,
}

// Mirrors `OpticsOutput` (96 bytes).
struct OpticsOutput {
    wet_albedo: vec4<f32>,
    absorbed: vec4<f32>,
    blended: vec4<f32>,
    lagarde_albedo: vec4<f32>,
    stern: f32,
    internal: f32,
    r_spec: f32,
    gamma: f32,
    film_specular: f32,
    wet_roughness: f32,
    lagarde_gloss: f32,
    _pad: f32,
}

// Everything `soak_shade::evaluate` computes, for one input row.
fn evaluate_optics(input: OpticsInput) -> OpticsOutput {
    var out: OpticsOutput;
    let n = input.refractive_index;
    let dry = input.albedo.xyz;
    out.stern = stern_mean_reflectance(n);
    out.internal = internal_reflectance(n);
    let f0 = fresnel_f0(n);
    out.r_spec = schlick(input.n_dot_l, f0);
    let wet = wet_albedo(dry, input.transmittance.xyz, out.r_spec, out.internal);
    out.wet_albedo = vec4<f32>(wet, 0.0);
    out.absorbed = vec4<f32>(absorbed_fraction(dry, input.transmittance.xyz, out.r_spec, out.internal), 0.0);
    out.gamma = gamma_eval(input.gamma_kind, input.gamma_param, input.saturation);
    out.blended = vec4<f32>(blend(dry, wet, out.gamma), 0.0);
    out.film_specular = film_specular(input.n_dot_l, input.n_dot_v, input.n_dot_h, input.v_dot_h,
        alpha_from_roughness(input.film_roughness), f0);
    out.wet_roughness = wet_roughness(input.dry_roughness, input.film_roughness, out.gamma);
    out.lagarde_albedo = vec4<f32>(lagarde_wet_diffuse(dry, input.porosity, out.gamma), 0.0);
    out.lagarde_gloss = lagarde_wet_gloss(1.0 - soak_unit(input.dry_roughness), input.porosity, out.gamma);
    out._pad = 0.0;
    return out;
}
