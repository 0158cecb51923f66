//! What passes through a texel in one step: absorption from the water it is
//! submerged in (simplified Darcy, thesis Eq. 5.5), rain, and evaporation
//! (thesis Eq. 5.8). The same arithmetic runs in `gpu/exchange.wgsl`.

use crate::environment::{Environment, EnvironmentResponse};
use crate::material::{Liquid, Material};
use crate::source::Region;

/// Per-step constants of the per-texel exchange.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rates {
    /// Absorption per metre of depth: `κ ρ g / μ`, 1/s (gain `absorb · d · Δt`, m).
    pub absorb: f64,
    /// Evaporation `f_env k_L C_M`, m/s.
    pub evaporate: f64,
    /// Rain on a horizontal surface, m/s.
    pub rain: f64,
    /// Where it rains.
    pub region: Region,
    /// `h_max`, m.
    pub saturation: f64,
}

impl Rates {
    pub fn new(
        material: &Material,
        liquid: &Liquid,
        response: &EnvironmentResponse,
        env: &Environment,
        density: f64,
        gravity: f64,
    ) -> Self {
        Self {
            absorb: material.kappa() * density * gravity / liquid.viscosity,
            evaporate: response.factor(env) * liquid.evaporation_rate * material.permeability,
            rain: env.rain.rate,
            region: env.rain.region,
            saturation: material.saturation,
        }
    }
}

/// Volumes per area (m) one texel gained or lost in a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Exchange {
    pub absorbed: f64,
    pub rained: f64,
    pub evaporated: f64,
}

/// Updates one texel's liquid `h` (m) over `dt` (s).
///
/// - `depth`: how far below the water surface the texel is, m (≤ 0 or NaN
///   when dry);
/// - `scale`: the texel's permeability relative to the material's (1 without
///   a permeability map);
/// - `up`: the world y component of its outward unit normal;
/// - `in_rain`: whether it lies in the rain's region.
///
/// A submerged texel absorbs `κ ρ g d Δt / μ` up to saturation and neither
/// dries nor catches rain; a dry one catches `rain · max(up, 0) · Δt` up to
/// saturation, then loses `f_env k_L C_M Δt` down to zero.
#[inline]
pub(crate) fn exchange(
    h: &mut f64,
    rates: &Rates,
    depth: f64,
    scale: f64,
    up: f64,
    in_rain: bool,
    dt: f64,
) -> Exchange {
    let mut out = Exchange::default();
    let hmax = rates.saturation;
    if depth > 0.0 {
        let gain = rates.absorb * scale * depth * dt;
        if gain > 0.0 && *h < hmax {
            let next = (*h + gain).min(hmax);
            out.absorbed = next - *h;
            *h = next;
        }
    } else {
        if in_rain && up > 0.0 {
            let gain = rates.rain * up * dt;
            if gain > 0.0 && *h < hmax {
                let next = (*h + gain).min(hmax);
                out.rained = next - *h;
                *h = next;
            }
        }
        let loss = rates.evaporate * scale * dt;
        if loss > 0.0 && *h > 0.0 {
            let e = loss.min(*h);
            out.evaporated = e;
            *h -= e;
        }
    }
    out
}

/// [`exchange`] of a texel out of the rain (`in_rain` false), written
/// without branches so that several texels run in vector lanes: the same
/// operations on the same values, so the same bits. Returns the new `h`,
/// the volume absorbed and the volume evaporated per area (m).
#[inline(always)]
pub(crate) fn exchange_dry_sky(h: f64, rates: &Rates, depth: f64, scale: f64, dt: f64) -> (f64, f64, f64) {
    let hmax = rates.saturation;
    let submerged = depth > 0.0;
    let gain = rates.absorb * scale * depth * dt;
    let absorbs = submerged & (gain > 0.0) & (h < hmax);
    let next = (h + gain).min(hmax);
    let loss = rates.evaporate * scale * dt;
    let dries = !submerged & (loss > 0.0) & (h > 0.0);
    let e = loss.min(h);
    let absorbed = if absorbs { next - h } else { 0.0 };
    let evaporated = if dries { e } else { 0.0 };
    let h = if absorbs {
        next
    } else if dries {
        h - e
    } else {
        h
    };
    (h, absorbed, evaporated)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rates() -> Rates {
        Rates::new(
            &Material::sand(),
            &Liquid::water(),
            &EnvironmentResponse::default(),
            &Environment::reference(),
            1000.0,
            9.81,
        )
    }

    #[test]
    fn the_branchless_form_computes_the_same_bits() {
        let values = [
            0.0,
            -0.0,
            1e-300,
            1e-9,
            3e-7,
            5e-7,
            0.1,
            0.3,
            0.5,
            1.0,
            10.0,
            -1.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let mut r = rates();
        for (absorb, evaporate) in [(r.absorb, r.evaporate), (0.0, 0.0), (1e3, 1e-2), (r.absorb, 0.0)] {
            (r.absorb, r.evaporate) = (absorb, evaporate);
            for &h in &values[..11] {
                for &depth in &values {
                    for scale in [0.0, 0.5, 1.0, 3.0] {
                        for dt in [0.0, 0.1, 10.0] {
                            let mut a = h;
                            let x = exchange(&mut a, &r, depth, scale, 0.0, false, dt);
                            let (b, absorbed, evaporated) = exchange_dry_sky(h, &r, depth, scale, dt);
                            assert_eq!(a.to_bits(), b.to_bits(), "{h} {depth} {scale} {dt}");
                            assert_eq!(x.absorbed.to_bits(), absorbed.to_bits());
                            assert_eq!(x.evaporated.to_bits(), evaporated.to_bits());
                            assert_eq!(x.rained, 0.0);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn darcy_absorption_has_the_stated_units() {
        let r = rates();
        // κ = 1e-9 m, μ = 1e-3 Pa s: κ ρ g / μ = 1e-9 · 9810 / 1e-3 = 9.81e-3 1/s.
        assert!((r.absorb - 9.81e-3).abs() < 1e-15);
        let mut h = 0.0;
        let x = exchange(&mut h, &r, 0.1, 1.0, 1.0, false, 1.0);
        assert!((h - 9.81e-4).abs() < 1e-15);
        assert_eq!(x.absorbed, h);
        // Capped at saturation.
        let x = exchange(&mut h, &r, 10.0, 1.0, 1.0, false, 1.0);
        assert_eq!(h, Material::sand().saturation);
        assert!(x.absorbed < 0.1);
    }

    #[test]
    fn evaporation_stops_at_zero_and_rain_falls_on_tops_only() {
        let mut r = rates();
        // f_env k_L C_M = 1 · 1e4 · 1e-11 = 1e-7 m/s.
        assert!((r.evaporate - 1e-7).abs() < 1e-20);
        let mut h = 5e-7;
        let x = exchange(&mut h, &r, -1.0, 1.0, 1.0, false, 10.0);
        assert_eq!(h, 0.0);
        assert_eq!(x.evaporated, 5e-7);
        r.evaporate = 0.0;
        r.rain = 1e-4;
        let x = exchange(&mut h, &r, f64::NAN, 1.0, 0.5, true, 1.0);
        assert!((x.rained - 5e-5).abs() < 1e-18);
        let x = exchange(&mut h, &r, -1.0, 1.0, -0.5, true, 1.0);
        assert_eq!(x.rained, 0.0);
        // Infinite depth with no permeability adds nothing (no 0 · ∞).
        r.absorb = 0.0;
        let before = h;
        exchange(&mut h, &r, f64::INFINITY, 1.0, 1.0, true, 1.0);
        assert_eq!(h, before);
    }
}
