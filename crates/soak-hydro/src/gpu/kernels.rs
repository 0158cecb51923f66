//! The compute pipelines: WGSL composed from the shared `shaders/` and the
//! kernels beside this file.

use std::borrow::Cow;

use super::error::GpuError;
use super::scope::scoped;

/// Buffer layouts shared by every kernel (top-level `shaders/`).
const BINDINGS: &str = include_str!("../../../../shaders/hydro_bindings.wgsl");
/// Water surfaces (top-level `shaders/`).
const WATER: &str = include_str!("../../../../shaders/water_surface.wgsl");
const BUOYANCY: &str = include_str!("buoyancy.wgsl");
const REDUCE: &str = include_str!("reduce.wgsl");
const MASS: &str = include_str!("mass.wgsl");
const DEFORM: &str = include_str!("deform.wgsl");

/// The WGSL of each kernel, as compiled (for tools that validate shaders).
pub fn kernel_sources() -> Vec<(&'static str, String)> {
    vec![
        ("buoyancy", [BINDINGS, WATER, BUOYANCY].concat()),
        ("reduce_hydro", reduce_source(super::layout::HYDRO_SLOTS, 3)),
        ("mass", [BINDINGS, MASS].concat()),
        (
            "reduce_mass",
            reduce_source(super::layout::MASS_SLOTS, super::layout::MASS_SLOTS),
        ),
        ("deform", [BINDINGS, DEFORM].concat()),
    ]
}

fn reduce_source(slots: u32, count_slot: u32) -> String {
    format!("{BINDINGS}\nconst SLOTS: u32 = {slots}u;\nconst COUNT_SLOT: u32 = {count_slot}u;\n{REDUCE}")
}

/// How a kernel sees one binding.
#[derive(Clone, Copy)]
enum Slot {
    Read,
    ReadWrite,
    Dispatch,
}

pub(crate) struct Kernel {
    pub layout: wgpu::BindGroupLayout,
    pub pipeline: wgpu::ComputePipeline,
}

pub(crate) struct Kernels {
    pub buoyancy: Kernel,
    pub reduce_hydro: Kernel,
    pub mass: Kernel,
    pub reduce_mass: Kernel,
    pub deform: Kernel,
}

impl Kernels {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, GpuError> {
        use Slot::*;
        let sources = kernel_sources();
        scoped(device, "compiling the hydrostatics kernels", 0, || {
            let make = |i: usize, slots: &[Slot]| kernel(device, sources[i].0, &sources[i].1, slots);
            Ok(Self {
                buoyancy: make(0, &[Read, Read, Read, Read, Read, Read, ReadWrite, Dispatch]),
                reduce_hydro: make(1, &[Read, Read, ReadWrite, Dispatch]),
                mass: make(2, &[Read, Read, Read, ReadWrite, Dispatch]),
                reduce_mass: make(3, &[Read, Read, ReadWrite, Dispatch]),
                deform: make(4, &[ReadWrite, Read, Read, Read, ReadWrite, Read, Dispatch]),
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
                Slot::Dispatch => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(size_of::<super::layout::Dispatch>() as u64),
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
    /// A bind group of whole buffers in binding order; the last binding is
    /// the dispatch uniform (one [`super::layout::Dispatch`] at a dynamic offset).
    pub(crate) fn bind(&self, device: &wgpu::Device, buffers: &[&wgpu::Buffer]) -> wgpu::BindGroup {
        let last = buffers.len() - 1;
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: if i == last {
                    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: b,
                        offset: 0,
                        size: wgpu::BufferSize::new(size_of::<super::layout::Dispatch>() as u64),
                    })
                } else {
                    b.as_entire_binding()
                },
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.layout,
            entries: &entries,
        })
    }
}
