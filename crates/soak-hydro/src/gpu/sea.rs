//! A spectral sea read exactly on the device ([`SeaSampling::Exact`](crate::SeaSampling::Exact)):
//! its tile evaluated in the batch's own submission and inverted at every
//! texel, as [`SpectralSurface`] does on the CPU.
//!
//! Each mode's amplitude is turned to the time on the CPU (`A e^{−iωt}`, in
//! f64, so that the phase of a long run keeps its precision), and the device
//! does the rest: the seven layers of coefficients of the tile's fields
//! (`sea_modes.wgsl`), their inverse FFTs (the radix-2 Stockham stages of the
//! interactive waves, `waves.wgsl`), and the fields laid out per node in the
//! `heights` binding (`sea_unpack.wgsl`), which the buoyancy kernel reads
//! (`SURFACE_SPECTRAL` in `water_surface.wgsl`).

use nalgebra::Vector3;

use super::error::GpuHydroError;
use super::layout::{Body, SEA_NODE_FLOATS, SURFACE_SPECTRAL, u32_indexed};
use super::waves::{STAGE_STRIDE, Stage};
use crate::water::SpectralSurface;

/// Layers of the tile's transforms (two real fields each).
pub(crate) const SEA_LAYERS: u32 = 7;

/// One sea's uniform (`Sea` in `sea_modes.wgsl` and `sea_unpack.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct SeaUniform {
    pub n: u32,
    pub modes_first: u32,
    pub fields_first: u32,
    pub pad: u32,
    pub dk: f32,
    pub lambda: f32,
    pub gravity: f32,
    pub cell: f32,
}

/// The spectral seas of one batch read on the device, each once however
/// many bodies read it.
#[derive(Debug, Default)]
pub(crate) struct DeviceSeas {
    /// (surface address, its index in `seas`).
    seen: Vec<(usize, usize)>,
    /// Every sea's turned amplitudes, end to end (re, im).
    pub modes: Vec<[f32; 2]>,
    pub seas: Vec<SeaUniform>,
    /// Floats the device writes of every sea's fields, end to end: after
    /// the batch's own samples in the height buffer, from
    /// [`DeviceSeas::place`] on.
    pub fields: usize,
}

impl DeviceSeas {
    /// Whether no body reads a sea on the device.
    pub(crate) fn is_empty(&self) -> bool {
        self.seas.is_empty()
    }

    /// Fills `body`'s surface fields for the spectral sea `s` at time `t`
    /// (s), seen from the body's atlas origin at world `ow` (m): the sea's
    /// modes taken and room counted for its fields on its first body (its
    /// fields' first float counted from the seas' own, until
    /// [`DeviceSeas::place`]).
    ///
    /// # Errors
    /// [`GpuHydroError::Gpu`] for modes or fields a `u32` does not index;
    /// [`GpuHydroError::Water`] for a mode whose turned amplitude is not
    /// finite.
    pub(crate) fn encode(
        &mut self,
        index: usize,
        s: &SpectralSurface,
        ow: &Vector3<f64>,
        t: f64,
        body: &mut Body,
    ) -> Result<(), GpuHydroError> {
        let sea = s.sea();
        let n = sea.cells;
        let key = s as *const SpectralSurface as usize;
        let k = match self.seen.iter().find(|e| e.0 == key) {
            Some(&(_, k)) => k,
            None => {
                let floats = n * n * SEA_NODE_FLOATS;
                u32_indexed(
                    "the spectral seas' fields of this batch",
                    self.fields as u64 + floats as u64,
                )?;
                u32_indexed(
                    "the spectral seas' modes of this batch",
                    self.modes.len() as u64 + (n * n) as u64,
                )?;
                let uniform = SeaUniform {
                    n: n as u32,
                    modes_first: self.modes.len() as u32,
                    fields_first: self.fields as u32,
                    pad: 0,
                    dk: (std::f64::consts::TAU / sea.size) as f32,
                    lambda: sea.choppiness as f32,
                    gravity: sea.gravity as f32,
                    cell: (sea.size / n as f64) as f32,
                };
                let turned = sea.turned_amplitudes(t);
                if let Some(a) = turned.iter().find(|a| !(a.re.is_finite() && a.im.is_finite())) {
                    return Err(GpuHydroError::Water {
                        body: index,
                        source: crate::WaterError::Parameter {
                            name: "sea mode amplitude",
                            value: if a.re.is_finite() { a.im } else { a.re },
                        },
                    });
                }
                self.modes
                    .extend(turned.iter().map(|a| [a.re as f32, a.im as f32]));
                self.fields += floats;
                self.seas.push(uniform);
                self.seen.push((key, self.seas.len() - 1));
                self.seas.len() - 1
            }
        };
        let d = sea.size / n as f64;
        // o_w's node (wrapped into the tile) and its place across the cell:
        // rest positions are counted from that node.
        let axis = |w: f64| {
            let g = w / d;
            let f = g.floor();
            let i = if f.abs() < 9.0e15 {
                (f as i64).rem_euclid(n as i64) as u32
            } else {
                0
            };
            (i, (g - f) as f32)
        };
        let (ix, fx) = axis(ow.x);
        let (iz, fz) = axis(ow.z);
        body.info = [
            SURFACE_SPECTRAL,
            self.seas[k].fields_first,
            n as u32,
            ix | (iz << 16),
        ];
        body.surface = [fx, fz, (1.0 / d) as f32, d as f32];
        body.surface2 = [(sea.level - ow.y) as f32, s.mean_wavenumber() as f32, 0.0, 0.0];
        body.current = [0.0; 4];
        Ok(())
    }

    /// Lays the seas' fields after the batch's `samples` floats of the
    /// height buffer (so that the upload stops there, and the device writes
    /// the rest): every sea's first float and those of `bodies` reading one
    /// moved on by `samples`.
    ///
    /// # Errors
    /// [`GpuHydroError::Gpu`] where the whole does not fit a `u32` index.
    pub(crate) fn place(&mut self, samples: usize, bodies: &mut [Body]) -> Result<(), GpuHydroError> {
        u32_indexed(
            "the height fields and spectral seas of this batch",
            samples as u64 + self.fields as u64,
        )?;
        let base = samples as u32;
        for sea in &mut self.seas {
            sea.fields_first += base;
        }
        for body in bodies.iter_mut().filter(|b| b.info[0] == SURFACE_SPECTRAL) {
            body.info[1] += base;
        }
        Ok(())
    }

    /// The uniforms of every sea, each at a multiple of [`STAGE_STRIDE`]:
    /// per sea its [`SeaUniform`], then its FFT's stages (inverse, rows then
    /// columns, [`SEA_LAYERS`] layers); and where each sea's begin.
    pub(crate) fn uniforms(&self) -> (Vec<u8>, Vec<u64>) {
        fn push(data: &mut Vec<u8>, bytes: &[u8]) {
            let at = data.len();
            data.resize(at + STAGE_STRIDE as usize, 0);
            data[at..at + bytes.len()].copy_from_slice(bytes);
        }
        let mut data = Vec::new();
        let mut firsts = Vec::with_capacity(self.seas.len());
        for sea in &self.seas {
            firsts.push(data.len() as u64);
            push(&mut data, bytemuck::bytes_of(sea));
            let log = sea.n.trailing_zeros();
            for (line_stride, pos_stride) in [(sea.n, 1), (1, sea.n)] {
                for s in 0..log {
                    push(
                        &mut data,
                        bytemuck::bytes_of(&Stage {
                            n: sea.n,
                            p: 1 << s,
                            line_stride,
                            pos_stride,
                            sign: 1.0,
                            layers: SEA_LAYERS,
                            pad: [0; 2],
                        }),
                    );
                }
            }
        }
        (data, firsts)
    }

    /// Bytes of the largest sea's seven layers of complex values.
    pub(crate) fn layer_bytes(&self) -> u64 {
        self.seas
            .iter()
            .map(|s| u64::from(SEA_LAYERS) * u64::from(s.n) * u64::from(s.n) * 8)
            .max()
            .unwrap_or(0)
    }
}
