//! The spectral sea against its references: the published closed forms of
//! the spectra, the target significant height and peak period recovered
//! from realisations, one mode against the Gerstner wave it must equal,
//! and the particles' velocity against the time derivative of their
//! position.

use soak_hydro::{
    DEFAULT_SEA_CELLS, Gerstner, GerstnerWave, STANDARD_GRAVITY, SeaMode, SeaSpectrum, SpectralSea,
    SpectrumShape, WaterError,
};

const G: f64 = STANDARD_GRAVITY;

fn pm(hs: f64, tp: f64) -> SeaSpectrum {
    SeaSpectrum {
        shape: SpectrumShape::PiersonMoskowitz,
        significant_height: hs,
        peak_period: tp,
        direction_deg: 30.0,
        spreading: 10.0,
    }
}

#[test]
fn pierson_moskowitz_is_its_closed_form() {
    // S(ω) = (5/16) Hs² ωp⁴ ω⁻⁵ exp(−5/4 (ωp/ω)⁴), whose m₀ is Hs²/16
    // exactly: the numerical scaling must give it back.
    let s = pm(2.0, 8.0);
    let wp = s.peak_frequency();
    let omegas: Vec<f64> = (1..60).map(|i| 0.05 * i as f64).collect();
    for (w, d) in omegas.iter().zip(s.densities(&omegas)) {
        let exact = 5.0 / 16.0 * 4.0 * wp.powi(4) * w.powi(-5) * (-1.25 * (wp / w).powi(4)).exp();
        assert!(
            (d - exact).abs() <= 1e-6 * exact.max(1e-12),
            "ω {w}: {d} against {exact}"
        );
    }
}

#[test]
fn jonswap_is_the_usual_formula_within_its_approximate_scaling() {
    // DNV-RP-C205: S_J = (1 − 0.287 ln γ) S_PM γ^r, the factor an
    // approximation of the exact scaling soak computes (within a few %).
    let gamma: f64 = 3.3;
    let s = SeaSpectrum::jonswap(2.0, 8.0);
    let wp = s.peak_frequency();
    let omegas: Vec<f64> = (8..40).map(|i| 0.05 * i as f64).collect();
    let mut worst: f64 = 0.0;
    for (w, d) in omegas.iter().zip(s.densities(&omegas)) {
        let pm = 5.0 / 16.0 * 4.0 * wp.powi(4) * w.powi(-5) * (-1.25 * (wp / w).powi(4)).exp();
        let sigma = if *w <= wp { 0.07 } else { 0.09 };
        let r = (-(w - wp).powi(2) / (2.0 * sigma * sigma * wp * wp)).exp();
        let dnv = (1.0 - 0.287 * gamma.ln()) * pm * gamma.powf(r);
        worst = worst.max((d / dnv - 1.0).abs());
    }
    assert!(worst < 0.03, "JONSWAP against DNV's formula: {worst}");
    // And its m₀ is Hs²/16 (trapezoid over a fine grid, independent of
    // the Simpson rule inside).
    let omegas: Vec<f64> = (1..200_000).map(|i| 1e-4 * i as f64).collect();
    let m0: f64 = s.densities(&omegas).iter().sum::<f64>() * 1e-4;
    assert!((m0 / 0.25 - 1.0).abs() < 1e-4, "m0 {m0}");
}

#[test]
fn spreading_is_normalised_and_cos_squared_at_s_one() {
    let mut s = pm(1.0, 6.0);
    s.spreading = 1.0;
    s.direction_deg = 0.0;
    let thetas: Vec<f64> = (-50..50)
        .map(|i| i as f64 * std::f64::consts::PI / 50.0)
        .collect();
    for (t, d) in thetas.iter().zip(s.spreading_densities(&thetas)) {
        // ∫ cos²(θ/2) dθ over a turn is π.
        let exact = (0.5 * t).cos().powi(2) / std::f64::consts::PI;
        assert!((d - exact).abs() < 1e-9, "θ {t}: {d} against {exact}");
    }
    for spread in [0.0, 3.0, 40.0] {
        s.spreading = spread;
        let n = 20_000;
        let thetas: Vec<f64> = (0..n)
            .map(|i| -std::f64::consts::PI + (i as f64 + 0.5) * std::f64::consts::TAU / n as f64)
            .collect();
        let total: f64 =
            s.spreading_densities(&thetas).iter().sum::<f64>() * std::f64::consts::TAU / n as f64;
        assert!((total - 1.0).abs() < 1e-6, "s {spread}: {total}");
    }
}

/// Significant height and peak frequency realised over 16 seeds, against
/// the target.
fn recovered(spectrum: &SeaSpectrum, size: f64, cells: usize) -> (f64, f64, f64) {
    let wp = spectrum.peak_frequency();
    let mut density = Vec::new();
    let (mut hs2, mut bin) = (0.0, 0.0);
    let seeds = 16;
    for seed in 0..seeds {
        let sea = SpectralSea::realize(spectrum, 0.0, size, cells, seed, G).unwrap();
        let fields = sea.fields(0.0);
        hs2 += fields.significant_height().powi(2);
        // Bins as wide as the tile's frequency resolution at the peak.
        bin = sea.frequency_resolution(wp);
        let realised = sea.frequency_spectrum(bin, (4.0 * wp / bin) as usize);
        density.resize(realised.len(), 0.0);
        for (d, r) in density.iter_mut().zip(realised) {
            *d += r / seeds as f64;
        }
    }
    let hs = (hs2 / seeds as f64).sqrt();
    let peak = density
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(b, _)| (b as f64 + 0.5) * bin)
        .unwrap();
    // The binned density holds the spectrum's variance below 4 ωp.
    let variance: f64 = density.iter().sum::<f64>() * bin;
    let (omegas, dw): (Vec<f64>, f64) = {
        let n = 4000;
        let dw = 4.0 * wp / n as f64;
        ((0..n).map(|i| (i as f64 + 0.5) * dw).collect(), dw)
    };
    let target: f64 = spectrum.densities(&omegas).iter().sum::<f64>() * dw;
    assert!(
        (variance / target - 1.0).abs() < 0.06,
        "binned variance {variance} against the target's {target} below 4 ωp"
    );
    (hs, peak, bin)
}

#[test]
fn realised_seas_recover_the_target_significant_height_and_peak() {
    for (name, spectrum) in [("JONSWAP", SeaSpectrum::jonswap(2.0, 8.0)), ("PM", pm(2.0, 8.0))] {
        let size = spectrum.default_tile(G);
        let (hs, peak, bin) = recovered(&spectrum, size, DEFAULT_SEA_CELLS);
        let wp = spectrum.peak_frequency();
        println!(
            "{name}: Hs {hs:.4} m against 2 m ({:+.2} %), peak {peak:.4} rad/s against {wp:.4} (bin {bin:.4})",
            100.0 * (hs / 2.0 - 1.0)
        );
        assert!((hs / 2.0 - 1.0).abs() < 0.03, "{name}: Hs {hs}");
        assert!(
            (peak - wp).abs() <= bin,
            "{name}: peak {peak} against {wp}, bin {bin}"
        );
    }
}

#[test]
fn a_seed_is_one_sea_and_another_seed_another() {
    let s = SeaSpectrum::jonswap(1.0, 5.0);
    let a = SpectralSea::realize(&s, 0.0, 100.0, 32, 7, G)
        .unwrap()
        .fields(3.0);
    let b = SpectralSea::realize(&s, 0.0, 100.0, 32, 7, G)
        .unwrap()
        .fields(3.0);
    let c = SpectralSea::realize(&s, 0.0, 100.0, 32, 8, G)
        .unwrap()
        .fields(3.0);
    assert_eq!(a, b);
    assert_ne!(a.height, c.height);
    // Zero mean: no energy at k = 0.
    let mean = a.height.iter().sum::<f64>() / a.height.len() as f64;
    assert!(mean.abs() < 1e-12, "{mean}");
}

#[test]
fn a_sea_whose_gravity_or_size_is_changed_is_evaluated_with_them() {
    // The modes' wavenumbers and frequencies, made once on the first
    // evaluation, follow the tile's public size and gravity when they are
    // changed after it: the same fields as a sea made with them from the
    // start (each mode one sinusoid, so a stale frequency or wavenumber
    // would show at once).
    let s = SeaSpectrum::jonswap(1.0, 5.0);
    let sea = SpectralSea::realize(&s, 0.0, 100.0, 32, 7, G).unwrap();
    let (mut changed, mut fresh) = (sea.clone(), sea.clone());
    let before = changed.fields(3.0);
    changed.gravity = 3.7;
    fresh.gravity = 3.7;
    let after = changed.fields(3.0);
    assert_eq!(after, fresh.fields(3.0));
    assert_ne!(after.height, before.height);
    let mut resized = sea.clone();
    let _ = resized.fields(3.0);
    resized.size = 140.0;
    let mut fresh = sea;
    fresh.size = 140.0;
    let after = resized.fields(3.0);
    assert_eq!(after, fresh.fields(3.0));
    assert_ne!(after.height_gradient[0], before.height_gradient[0]);
}

#[test]
fn one_mode_is_the_gerstner_wave_of_its_amplitude_and_length() {
    // Mode (3, −2) of a 64 m tile: a wave 17.75 m long at −33.7°,
    // amplitude 0.4 m, choppiness 0.8: the Gerstner wave with steepness
    // λ k a, at every node, at three times.
    let (size, cells) = (64.0, 32);
    let mode = SeaMode {
        n: 3,
        l: -2,
        amplitude: 0.4,
        phase: 0.7,
    };
    let lambda = 0.8;
    let sea = SpectralSea::from_modes(1.5, size, cells, &[mode], G)
        .unwrap()
        .with_choppiness(lambda)
        .unwrap();
    let k = std::f64::consts::TAU / size * ((3.0f64).powi(2) + 4.0).sqrt();
    let gerstner = Gerstner::new(
        1.5,
        vec![GerstnerWave {
            amplitude: 0.4,
            wavelength: std::f64::consts::TAU / k,
            direction_deg: (-2.0f64).atan2(3.0).to_degrees(),
            steepness: lambda * k * 0.4,
            phase: 0.7,
        }],
        G,
    )
    .unwrap();
    let d = size / cells as f64;
    let mut worst: f64 = 0.0;
    for t in [0.0, 1.7, 13.1] {
        let f = sea.fields(t);
        for iz in 0..cells {
            for ix in 0..cells {
                let p = f.particle(ix, iz);
                let q = gerstner.particle(ix as f64 * d, iz as f64 * d, t);
                worst = worst.max((p[0] - q.x).abs().max((p[1] - q.y).abs()).max((p[2] - q.z).abs()));
            }
        }
    }
    println!("one mode against Gerstner: largest difference {worst:.2e} m");
    assert!(worst < 1e-6, "{worst}");
}

#[test]
fn the_fields_are_the_derivatives_of_the_particles_position() {
    // Central differences in time and over the rest position, on a
    // realised sea: velocity, elevation gradient, displacement gradient.
    let s = SeaSpectrum::jonswap(1.0, 4.0);
    let size = 4.0 * s.peak_wavelength(G);
    let cells = 64;
    let sea = SpectralSea::realize(&s, 0.0, size, cells, 3, G).unwrap();
    let (t, h) = (2.0, 1e-4);
    let f = sea.fields(t);
    let (fm, fp) = (sea.fields(t - h), sea.fields(t + h));
    let scale = f.height.iter().fold(0.0f64, |m, x| m.max(x.abs())) * s.peak_frequency();
    let mut worst: f64 = 0.0;
    for i in 0..cells * cells {
        let dt = |a: &[f64], b: &[f64]| (b[i] - a[i]) / (2.0 * h);
        let fd = [
            dt(&fm.displacement[0], &fp.displacement[0]),
            dt(&fm.height, &fp.height),
            dt(&fm.displacement[1], &fp.displacement[1]),
        ];
        for (v, d) in f.velocity.iter().zip(fd) {
            worst = worst.max((v[i] - d).abs() / scale);
        }
    }
    assert!(worst < 1e-6, "velocity against d/dt: {worst}");
    // Spatial derivatives: the fields at a shifted tile (a mode's phase
    // turned by k·δ) against those at the nodes.
    let delta = 1e-4;
    let shifted = |dx: f64, dz: f64| {
        let dk = std::f64::consts::TAU / size;
        let modes: Vec<SeaMode> = sea
            .sea_modes()
            .into_iter()
            .map(|m| SeaMode {
                phase: m.phase + dk * (m.n as f64 * dx + m.l as f64 * dz),
                ..m
            })
            .collect();
        SpectralSea::from_modes(0.0, size, cells, &modes, G)
            .unwrap()
            .fields(t)
    };
    let (xm, xp, zm, zp) = (
        shifted(-delta, 0.0),
        shifted(delta, 0.0),
        shifted(0.0, -delta),
        shifted(0.0, delta),
    );
    let mut worst: f64 = 0.0;
    let slope = scale / s.peak_frequency() * 2.0 * std::f64::consts::PI / s.peak_wavelength(G);
    for i in 0..cells * cells {
        let d = |a: &[f64], b: &[f64]| (b[i] - a[i]) / (2.0 * delta);
        let pairs = [
            (f.height_gradient[0][i], d(&xm.height, &xp.height)),
            (f.height_gradient[1][i], d(&zm.height, &zp.height)),
            (
                f.displacement_gradient[0][i],
                d(&xm.displacement[0], &xp.displacement[0]),
            ),
            (
                f.displacement_gradient[1][i],
                d(&zm.displacement[0], &zp.displacement[0]),
            ),
            (
                f.displacement_gradient[1][i],
                d(&xm.displacement[1], &xp.displacement[1]),
            ),
            (
                f.displacement_gradient[2][i],
                d(&zm.displacement[1], &zp.displacement[1]),
            ),
        ];
        for (a, b) in pairs {
            worst = worst.max((a - b).abs() / slope);
        }
    }
    assert!(worst < 1e-5, "gradients against differences: {worst}");
}

#[test]
fn bad_parameters_are_named() {
    let good = SeaSpectrum::jonswap(2.0, 8.0);
    let name = |e: WaterError| match e {
        WaterError::Parameter { name, .. } => name,
        WaterError::Mode { field, .. } => field,
        other => panic!("{other:?}"),
    };
    let cases: [(SeaSpectrum, &str); 5] = [
        (
            SeaSpectrum {
                significant_height: 0.0,
                ..good
            },
            "significant_height",
        ),
        (
            SeaSpectrum {
                peak_period: f64::NAN,
                ..good
            },
            "peak_period",
        ),
        (
            SeaSpectrum {
                shape: SpectrumShape::Jonswap { gamma: 0.5 },
                ..good
            },
            "gamma",
        ),
        (
            SeaSpectrum {
                spreading: -1.0,
                ..good
            },
            "spreading",
        ),
        (
            SeaSpectrum {
                direction_deg: f64::INFINITY,
                ..good
            },
            "direction_deg",
        ),
    ];
    for (s, field) in cases {
        assert_eq!(
            name(SpectralSea::realize(&s, 0.0, 100.0, 64, 0, G).unwrap_err()),
            field
        );
    }
    for (size, cells, field) in [
        (0.0, 64, "tile"),
        (100.0, 48, "cells"),
        (100.0, 4, "cells"),
        (100.0, 4096, "cells"),
    ] {
        assert_eq!(
            name(SpectralSea::realize(&good, 0.0, size, cells, 0, G).unwrap_err()),
            field
        );
    }
    assert_eq!(
        name(SpectralSea::realize(&good, f64::NAN, 100.0, 64, 0, G).unwrap_err()),
        "level"
    );
    let mode = SeaMode {
        n: 16,
        l: 0,
        amplitude: 1.0,
        phase: 0.0,
    };
    assert_eq!(
        name(SpectralSea::from_modes(0.0, 100.0, 32, &[mode], G).unwrap_err()),
        "n"
    );
    // The mean is no wave: its height is the sea's level.
    let mean = SeaMode { n: 0, ..mode };
    assert_eq!(
        name(SpectralSea::from_modes(0.0, 100.0, 32, &[mean], G).unwrap_err()),
        "n and l (the mean; set the level instead)"
    );
    // Named as a mode of the list given, not as a Gerstner wave.
    let message = SpectralSea::from_modes(0.0, 100.0, 32, &[mode, mean], G)
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("spectral mode 0 (of those given): `n`"),
        "{message}"
    );
    let mode = SeaMode {
        n: 1,
        amplitude: -1.0,
        ..mode
    };
    assert_eq!(
        name(SpectralSea::from_modes(0.0, 100.0, 32, &[mode], G).unwrap_err()),
        "amplitude"
    );
    let sea = SpectralSea::from_modes(0.0, 100.0, 32, &[], G).unwrap();
    assert_eq!(name(sea.with_choppiness(-0.5).unwrap_err()), "choppiness");
}

/// The particle at rest `(x0, z0)` by the sum over every mode (no
/// interpolation): its horizontal position, the Jacobian of it over the
/// rest position, and its height.
fn exact_particle(sea: &SpectralSea, x0: f64, z0: f64, t: f64) -> ([f64; 2], [[f64; 2]; 2], f64) {
    let dk = std::f64::consts::TAU / sea.size;
    let (mut p, mut j, mut y) = ([x0, z0], [[1.0, 0.0], [0.0, 1.0]], sea.level);
    for (k, omega, _) in sea.modes() {
        let (n, l) = ((k[0] / dk).round() as i64, (k[1] / dk).round() as i64);
        let a = sea.amplitude(n, l);
        let kk = k[0].hypot(k[1]);
        let u = [k[0] / kk, k[1] / kk];
        let th = k[0] * x0 + k[1] * z0 - omega * t + a.arg();
        let (s, c) = th.sin_cos();
        y += a.norm() * c;
        for r in 0..2 {
            p[r] -= sea.choppiness * u[r] * a.norm() * s;
            for q in 0..2 {
                j[r][q] -= sea.choppiness * u[r] * k[q] * a.norm() * c;
            }
        }
    }
    (p, j, y)
}

/// The height above `(x, z)` by Newton's method on the exact sums.
fn exact_height(sea: &SpectralSea, x: f64, z: f64, t: f64) -> f64 {
    let (mut x0, mut z0) = (x, z);
    for _ in 0..50 {
        let (p, j, _) = exact_particle(sea, x0, z0, t);
        let (rx, rz) = (p[0] - x, p[1] - z);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        x0 -= (j[1][1] * rx - j[0][1] * rz) / det;
        z0 -= (j[0][0] * rz - j[1][0] * rx) / det;
        if rx.abs() + rz.abs() < 1e-13 {
            break;
        }
    }
    exact_particle(sea, x0, z0, t).2
}

#[test]
fn the_surface_inverts_the_choppy_map_as_the_exact_sums_do() {
    use soak_hydro::{SpectralSurface, Surface};
    // A wind sea (Hs 1 m, Tp 5 s) realised on its default tile at 64
    // cells, then the same modes on grids of 128 and 256 (finer nodes, the
    // same sea): heights at 300 scattered points against Newton's method
    // on the sum over every mode, the error falling as the node spacing's
    // fourth power.
    let spectrum = SeaSpectrum::jonswap(1.0, 5.0);
    let size = spectrum.default_tile(G);
    let coarse = SpectralSea::realize(&spectrum, 0.3, size, 64, 11, G).unwrap();
    let modes = coarse.sea_modes();
    let mut errors = Vec::new();
    for cells in [64, 128, 256] {
        let sea = SpectralSea::from_modes(0.3, size, cells, &modes, G)
            .unwrap()
            .with_choppiness(0.8)
            .unwrap();
        let surface = SpectralSurface::new(sea.clone());
        let (mut worst, mut slope_worst): (f64, f64) = (0.0, 0.0);
        for i in 0..300 {
            let x = (i as f64 * 7.31).rem_euclid(size) - 0.5 * size;
            let z = (i as f64 * 3.77 + 11.0).rem_euclid(size);
            let t = 4.0;
            let h = surface.height(x, z, t);
            worst = worst.max((h - exact_height(&sea, x, z, t)).abs());
            // The slope against central differences of the height.
            let e = 1e-4;
            let s = surface.slope(x, z, t, &[0.0, 0.0]);
            let fd = [
                (surface.height(x + e, z, t) - surface.height(x - e, z, t)) / (2.0 * e),
                (surface.height(x, z + e, t) - surface.height(x, z - e, t)) / (2.0 * e),
            ];
            slope_worst = slope_worst.max((s[0] - fd[0]).abs().max((s[1] - fd[1]).abs()));
        }
        println!(
            "{cells} cells: height {worst:.2e} m from the exact sums (Hs 1 m), slope {slope_worst:.1e} from differences"
        );
        assert!(slope_worst < 1e-5, "{slope_worst}");
        errors.push(worst);
        // The bounds hold every height read, between the nodes too.
        let (lo, hi) = surface.height_bounds(4.0).unwrap();
        let mut seen = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..20_000 {
            let (x, z) = (
                (i as f64 * 0.6180339887).fract() * size,
                (i as f64 * 0.7548776662).fract() * size,
            );
            let h = surface.height(x, z, 4.0);
            seen = (seen.0.min(h), seen.1.max(h));
        }
        assert!(lo <= seen.0 && seen.1 <= hi, "bounds {lo}..{hi}, read {seen:?}");
        assert!(
            hi - lo < 1.5 * (seen.1 - seen.0),
            "bounds {lo}..{hi}, read {seen:?}"
        );
    }
    assert!(errors[0] < 0.02, "{errors:?}");
    assert!(
        errors[1] < errors[0] / 8.0 && errors[2] < errors[1] / 8.0,
        "the error falls with the spacing: {errors:?}"
    );
}

#[test]
fn the_nodes_twists_are_the_surfaces_mixed_derivative() {
    use soak_hydro::{SpectralSurface, Surface, SurfaceNode};
    // A choppy wind sea; nodes across several of its cells: each node's
    // twist against central differences of the surface's own slope, both
    // ways round (the surface the twist belongs to is the interpolated
    // one, so the differences agree to their own error).
    let spectrum = SeaSpectrum::jonswap(1.0, 5.0);
    let size = spectrum.default_tile(G);
    let sea = SpectralSea::realize(&spectrum, 0.3, size, 64, 11, G)
        .unwrap()
        .with_choppiness(0.8)
        .unwrap();
    let surface = SpectralSurface::new(sea);
    assert!(surface.node_twists());
    let (origin, spacing, nodes) = ([-13.0, 7.0], 0.61, [9, 7]);
    let (t, e, h) = (2.5, 1e-4, [0.0, 0.0]);
    let mut out = vec![SurfaceNode::default(); nodes[0] * nodes[1]];
    surface.sample_nodes(t, origin, spacing, nodes, &mut out);
    let mut largest: f64 = 0.0;
    for (k, node) in out.iter().enumerate() {
        let x = origin[0] + (k % nodes[0]) as f64 * spacing;
        let z = origin[1] + (k / nodes[0]) as f64 * spacing;
        let sxz = (surface.slope(x, z + e, t, &h)[0] - surface.slope(x, z - e, t, &h)[0]) / (2.0 * e);
        let szx = (surface.slope(x + e, z, t, &h)[1] - surface.slope(x - e, z, t, &h)[1]) / (2.0 * e);
        let twist = node.twist.expect("a spectral sea gives its nodes' twists");
        largest = largest.max(twist.abs());
        assert!(
            (twist - sxz).abs() < 1e-6 && (twist - szx).abs() < 1e-6,
            "node {k}: twist {twist} against {sxz} and {szx}"
        );
    }
    assert!(largest > 1e-3, "the twists are not all flat: {largest}");
}

#[test]
fn one_mode_read_as_a_surface_is_the_gerstner_surface() {
    use soak_hydro::{SpectralSurface, Surface};
    // 16 cells a wavelength along x: the interpolated surface against the
    // Gerstner surface's own inversion.
    let (size, cells) = (64.0, 64);
    let mode = SeaMode {
        n: 4,
        l: 0,
        amplitude: 0.5,
        phase: 0.2,
    };
    let sea = SpectralSea::from_modes(0.0, size, cells, &[mode], G)
        .unwrap()
        .with_choppiness(0.9)
        .unwrap();
    let k = std::f64::consts::TAU * 4.0 / size;
    let gerstner = Gerstner::new(
        0.0,
        vec![GerstnerWave {
            amplitude: 0.5,
            wavelength: size / 4.0,
            direction_deg: 0.0,
            steepness: 0.9 * k * 0.5,
            phase: 0.2,
        }],
        G,
    )
    .unwrap();
    let surface = SpectralSurface::new(sea);
    let mut worst: f64 = 0.0;
    for i in 0..400 {
        let (x, z, t) = (i as f64 * 0.377, i as f64 * 0.91, 0.1 * i as f64);
        worst = worst.max((surface.height(x, z, t) - gerstner.height(x, z, t)).abs());
    }
    println!("one mode read between the nodes: {worst:.2e} m from the Gerstner surface");
    assert!(worst < 1e-3 * 0.5, "{worst}");
}
