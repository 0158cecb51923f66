//! The weather a wet surface dries in: temperature, humidity, wind and rain,
//! the thesis' environment factor `f_env` (Eq. 5.8, Table 5.1), and a track
//! of keyframes for weather that changes over time.

use serde::{Deserialize, Serialize};

use crate::error::{WetError, non_negative};
use crate::source::Rain;

/// Conditions around the wet bodies, the same for all of them (thesis §5.3.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Environment {
    /// Air temperature k_T, K.
    pub temperature: f64,
    /// Relative humidity k_h as a fraction in [0, 1] (the thesis writes it
    /// in %): at 1 the air is saturated and nothing evaporates.
    pub relative_humidity: f64,
    /// Wind speed k_w, m/s.
    pub wind_speed: f64,
    /// Rain falling on upward-facing dry texels; [`Rain::none`] for none.
    #[serde(default)]
    pub rain: Rain,
}

impl Default for Environment {
    /// A mild day: 20 °C, 50 % humidity, 2 m/s of wind, no rain.
    fn default() -> Self {
        Self {
            temperature: 293.15,
            relative_humidity: 0.5,
            wind_speed: 2.0,
            rain: Rain::none(),
        }
    }
}

impl Environment {
    /// Still, dry air at 20 °C: the conditions where `f_env = 1`.
    pub fn reference() -> Self {
        Self {
            temperature: 293.15,
            relative_humidity: 0.0,
            wind_speed: 0.0,
            rain: Rain::none(),
        }
    }

    /// Checks the temperature is positive, the humidity in [0, 1], the wind
    /// non-negative (all finite) and the rain valid.
    pub fn validate(&self) -> Result<(), WetError> {
        if !(self.temperature.is_finite() && self.temperature > 0.0) {
            return Err(WetError::parameter(
                "environment.temperature",
                self.temperature,
                "finite and > 0 K",
            ));
        }
        if !(0.0..=1.0).contains(&self.relative_humidity) {
            return Err(WetError::parameter(
                "environment.relative_humidity",
                self.relative_humidity,
                "a fraction in [0, 1]",
            ));
        }
        non_negative("environment.wind_speed", self.wind_speed)?;
        self.rain.validate()
    }
}

/// How the environment scales evaporation: `f_env = f_T · f_h · f_w`, the
/// product of three linear terms (thesis Eq. 5.8):
///
/// - temperature `f_T = max(0, 1 + α_T (T − T_ref))`; the default slope
///   α_T = 0.037 1/K is the secant of water's saturation vapour pressure
///   between 0 °C (0.26× its 20 °C value) and 20 °C;
/// - humidity `f_h = 1 − H`: the vapour gradient of Hall and Hoff's rate
///   (thesis Eq. 5.6) vanishes in saturated air;
/// - wind `f_w = 1 + α_w w`, α_w = 0.54 s/m as in Penman's wind function.
///
/// `f_env = 1` in still dry air at `T_ref` (20 °C by default).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EnvironmentResponse {
    /// T_ref, K.
    pub reference_temperature: f64,
    /// α_T, 1/K.
    pub temperature_slope: f64,
    /// α_w, s/m.
    pub wind_slope: f64,
}

impl Default for EnvironmentResponse {
    fn default() -> Self {
        Self {
            reference_temperature: 293.15,
            temperature_slope: 0.037,
            wind_slope: 0.54,
        }
    }
}

impl EnvironmentResponse {
    /// `f_env` for `env` (dimensionless, ≥ 0).
    pub fn factor(&self, env: &Environment) -> f64 {
        let t = (1.0 + self.temperature_slope * (env.temperature - self.reference_temperature)).max(0.0);
        let h = (1.0 - env.relative_humidity).clamp(0.0, 1.0);
        let w = (1.0 + self.wind_slope * env.wind_speed).max(0.0);
        t * h * w
    }

    /// Checks the fields are finite, the reference temperature positive
    /// and the slopes non-negative.
    pub fn validate(&self) -> Result<(), WetError> {
        if !(self.reference_temperature.is_finite() && self.reference_temperature > 0.0) {
            return Err(WetError::parameter(
                "response.reference_temperature",
                self.reference_temperature,
                "finite and > 0 K",
            ));
        }
        non_negative("response.temperature_slope", self.temperature_slope)?;
        non_negative("response.wind_slope", self.wind_slope)
    }
}

/// Weather over time: keyframes `(time in s, environment)`, linearly
/// interpolated between keys (temperature, humidity, wind and rain rate; the
/// rain's region is the earlier key's) and held before the first and after
/// the last.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnvironmentTrack {
    keys: Vec<(f64, Environment)>,
}

impl EnvironmentTrack {
    /// A track from keyframes in increasing time order, validated.
    pub fn new(keys: Vec<(f64, Environment)>) -> Result<Self, WetError> {
        if keys.is_empty() {
            return Err(WetError::parameter(
                "environment_track.keys",
                0.0,
                "at least one keyframe",
            ));
        }
        let mut last = f64::NEG_INFINITY;
        for (t, env) in &keys {
            if !t.is_finite() || *t <= last {
                return Err(WetError::parameter(
                    "environment_track.time",
                    *t,
                    "finite and increasing",
                ));
            }
            last = *t;
            env.validate()?;
        }
        Ok(Self { keys })
    }

    /// A track holding one environment at all times.
    pub fn constant(env: Environment) -> Self {
        Self {
            keys: vec![(0.0, env)],
        }
    }

    /// The keyframes.
    pub fn keys(&self) -> &[(f64, Environment)] {
        &self.keys
    }

    /// The environment at time `t` (s).
    pub fn at(&self, t: f64) -> Environment {
        let Some(first) = self.keys.first() else {
            return Environment::default();
        };
        if t.is_nan() || t <= first.0 {
            return first.1;
        }
        let k = self.keys.partition_point(|(tk, _)| *tk <= t);
        if k >= self.keys.len() {
            return self.keys[self.keys.len() - 1].1;
        }
        let (t0, a) = self.keys[k - 1];
        let (t1, b) = self.keys[k];
        let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        let lerp = |x: f64, y: f64| x + (y - x) * s;
        Environment {
            temperature: lerp(a.temperature, b.temperature),
            relative_humidity: lerp(a.relative_humidity, b.relative_humidity),
            wind_speed: lerp(a.wind_speed, b.wind_speed),
            rain: Rain {
                rate: lerp(a.rain.rate, b.rain.rate),
                region: a.rain.region,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factor_is_one_at_the_reference_and_linear_in_each_term() {
        let r = EnvironmentResponse::default();
        assert!((r.factor(&Environment::reference()) - 1.0).abs() < 1e-15);
        let humid = Environment {
            relative_humidity: 1.0,
            ..Environment::reference()
        };
        assert_eq!(r.factor(&humid), 0.0);
        let windy = Environment {
            wind_speed: 2.0,
            ..Environment::reference()
        };
        assert!((r.factor(&windy) - 2.08).abs() < 1e-12);
        let cold = Environment {
            temperature: 273.15,
            ..Environment::reference()
        };
        assert!((r.factor(&cold) - 0.26).abs() < 1e-12);
        let frozen = Environment {
            temperature: 200.0,
            ..Environment::reference()
        };
        assert_eq!(r.factor(&frozen), 0.0);
    }

    #[test]
    fn track_interpolates_and_holds() {
        let a = Environment::reference();
        let b = Environment {
            temperature: 303.15,
            wind_speed: 4.0,
            ..a
        };
        let track = EnvironmentTrack::new(vec![(10.0, a), (20.0, b)]).unwrap();
        assert_eq!(track.at(0.0), a);
        assert_eq!(track.at(25.0), b);
        let mid = track.at(15.0);
        assert!((mid.temperature - 298.15).abs() < 1e-12);
        assert!((mid.wind_speed - 2.0).abs() < 1e-12);
        assert!(EnvironmentTrack::new(vec![(1.0, a), (1.0, b)]).is_err());
        let bad = Environment {
            relative_humidity: 1.5,
            ..a
        };
        let e = EnvironmentTrack::new(vec![(0.0, bad)]).unwrap_err().to_string();
        assert!(e.contains("relative_humidity"), "{e}");
    }
}
