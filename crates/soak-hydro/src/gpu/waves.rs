//! The interactive waves' solver on the GPU ([`GpuWaves`]): the step of
//! [`InteractiveWaves`](crate::InteractiveWaves) (every mode turned exactly
//! at `ω = √(g k)` about the depression the pressure holds, then the
//! sponge) with a radix-2 Stockham FFT in compute kernels, f32 on the
//! device.

use soak_gpu::{Binding, Kernel, read_back, scoped};

use super::error::GpuHydroError;
use crate::error::WaterError;
use crate::waves::{WaveRegion, check_waves};

pub(super) const FFT: &str = include_str!("../../shaders/waves.wgsl");
const MODES: &str = include_str!("../../shaders/waves_modes.wgsl");
const FINISH: &str = include_str!("../../shaders/waves_finish.wgsl");

/// Bytes between the uniform structs of the FFT's stages (the WebGPU
/// baseline's uniform offset alignment).
pub(super) const STAGE_STRIDE: u64 = 256;

/// One FFT stage's uniform (`Stage` in `waves.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct Stage {
    pub n: u32,
    pub p: u32,
    pub line_stride: u32,
    pub pos_stride: u32,
    pub sign: f32,
    pub layers: u32,
    pub pad: [u32; 2],
}

/// The rotation's uniform (`Modes` in `waves_modes.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Modes {
    n: u32,
    pad0: u32,
    base: f32,
    g: f32,
    dt: f32,
    pad: [f32; 3],
}

/// The finish's uniform (`Finish` in `waves_finish.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Finish {
    n: u32,
    sponge: u32,
    rate: f32,
    dt: f32,
}

/// Interactive deep-water waves stepped on the GPU: the same step as
/// [`InteractiveWaves::step`](crate::InteractiveWaves::step) (the exact
/// per-mode rotation under the pressure held over the step, then the
/// sponge), in f32, with one submission per step. The surface stays on the
/// device; [`GpuWaves::heights`] reads the elevation back.
///
/// Cells per side must be a power of two (the FFT is radix-2). The
/// sponge's energy is not counted on the device: use
/// [`InteractiveWaves`](crate::InteractiveWaves) for the energy ledger.
pub struct GpuWaves {
    device: wgpu::Device,
    queue: wgpu::Queue,
    region: WaveRegion,
    gravity: f64,
    sponge: usize,
    /// Three layers of n² complex values (elevation, potential, pressure);
    /// the FFT's scratch of the same size lives in the stage bind groups.
    spec: wgpu::Buffer,
    /// The pressure as the third layer wants it (complex, zero imaginary
    /// parts), copied in before each step's transform.
    pressure: wgpu::Buffer,
    heights: wgpu::Buffer,
    staging: wgpu::Buffer,
    modes: wgpu::Buffer,
    finish: wgpu::Buffer,
    fft: Kernel,
    rotate: Kernel,
    close: Kernel,
    /// Stage bind groups: spectrum → scratch, scratch → spectrum.
    forth: wgpu::BindGroup,
    back: wgpu::BindGroup,
    rotate_group: wgpu::BindGroup,
    finish_group: wgpu::BindGroup,
    time: f64,
}

impl std::fmt::Debug for GpuWaves {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuWaves")
            .field("region", &self.region)
            .field("gravity", &self.gravity)
            .field("sponge", &self.sponge)
            .field("time", &self.time)
            .finish_non_exhaustive()
    }
}

impl GpuWaves {
    /// Still water over `region` under `gravity` (m/s²), with a sponge
    /// `sponge` cells wide, on the caller's device (see
    /// [`InteractiveWaves::new`](crate::InteractiveWaves::new); the density
    /// plays no part in the step).
    ///
    /// # Errors
    /// [`GpuHydroError::Waves`] for what `InteractiveWaves::new` refuses and
    /// for cells per side that are not a power of two; device errors.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        region: WaveRegion,
        gravity: f64,
        sponge: usize,
    ) -> Result<Self, GpuHydroError> {
        check_waves(&region, gravity, 1.0, sponge).map_err(GpuHydroError::Waves)?;
        let n = region.cells;
        if !n.is_power_of_two() {
            return Err(GpuHydroError::Waves(WaterError::Parameter {
                name: "waves.cells (a power of two on the GPU)",
                value: n as f64,
            }));
        }
        let nn = (n * n) as u64;
        let spectrum_bytes = 3 * nn * 8;
        let log = n.trailing_zeros();
        let count = 4 * log as u64;
        scoped::<_, GpuHydroError>(device, "waves: buffers and kernels", 2 * spectrum_bytes, || {
            let storage = |label: &str, size: u64| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size,
                    usage: wgpu::BufferUsages::STORAGE
                        | wgpu::BufferUsages::COPY_DST
                        | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                })
            };
            let uniform = |label: &str, size: u64| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            let spec = storage("waves spectrum", spectrum_bytes);
            let scratch = storage("waves scratch", spectrum_bytes);
            let heights = storage("waves heights", nn * 4);
            let pressure = storage("waves pressure", nn * 8);
            let staging = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("waves staging"),
                size: 2 * nn * 8,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let stage_size = std::mem::size_of::<Stage>() as u64;
            let stages = uniform("waves stages", count * STAGE_STRIDE);
            let modes = uniform("waves modes", std::mem::size_of::<Modes>() as u64);
            let finish = uniform("waves finish", std::mem::size_of::<Finish>() as u64);
            // Forward rows, forward columns (three layers), inverse rows,
            // inverse columns (elevation and potential).
            let mut data = vec![0u8; (count * STAGE_STRIDE) as usize];
            let mut at = 0;
            for (sign, layers) in [(-1.0f32, 3u32), (1.0, 2)] {
                for (line_stride, pos_stride) in [(n as u32, 1u32), (1, n as u32)] {
                    for s in 0..log {
                        let stage = Stage {
                            n: n as u32,
                            p: 1 << s,
                            line_stride,
                            pos_stride,
                            sign,
                            layers,
                            pad: [0; 2],
                        };
                        let offset = at * STAGE_STRIDE as usize;
                        data[offset..offset + stage_size as usize]
                            .copy_from_slice(bytemuck::bytes_of(&stage));
                        at += 1;
                    }
                }
            }
            queue.write_buffer(&stages, 0, &data);
            let fft = Kernel::new(
                device,
                "waves fft stage",
                FFT,
                &[
                    Binding::Read,
                    Binding::ReadWrite,
                    Binding::DynamicUniform { size: stage_size },
                ],
            );
            let rotate = Kernel::new(
                device,
                "waves modes",
                MODES,
                &[
                    Binding::ReadWrite,
                    Binding::Uniform {
                        size: std::mem::size_of::<Modes>() as u64,
                    },
                ],
            );
            let close = Kernel::new(
                device,
                "waves finish",
                FINISH,
                &[
                    Binding::ReadWrite,
                    Binding::ReadWrite,
                    Binding::Uniform {
                        size: std::mem::size_of::<Finish>() as u64,
                    },
                ],
            );
            let forth = fft.bind(device, &[&spec, &scratch, &stages]);
            let back = fft.bind(device, &[&scratch, &spec, &stages]);
            let rotate_group = rotate.bind(device, &[&spec, &modes]);
            let finish_group = close.bind(device, &[&spec, &heights, &finish]);
            Ok(Self {
                device: device.clone(),
                queue: queue.clone(),
                region,
                gravity,
                sponge,
                spec,
                pressure,
                heights,
                staging,
                modes,
                finish,
                fft,
                rotate,
                close,
                forth,
                back,
                rotate_group,
                finish_group,
                time: 0.0,
            })
        })
    }

    /// The region.
    pub fn region(&self) -> &WaveRegion {
        &self.region
    }

    /// Time stepped so far, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Sets the elevation (m) and potential (m²/s) per cell (as
    /// [`InteractiveWaves::set_state`](crate::InteractiveWaves::set_state)).
    ///
    /// # Errors
    /// [`GpuHydroError::Waves`] for slices of another length or a value
    /// that is not finite.
    pub fn set_state(&mut self, h: &[f64], phi: &[f64]) -> Result<(), GpuHydroError> {
        let n = self.region.cells;
        for values in [h, phi] {
            check_field(values, n)?;
        }
        let layers: Vec<[f32; 2]> = h.iter().chain(phi).map(|&v| [v as f32, 0.0]).collect();
        self.queue
            .write_buffer(&self.spec, 0, bytemuck::cast_slice(&layers));
        Ok(())
    }

    /// Sets the pressure over density held over the next steps, per cell,
    /// m²/s² (`g` times the depth a hull holds the surface down by; as
    /// [`InteractiveWaves::pressure_mut`](crate::InteractiveWaves::pressure_mut)).
    ///
    /// # Errors
    /// [`GpuHydroError::Waves`] for a slice of another length or a value
    /// that is not finite.
    pub fn set_pressure(&mut self, pressure: &[f64]) -> Result<(), GpuHydroError> {
        let n = self.region.cells;
        check_field(pressure, n)?;
        let layer: Vec<[f32; 2]> = pressure.iter().map(|&v| [v as f32, 0.0]).collect();
        self.queue
            .write_buffer(&self.pressure, 0, bytemuck::cast_slice(&layer));
        Ok(())
    }

    /// Advances the surface by `dt` (s) with the pressure held over the
    /// step, then lets the sponge absorb what reached the border: one
    /// submission, nothing read back.
    ///
    /// # Errors
    /// [`GpuHydroError::Waves`] for a `dt` that is not finite and > 0;
    /// device errors.
    pub fn step(&mut self, dt: f64) -> Result<(), GpuHydroError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(GpuHydroError::Waves(WaterError::Parameter {
                name: "waves.dt",
                value: dt,
            }));
        }
        let n = self.region.cells;
        let log = n.trailing_zeros();
        let g = self.gravity;
        let d = self.region.cell();
        let modes = Modes {
            n: n as u32,
            pad0: 0,
            base: (2.0 * std::f64::consts::PI / self.region.size) as f32,
            g: g as f32,
            dt: dt as f32,
            pad: [0.0; 3],
        };
        let rate = if self.sponge > 0 {
            (g * std::f64::consts::PI / (self.sponge as f64 * d)).sqrt()
        } else {
            0.0
        };
        let finish = Finish {
            n: n as u32,
            sponge: self.sponge as u32,
            rate: rate as f32,
            dt: dt as f32,
        };
        let nn = (n * n) as u32;
        let groups = super::layout::thread_groups;
        scoped::<_, GpuHydroError>(&self.device, "waves: step", 0, || {
            self.queue
                .write_buffer(&self.modes, 0, bytemuck::bytes_of(&modes));
            self.queue
                .write_buffer(&self.finish, 0, bytemuck::bytes_of(&finish));
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("waves step"),
                });
            let layer = u64::from(nn) * 8;
            encoder.copy_buffer_to_buffer(&self.pressure, 0, &self.spec, 2 * layer, layer);
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("waves step"),
                    timestamp_writes: None,
                });
                let fft = |pass: &mut wgpu::ComputePass<'_>, first: u32, layers: u32| {
                    pass.set_pipeline(self.fft.pipeline());
                    let g = groups(layers * nn / 2);
                    for s in 0..2 * log {
                        let group = if s % 2 == 0 { &self.forth } else { &self.back };
                        pass.set_bind_group(0, group, &[(first + s) * STAGE_STRIDE as u32]);
                        pass.dispatch_workgroups(g[0], g[1], 1);
                    }
                };
                fft(&mut pass, 0, 3);
                pass.set_pipeline(self.rotate.pipeline());
                pass.set_bind_group(0, &self.rotate_group, &[]);
                let g = groups(nn);
                pass.dispatch_workgroups(g[0], g[1], 1);
                fft(&mut pass, 2 * log, 2);
                pass.set_pipeline(self.close.pipeline());
                pass.set_bind_group(0, &self.finish_group, &[]);
                pass.dispatch_workgroups(g[0], g[1], 1);
            }
            self.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        self.time += dt;
        Ok(())
    }

    /// The elevation per cell, m, read back (waits for the queue).
    ///
    /// # Errors
    /// Device errors.
    pub fn heights(&self) -> Result<Vec<f64>, GpuHydroError> {
        let bytes = (self.region.cells * self.region.cells) as u64 * 4;
        self.read(&self.heights, 0, bytes)
            .map(|f| f.into_iter().map(f64::from).collect())
    }

    /// The elevation (m) and potential (m²/s) per cell, read back.
    ///
    /// # Errors
    /// Device errors.
    pub fn state(&self) -> Result<(Vec<f64>, Vec<f64>), GpuHydroError> {
        let nn = self.region.cells * self.region.cells;
        let f = self.read(&self.spec, 0, 2 * nn as u64 * 8)?;
        let real = |layer: usize| (0..nn).map(|i| f64::from(f[2 * (layer * nn + i)])).collect();
        Ok((real(0), real(1)))
    }

    fn read(&self, buffer: &wgpu::Buffer, offset: u64, bytes: u64) -> Result<Vec<f32>, GpuHydroError> {
        scoped::<_, GpuHydroError>(&self.device, "waves: read back", bytes, || {
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
            encoder.copy_buffer_to_buffer(buffer, offset, &self.staging, 0, bytes);
            self.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let data = read_back(&self.device, &self.staging, bytes, "waves: read back")?;
        Ok(data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect())
    }
}

/// A per-cell field of `n`×`n` finite values.
fn check_field(values: &[f64], n: usize) -> Result<(), GpuHydroError> {
    if values.len() != n * n {
        return Err(GpuHydroError::Waves(WaterError::HeightFieldShape {
            nx: n,
            nz: n,
            len: values.len(),
        }));
    }
    if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(GpuHydroError::Waves(WaterError::HeightFieldSample {
            index,
            value,
        }));
    }
    Ok(())
}
