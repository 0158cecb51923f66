//! Waves that bodies make: an interactive, dispersive height field over a
//! square region ([`InteractiveWaves`]), linear deep water solved exactly
//! mode by mode.
//!
//! The surface's elevation `h` and velocity potential `φ` (at the surface)
//! obey linear deep-water theory, `∂h/∂t = |k| φ`, `∂φ/∂t = −g h − p/ρ` in
//! Fourier space (`p` the pressure applied at the surface, e.g. by a
//! body's hull): every mode of wavenumber `k` turns at `ω = √(g k)`, the
//! deep-water dispersion, about the depression `−p/(ρ g)` a steady
//! pressure holds. With the pressure held over a step the step is the
//! exact rotation: no numerical dispersion, no damping, no stability
//! limit on the time step (iWave, Tessendorf 2004, approximates the same
//! operator `|k|` by a convolution kernel and steps it explicitly). The
//! energy `E = ½ ρ ∫ (g h² + φ |k| φ) dA` is conserved exactly without
//! pressure, and the work a pressure does is `−∫ p ∂h/∂t dA`.
//!
//! The region is periodic for the transform; a sponge along its border
//! absorbs the waves that reach it ([`InteractiveWaves::absorbed`] counts
//! their energy), so that they do not come back in on the other side.

use crate::fft2::Fft2;
use rustfft::num_complex::Complex;
use serde::Serialize;

use crate::error::WaterError;

mod on_waves;
mod region;
#[cfg(test)]
mod tests;

use self::on_waves::OnWaves;
use self::region::bilinear;
pub(crate) use self::region::check_waves;
pub use self::region::{MAX_WAVE_CELLS, WaveHeights, WaveRegion};

/// What an [`InteractiveWaves`] evolves ([`InteractiveWaves::state`]).
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct WavesState {
    /// The region's centre `(x, z)`, world, m.
    pub centre: [f64; 2],
    /// Time stepped, s.
    pub time: f64,
    /// Energy the sponge took, J.
    pub absorbed: f64,
    /// Elevation per cell, m.
    pub h: Vec<f64>,
    /// Surface velocity potential per cell, m²/s.
    pub phi: Vec<f64>,
}

/// An interactive deep-water height field: the surface's elevation `h` and
/// velocity potential `φ` obey linear deep-water theory, `∂h/∂t = |k| φ`,
/// `∂φ/∂t = −g h − p/ρ` in Fourier space (`p` the pressure on the surface,
/// a hull's), so every mode turns at `ω = √(g k)` about the depression
/// `−p/(ρ g)` a steady pressure holds. With the pressure held over a step
/// the step is that rotation, exactly: no numerical dispersion, no
/// damping, no limit on the time step. The energy
/// `E = ½ ρ ∫ (g h² + φ |k| φ) dA` is kept without pressure; a pressure
/// does the work `−∫ p ∂h/∂t dA`. The region is periodic for the
/// transform; a sponge along its border absorbs the waves that reach it
/// ([`InteractiveWaves::absorbed`]).
pub struct InteractiveWaves {
    region: WaveRegion,
    gravity: f64,
    density: f64,
    /// Elevation, m, cell `(ix, iz)` at `iz · n + ix`.
    h: Vec<f64>,
    /// Surface velocity potential, m²/s.
    phi: Vec<f64>,
    /// Pressure over density applied this step, m²/s² (`g` times the
    /// depth a hull pushes the surface down by).
    pressure: Vec<f64>,
    /// Sponge width, cells.
    sponge: usize,
    /// Energy the sponge took, J.
    absorbed: f64,
    time: f64,
    fft: Fft2,
    scratch: Vec<Complex<f64>>,
    /// `|k|` per mode, rad/m, in the transform's order.
    k: Vec<f64>,
    /// The step's rotation per mode for the last `dt`: `(dt, [cos ωdt,
    /// sin ωdt · k/ω, sin ωdt · g/ω])`, made again when `dt` changes.
    turn: Option<(f64, Vec<[f64; 3]>)>,
}

impl std::fmt::Debug for InteractiveWaves {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InteractiveWaves")
            .field("region", &self.region)
            .field("gravity", &self.gravity)
            .field("density", &self.density)
            .field("time", &self.time)
            .finish_non_exhaustive()
    }
}

impl InteractiveWaves {
    /// Still water over `region` under `gravity` (m/s²) of `density`
    /// (kg/m³), with a sponge `sponge` cells wide along the border (0 for
    /// none: waves leaving one side come in on the other).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for a region, gravity or density that is
    /// not finite and > 0, fewer than 8 cells, more than
    /// [`MAX_WAVE_CELLS`] or an odd count, or a sponge wider than a quarter
    /// of the region.
    pub fn new(region: WaveRegion, gravity: f64, density: f64, sponge: usize) -> Result<Self, WaterError> {
        check_waves(&region, gravity, density, sponge)?;
        let n = region.cells;
        Ok(Self {
            region,
            gravity,
            density,
            h: vec![0.0; n * n],
            phi: vec![0.0; n * n],
            pressure: vec![0.0; n * n],
            sponge,
            absorbed: 0.0,
            time: 0.0,
            fft: Fft2::new(n),
            scratch: vec![Complex::default(); n * n],
            k: {
                let base = 2.0 * std::f64::consts::PI / region.size;
                let signed = |i: usize| if i < n / 2 { i as f64 } else { i as f64 - n as f64 };
                (0..n * n)
                    .map(|i| base * (signed(i % n).powi(2) + signed(i / n).powi(2)).sqrt())
                    .collect()
            },
            turn: None,
        })
    }

    /// The region.
    pub fn region(&self) -> &WaveRegion {
        &self.region
    }

    /// The gravity the waves fall under, m/s².
    pub fn gravity(&self) -> f64 {
        self.gravity
    }

    /// Time stepped so far, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The elevation per cell, m (cell `(ix, iz)` at `iz · n + ix`, its
    /// centre at [`InteractiveWaves::cell_centre`]).
    pub fn heights(&self) -> &[f64] {
        &self.h
    }

    /// The centre `(x, z)` of cell `(ix, iz)`, world, m.
    pub fn cell_centre(&self, ix: usize, iz: usize) -> [f64; 2] {
        let (x0, z0) = self.corner();
        let d = self.region.cell();
        [x0 + (ix as f64 + 0.5) * d, z0 + (iz as f64 + 0.5) * d]
    }

    fn corner(&self) -> (f64, f64) {
        let half = 0.5 * self.region.size;
        (self.region.centre[0] - half, self.region.centre[1] - half)
    }

    /// The elevation at `(x, z)` (world, m), bilinear between cell centres;
    /// 0 outside the region.
    pub fn height(&self, x: f64, z: f64) -> f64 {
        bilinear(&self.region, &self.h, x, z)
    }

    /// The elevation now, to keep or draw ([`WaveHeights`]).
    pub fn snapshot(&self) -> WaveHeights {
        WaveHeights {
            region: self.region,
            heights: self.h.clone(),
        }
    }

    /// The crests along a ray: the distances (m) from `from` (`(x, z)`,
    /// world, m) along `heading` (radians from +x towards +z) between
    /// `near` and `far` where the elevation has a local maximum above 0,
    /// the profile read every tenth of a cell. For a ring's crests.
    pub fn crests(&self, from: [f64; 2], heading: f64, near: f64, far: f64) -> Vec<f64> {
        let step = 0.1 * self.region.cell();
        let samples = ((far - near) / step).ceil().max(2.0) as usize;
        let (s, c) = heading.sin_cos();
        let profile: Vec<(f64, f64)> = (0..=samples)
            .map(|k| {
                let r = near + (far - near) * k as f64 / samples as f64;
                (r, self.height(from[0] + r * c, from[1] + r * s))
            })
            .collect();
        profile
            .windows(3)
            .filter(|w| w[1].1 > w[0].1 && w[1].1 >= w[2].1 && w[1].1 > 0.0)
            .map(|w| w[1].0)
            .collect()
    }

    /// Crests of a ring against the deep-water group velocity, `t` seconds
    /// after the disturbance that sent it out, under `gravity` (m/s²): for
    /// each pair of neighbouring crests (distances from the disturbance, m,
    /// increasing, as [`InteractiveWaves::crests`] gives them) whose waves
    /// are at least `shortest` long (m; the wavelength at `r` is
    /// `8π r²/(g t²)`) and where stationary phase holds (the phase
    /// `g t²/(4r)` over 3π at the outer crest), the inner and outer
    /// distance and the phase's step between them over 2π: 1 where each
    /// wavelength is where its group velocity `½ √(g/k)` has carried it
    /// (Cauchy–Poisson).
    pub fn phase_steps(crests: &[f64], t: f64, gravity: f64, shortest: f64) -> Vec<(f64, f64, f64)> {
        let tau = 2.0 * std::f64::consts::PI;
        let phase = |r: f64| gravity * t * t / (4.0 * r);
        crests
            .windows(2)
            .filter(|pair| {
                let wavelength = 4.0 * tau * pair[0] * pair[0] / (gravity * t * t);
                wavelength >= shortest && phase(pair[1]) >= 1.5 * tau
            })
            .map(|pair| (pair[0], pair[1], (phase(pair[0]) - phase(pair[1])) / tau))
            .collect()
    }

    /// The half-angle (degrees) of the wake of a source at `source`
    /// (`(x, z)`, world, m) moving along `heading` (radians from +x towards
    /// +z), seen `behind` metres behind it, on the side to its right of
    /// the track (+z for heading 0): across the track, the local amplitude
    /// (the largest |h| within a metre along the track) rises to the cusp
    /// waves' peak and then falls off as Airy's function does past a
    /// caustic; the caustic, Kelvin's line, is taken where it has fallen to
    /// `Ai(0)/max Ai = 0.663` of that peak (the peak lies inside the line
    /// and nears it only slowly with the distance behind). Read at 0.1°
    /// steps up to 40°.
    pub fn wake_half_angle(&self, source: [f64; 2], heading: f64, behind: f64) -> f64 {
        let (s, c) = heading.sin_cos();
        let amplitudes: Vec<f64> = (0..=400)
            .map(|j| {
                let across = behind * (0.1 * j as f64).to_radians().tan();
                (0..=20)
                    .map(|k| {
                        let along = -behind - 1.0 + 0.1 * k as f64;
                        let x = source[0] + along * c - across * s;
                        let z = source[1] + along * s + across * c;
                        self.height(x, z).abs()
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        let (peak, max) = amplitudes
            .iter()
            .enumerate()
            .fold((0, 0.0), |a, (j, &v)| if v > a.1 { (j, v) } else { a });
        let edge = (peak..amplitudes.len())
            .find(|&j| amplitudes[j] < 0.663 * max)
            .unwrap_or(amplitudes.len());
        0.1 * edge as f64
    }

    /// Clears the pressure applied at the surface.
    pub fn clear_pressure(&mut self) {
        self.pressure.iter_mut().for_each(|p| *p = 0.0);
    }

    /// The pressure over density held at the surface, per cell, m²/s².
    pub fn pressure(&self) -> &[f64] {
        &self.pressure
    }

    /// The pressure over density applied at the surface this step, per cell,
    /// m²/s² (`g` times the depth a hull holds the surface down by), to
    /// add a body's footprint to.
    pub fn pressure_mut(&mut self) -> &mut [f64] {
        &mut self.pressure
    }

    /// Adds a Gaussian pressure `ρ g depth · exp(−r²/(2σ²))` centred at
    /// `(x, z)` (world, m): a round hull of draft `depth` (m) and radius
    /// about `2σ`.
    pub fn add_gaussian(&mut self, x: f64, z: f64, sigma: f64, depth: f64) {
        let n = self.region.cells;
        let g = self.gravity;
        for iz in 0..n {
            for ix in 0..n {
                let [cx, cz] = self.cell_centre(ix, iz);
                let r2 = (cx - x).powi(2) + (cz - z).powi(2);
                if r2 < 36.0 * sigma * sigma {
                    self.pressure[iz * n + ix] += g * depth * (-r2 / (2.0 * sigma * sigma)).exp();
                }
            }
        }
    }

    /// Presses a body's hull on the surface: [`InteractiveWaves::pressed`]
    /// added to the pressure ([`InteractiveWaves::add_pressure`]). Returns
    /// the cells touched and the depth (m) added to each.
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for a state that is not finite.
    pub fn press(
        &mut self,
        atlas: &soak_bake::Atlas,
        water: &crate::Water,
        state: &crate::BodyState,
        t: f64,
    ) -> Result<Vec<(usize, f64)>, WaterError> {
        let pressed = self.pressed(atlas, water, state, t)?;
        self.add_pressure(&pressed);
        Ok(pressed)
    }

    /// What a body's hull would press on the surface: every submerged
    /// texel of `atlas` at `state` adds its column, `−A_y d` (m³: its
    /// area's vertical part times its depth under `water`'s surface,
    /// negative for the texels on top of the submerged part), to the cell
    /// under it, so that each cell holds the submerged height of the body
    /// over it. Returns the cells touched (in increasing order) and that
    /// depth (m) for each: `ρ g` times it is the pressure the hull holds
    /// the surface down with, and the sum times a cell's area is the
    /// body's submerged volume. Texels outside the region press nothing.
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for a state that is not finite.
    pub fn pressed(
        &self,
        atlas: &soak_bake::Atlas,
        water: &crate::Water,
        state: &crate::BodyState,
        t: f64,
    ) -> Result<Vec<(usize, f64)>, WaterError> {
        let finite = state.pose.translation.vector.iter().all(|c| c.is_finite())
            && state.pose.rotation.coords.iter().all(|c| c.is_finite());
        if !finite {
            return Err(WaterError::Parameter {
                name: "waves.body_pose",
                value: f64::NAN,
            });
        }
        let n = self.region.cells;
        let d = self.region.cell();
        let (x0, z0) = self.corner();
        let rot = state.pose.rotation.to_rotation_matrix().into_inner();
        let ow = (state.pose * atlas.origin()).coords;
        let mut columns: std::collections::BTreeMap<usize, f64> = std::collections::BTreeMap::new();
        for i in 0..atlas.len() {
            let (x, a) = crate::hydrostatics::frame::texel(atlas, i);
            let p = rot * x + ow;
            let depth = water.surface.depth(&nalgebra::Point3::from(p), t);
            if depth.is_nan() || depth <= 0.0 {
                continue;
            }
            let (u, v) = ((p.x - x0) / d, (p.z - z0) / d);
            if !(u >= 0.0 && v >= 0.0 && u < n as f64 && v < n as f64) {
                continue;
            }
            let cell = (v as usize) * n + u as usize;
            *columns.entry(cell).or_insert(0.0) += -(rot * a).y * depth / (d * d);
        }
        Ok(columns
            .into_iter()
            .filter(|(_, depth)| depth.is_finite())
            .collect())
    }

    /// Adds what [`InteractiveWaves::pressed`] found to the pressure: `g`
    /// times each cell's depth (cells outside the region are left out).
    pub fn add_pressure(&mut self, pressed: &[(usize, f64)]) {
        let g = self.gravity;
        for &(cell, depth) in pressed {
            if let Some(p) = self.pressure.get_mut(cell) {
                *p += g * depth;
            }
        }
    }

    /// Lowers the surface by what [`InteractiveWaves::pressed`] found, at
    /// rest: the depression a hull held still that long would hold (each
    /// mode's rest under a steady pressure is `−p/(ρ g)`, cell by cell), so
    /// that a body set on the water at its floating level starts no waves.
    pub fn hold(&mut self, pressed: &[(usize, f64)]) {
        for &(cell, depth) in pressed {
            if let Some(h) = self.h.get_mut(cell) {
                *h -= depth;
            }
        }
    }

    /// Renumbers cells found before a [`InteractiveWaves::recentre`] that
    /// shifted the region by `shift` (cells along x and z) for the region
    /// now, dropping those that left it.
    pub fn shift_cells(&self, cells: &mut Vec<(usize, f64)>, shift: (i64, i64)) {
        if shift == (0, 0) {
            return;
        }
        let n = self.region.cells as i64;
        cells.retain_mut(|(cell, _)| {
            let (ix, iz) = ((*cell as i64) % n - shift.0, (*cell as i64) / n - shift.1);
            let inside = (0..n).contains(&ix) && (0..n).contains(&iz);
            if inside {
                *cell = (iz * n + ix) as usize;
            }
            inside
        });
    }

    /// The highest elevation over the region, m (0 for still water).
    pub fn highest(&self) -> f64 {
        self.h.iter().fold(0.0, |a, &h| a.max(h))
    }

    /// The water a body at `state` floats on: `base` with these waves on
    /// it, less the body's own depression `own` (what
    /// [`InteractiveWaves::pressed`] found for it the step before: a hull
    /// does not sink into the hollow it holds, it feels the waves and what
    /// its own motion stirred), sampled once over the body's footprint on
    /// the cells' grid as a [`SurfacePatch`](crate::SurfacePatch) (heights
    /// at the cell centres, slopes by central differences; with
    /// `with_velocity` also the base's fluid velocity). `None` when the
    /// footprint misses the region: the body floats on `base` alone.
    ///
    /// The waves' own orbital velocity is not in the patch (the drag sees
    /// the base's current only).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for a state that is not finite.
    pub fn water_for(
        &self,
        base: &crate::Water,
        atlas: &soak_bake::Atlas,
        state: &crate::BodyState,
        own: &[(usize, f64)],
        t: f64,
        with_velocity: bool,
    ) -> Result<Option<crate::Water>, WaterError> {
        let centre = state.pose * atlas.origin();
        let radius = atlas.bounding_radius();
        if !(centre.coords.iter().all(|c| c.is_finite()) && radius.is_finite()) {
            return Err(WaterError::Parameter {
                name: "waves.body_pose",
                value: f64::NAN,
            });
        }
        let d = self.region.cell();
        let (x0, z0) = self.corner();
        let reach = radius + 2.0 * d;
        let half = 0.5 * self.region.size;
        let [cx, cz] = self.region.centre;
        if (centre.x - cx).abs() > half + reach || (centre.z - cz).abs() > half + reach {
            return Ok(None);
        }
        // Nodes on the cell centres.
        let align = |c: f64, o: f64| o + (((c - o) / d - 0.5).floor() + 0.5) * d;
        let min = [align(centre.x - reach, x0), align(centre.z - reach, z0)];
        let max = [centre.x + reach, centre.z + reach];
        let surface = OnWaves {
            base: &*base.surface,
            waves: self,
            own,
        };
        let velocity = with_velocity.then_some((centre.y - radius, centre.y + radius));
        let patch = crate::SurfacePatch::sample(&surface, t, min, max, d, velocity)?;
        Ok(Some(base.under(patch)))
    }

    /// The elevation (m) and its slope at `(x, z)` (world, m) of the cell
    /// values `value(ix, iz)` (0 outside the region): bilinear between the
    /// cell centres, the slope bilinear between central differences there.
    fn field(&self, x: f64, z: f64, value: impl Fn(i64, i64) -> f64) -> (f64, [f64; 2]) {
        let d = self.region.cell();
        let (x0, z0) = self.corner();
        let (u, v) = ((x - x0) / d - 0.5, (z - z0) / d - 0.5);
        let (i, j) = (u.floor(), v.floor());
        let (fu, fv) = (u - i, v - j);
        let (i, j) = (i as i64, j as i64);
        let weights = [
            (0, 0, (1.0 - fu) * (1.0 - fv)),
            (1, 0, fu * (1.0 - fv)),
            (0, 1, (1.0 - fu) * fv),
            (1, 1, fu * fv),
        ];
        let (mut h, mut sx, mut sz) = (0.0, 0.0, 0.0);
        for (di, dj, w) in weights {
            let (a, b) = (i + di, j + dj);
            h += w * value(a, b);
            sx += w * (value(a + 1, b) - value(a - 1, b)) / (2.0 * d);
            sz += w * (value(a, b + 1) - value(a, b - 1)) / (2.0 * d);
        }
        (h, [sx, sz])
    }

    /// Moves the region to be centred as near `centre` (`(x, z)`, world,
    /// m) as a whole number of cells allows, keeping the surface where it
    /// is in the world; cells that come in are still water, and the energy
    /// of the waves that leave is counted as absorbed. Returns the shift,
    /// cells along x and z.
    pub fn recentre(&mut self, centre: [f64; 2]) -> (i64, i64) {
        let d = self.region.cell();
        let sx = ((centre[0] - self.region.centre[0]) / d).round() as i64;
        let sz = ((centre[1] - self.region.centre[1]) / d).round() as i64;
        if sx == 0 && sz == 0 || !(centre[0].is_finite() && centre[1].is_finite()) {
            return (0, 0);
        }
        let before = self.energy();
        let n = self.region.cells as i64;
        let shift = |values: &[f64]| {
            let mut out = vec![0.0; values.len()];
            for iz in 0..n {
                for ix in 0..n {
                    let (fx, fz) = (ix + sx, iz + sz);
                    if (0..n).contains(&fx) && (0..n).contains(&fz) {
                        out[(iz * n + ix) as usize] = values[(fz * n + fx) as usize];
                    }
                }
            }
            out
        };
        self.h = shift(&self.h);
        self.phi = shift(&self.phi);
        self.pressure = shift(&self.pressure);
        self.region.centre[0] += sx as f64 * d;
        self.region.centre[1] += sz as f64 * d;
        self.absorbed += (before - self.energy()).max(0.0);
        (sx, sz)
    }

    /// Sets the elevation (m) and potential (m²/s) per cell, e.g. a
    /// disturbance to watch spread.
    ///
    /// # Errors
    /// [`WaterError::HeightFieldShape`] for slices of another length,
    /// [`WaterError::HeightFieldSample`] for a value that is not finite.
    pub fn set_state(&mut self, h: &[f64], phi: &[f64]) -> Result<(), WaterError> {
        let n = self.region.cells;
        for values in [h, phi] {
            if values.len() != n * n {
                return Err(WaterError::HeightFieldShape {
                    nx: n,
                    nz: n,
                    len: values.len(),
                });
            }
            if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(WaterError::HeightFieldSample { index, value });
            }
        }
        self.h.copy_from_slice(h);
        self.phi.copy_from_slice(phi);
        Ok(())
    }

    /// What the surface has become, for saving: the region's centre, the
    /// time, the sponge's energy and each cell's elevation and potential.
    pub fn state(&self) -> WavesState {
        WavesState {
            centre: self.region.centre,
            time: self.time,
            absorbed: self.absorbed,
            h: self.h.clone(),
            phi: self.phi.clone(),
        }
    }

    /// Takes a state [`InteractiveWaves::state`] saved from a surface over
    /// a region of the same size and cells; the pressure is cleared.
    ///
    /// # Errors
    /// As [`InteractiveWaves::set_state`], and [`WaterError::Parameter`]
    /// for a centre, time or absorbed energy that is not finite.
    pub fn restore(&mut self, state: &WavesState) -> Result<(), WaterError> {
        for (name, value) in [
            ("waves.centre", state.centre[0] + state.centre[1]),
            ("waves.time", state.time),
            ("waves.absorbed", state.absorbed),
        ] {
            if !value.is_finite() {
                return Err(WaterError::Parameter { name, value });
            }
        }
        self.set_state(&state.h, &state.phi)?;
        self.region.centre = state.centre;
        self.time = state.time;
        self.absorbed = state.absorbed;
        self.clear_pressure();
        Ok(())
    }

    /// The energy of the waves in the region, J: `½ ρ ∫ (g h² + φ |k| φ) dA`.
    pub fn energy(&self) -> f64 {
        self.energy_about(&[])
    }

    /// The energy of the waves about the depressions `held` (cells and
    /// depths, m, as [`InteractiveWaves::pressed`] returns them: the
    /// surface the hulls pressing them hold at rest), J:
    /// `½ ρ ∫ (g (h + d)² + φ |k| φ) dA`. With the bodies' presses this is
    /// the energy their motion radiated and that is still in the region;
    /// with none it is [`InteractiveWaves::energy`].
    pub fn energy_about(&self, held: &[&[(usize, f64)]]) -> f64 {
        let n = self.region.cells;
        let area = self.region.cell().powi(2);
        let mut h = self.h.clone();
        for cells in held {
            for &(cell, depth) in *cells {
                if let Some(h) = h.get_mut(cell) {
                    *h += depth;
                }
            }
        }
        let potential: f64 = h.iter().map(|h| h * h).sum::<f64>() * 0.5 * self.density * self.gravity * area;
        let phi = self.transform(&self.phi, &mut vec![Complex::default(); n * n]);
        let kinetic: f64 = self.k.iter().zip(&phi).map(|(k, p)| k * p.norm_sqr()).sum();
        potential + 0.5 * self.density * kinetic * area / (n * n) as f64
    }

    /// The energy the sponge took from the waves reaching the border so
    /// far, J.
    pub fn absorbed(&self) -> f64 {
        self.absorbed
    }

    /// The 2-D forward transform of `values` (unnormalised).
    fn transform(&self, values: &[f64], scratch: &mut [Complex<f64>]) -> Vec<Complex<f64>> {
        let mut data: Vec<Complex<f64>> = values.iter().map(|&v| Complex::new(v, 0.0)).collect();
        self.fft2(&mut data, true, scratch);
        data
    }

    /// The 2-D transform in place.
    fn fft2(&self, data: &mut [Complex<f64>], forward: bool, scratch: &mut [Complex<f64>]) {
        self.fft.process(data, forward, scratch);
    }

    /// Advances the surface by `dt` (s) with the pressure held over the
    /// step (exactly: see [`InteractiveWaves`]), then lets the sponge
    /// absorb what reached the border.
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for a `dt` that is not finite and > 0, or
    /// a pressure that is not finite (the surface is then unchanged).
    pub fn step(&mut self, dt: f64) -> Result<(), WaterError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(WaterError::Parameter {
                name: "waves.dt",
                value: dt,
            });
        }
        if let Some(&p) = self.pressure.iter().find(|p| !p.is_finite()) {
            return Err(WaterError::Parameter {
                name: "waves.pressure",
                value: p,
            });
        }
        let n = self.region.cells;
        let g = self.gravity;
        let mut scratch = std::mem::take(&mut self.scratch);
        let mut h = self.transform(&self.h, &mut scratch);
        let mut phi = self.transform(&self.phi, &mut scratch);
        let p = if self.pressure.iter().all(|&p| p == 0.0) {
            vec![Complex::default(); n * n]
        } else {
            self.transform(&self.pressure, &mut scratch)
        };
        if self.turn.as_ref().is_none_or(|(t, _)| *t != dt) {
            let turn = self
                .k
                .iter()
                .map(|&k| {
                    let omega = (g * k).sqrt();
                    let (s, c) = (omega * dt).sin_cos();
                    if k == 0.0 {
                        [1.0, 0.0, 0.0]
                    } else {
                        [c, k / omega * s, g / omega * s]
                    }
                })
                .collect();
            self.turn = Some((dt, turn));
        }
        let turn = &self.turn.as_ref().expect("made above").1;
        for i in 0..n * n {
            if self.k[i] == 0.0 {
                phi[i] -= (h[i] * g + p[i]) * dt;
                continue;
            }
            let [c, hs, ps] = turn[i];
            // About the depression the pressure holds, −P/g.
            let rest = h[i] + p[i] / g;
            h[i] = rest * c + phi[i] * hs - p[i] / g;
            phi[i] = phi[i] * c - rest * ps;
        }
        // The energy now, from the modes (Parseval), for the sponge's account.
        let before = (self.sponge > 0).then(|| {
            let sum: f64 = (0..n * n)
                .map(|i| g * h[i].norm_sqr() + self.k[i] * phi[i].norm_sqr())
                .sum();
            0.5 * self.density * sum * self.region.cell().powi(2) / (n * n) as f64
        });
        self.fft2(&mut h, false, &mut scratch);
        self.fft2(&mut phi, false, &mut scratch);
        self.scratch = scratch;
        let scale = 1.0 / (n * n) as f64;
        for i in 0..n * n {
            self.h[i] = h[i].re * scale;
            self.phi[i] = phi[i].re * scale;
        }
        if let Some(before) = before {
            self.absorb(dt, before);
        }
        self.time += dt;
        Ok(())
    }

    /// The sponge: within `sponge` cells of the border, `h` and `φ` decay
    /// at a rate growing as the square of the depth into the sponge, up to
    /// `ω` of a wave two sponge-widths long (a few of its periods to
    /// cross). The energy it takes is the waves' energy before less after.
    fn absorb(&mut self, dt: f64, before: f64) {
        let n = self.region.cells;
        let w = self.sponge as f64;
        let d = self.region.cell();
        let k = std::f64::consts::PI / (w * d);
        let rate = (self.gravity * k).sqrt();
        for iz in 0..n {
            for ix in 0..n {
                let edge = ix.min(iz).min(n - 1 - ix).min(n - 1 - iz) as f64;
                if edge >= w {
                    continue;
                }
                let depth = (w - edge) / w;
                let factor = (-rate * depth * depth * dt).exp();
                let i = iz * n + ix;
                self.h[i] *= factor;
                self.phi[i] *= factor;
            }
        }
        self.absorbed += before - self.energy();
    }
}
