//! The compute pipelines: WGSL composed from soak-hydro's shared
//! `shaders/` (bindings and water surfaces) and the kernels beside this file.

use std::borrow::Cow;

use soak_hydro::gpu::GpuError;

use super::scope::scoped;

/// soak-hydro's buffer layouts (Body, Wave) and water surfaces (top-level `shaders/`).
const HYDRO_BINDINGS: &str = include_str!("../../../../shaders/hydro_bindings.wgsl");
const WATER: &str = include_str!("../../../../shaders/water_surface.wgsl");
const BINDINGS: &str = include_str!("bindings.wgsl");
const EXCHANGE: &str = include_str!("exchange.wgsl");
const GATHER: &str = include_str!("gather.wgsl");
const SUBSTEP: &str = include_str!("substep.wgsl");
const SCATTER: &str = include_str!("scatter.wgsl");
const SMOOTH: &str = include_str!("smooth.wgsl");
const FINISH: &str = include_str!("finish.wgsl");
const ACTIVITY: &str = include_str!("activity.wgsl");
const DELTA: &str = include_str!("delta.wgsl");
const RESIDUAL: &str = include_str!("residual.wgsl");

/// The WGSL of each kernel, as compiled (for tools that validate shaders).
pub fn kernel_sources() -> Vec<(&'static str, String)> {
    vec![
        (
            "wet_exchange",
            [HYDRO_BINDINGS, WATER, BINDINGS, EXCHANGE].concat(),
        ),
        ("wet_gather", [BINDINGS, GATHER].concat()),
        ("wet_substep", [BINDINGS, SUBSTEP].concat()),
        ("wet_finish", [BINDINGS, FINISH].concat()),
        ("wet_activity", [BINDINGS, ACTIVITY].concat()),
        ("wet_delta", [BINDINGS, SMOOTH, DELTA].concat()),
        ("wet_residual", [BINDINGS, RESIDUAL].concat()),
        ("wet_scatter", [BINDINGS, SCATTER].concat()),
    ]
}

/// How a kernel sees one binding.
#[derive(Clone, Copy)]
enum Slot {
    Read,
    ReadWrite,
    Uniform,
}

pub(crate) struct Kernel {
    pub layout: wgpu::BindGroupLayout,
    pub pipeline: wgpu::ComputePipeline,
}

pub(crate) struct Kernels {
    pub exchange: Kernel,
    pub gather: Kernel,
    pub substep: Kernel,
    pub finish: Kernel,
    pub activity: Kernel,
    pub delta: Kernel,
    pub residual: Kernel,
    pub scatter: Kernel,
}

impl Kernels {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, GpuError> {
        use Slot::*;
        let sources = kernel_sources();
        scoped(device, "compiling the wetting kernels", 0, || {
            let make = |i: usize, slots: &[Slot]| kernel(device, sources[i].0, &sources[i].1, slots);
            Ok(Self {
                exchange: make(0, &[Read, ReadWrite, Read, Read, Read, Read, Read, Uniform]),
                gather: make(1, &[Read, Read, Read, Read, Read, ReadWrite, ReadWrite, Uniform]),
                substep: make(2, &[Read, ReadWrite, Read, Read, Read, Uniform]),
                finish: make(3, &[Read, Read, Read, ReadWrite, Uniform]),
                activity: make(4, &[Read, Read, Read, ReadWrite, Uniform]),
                delta: make(5, &[Read, Read, Read, Read, Read, Read, ReadWrite, Uniform]),
                residual: make(6, &[Read, Read, Read, Read, Read, ReadWrite, Uniform]),
                scatter: make(7, &[Read, ReadWrite, Read, Read, Read, Read, Read, Uniform]),
            })
        })
    }
}

fn kernel(device: &wgpu::Device, label: &str, source: &str, slots: &[Slot]) -> Kernel {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = slots
        .iter()
        .enumerate()
        .map(|(i, s)| wgpu::BindGroupLayoutEntry {
            binding: i as u32,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: match s {
                Slot::Read | Slot::ReadWrite => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage {
                        read_only: matches!(s, Slot::Read),
                    },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                Slot::Uniform => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(size_of::<super::layout::Params>() as u64),
                },
            },
            count: None,
        })
        .collect();
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &entries,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(source)),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    Kernel { layout, pipeline }
}

impl Kernel {
    /// A bind group of whole buffers in binding order.
    pub(crate) fn bind(&self, device: &wgpu::Device, buffers: &[&wgpu::Buffer]) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.layout,
            entries: &entries,
        })
    }
}
