//! Compute kernels: a pipeline and its bind group layout from WGSL and a list
//! of bindings, and bind groups of buffers in binding order.

use std::borrow::Cow;

/// How a compute kernel sees one binding; binding `i` of group 0 is the
/// `i`-th of the list given to [`Kernel::new`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Binding {
    /// A storage buffer the kernel only reads (`var<storage, read>`).
    Read,
    /// A storage buffer the kernel reads and writes (`var<storage, read_write>`).
    ReadWrite,
    /// A uniform buffer bound whole (`var<uniform>`) of at least `size` bytes.
    Uniform {
        /// The uniform struct's size, bytes.
        size: u64,
    },
    /// A uniform struct of `size` bytes read at a dynamic offset into a
    /// larger buffer, one offset per dispatch.
    DynamicUniform {
        /// The uniform struct's size, bytes.
        size: u64,
    },
}

/// A compute pipeline with entry point `main`, and the layout of its bind
/// group 0.
#[derive(Debug)]
pub struct Kernel {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    bindings: Vec<Binding>,
}

impl Kernel {
    /// Compiles `source` (WGSL with an entry point `main` and bind group 0
    /// declared as `bindings`) into a pipeline labelled `label`.
    ///
    /// wgpu reports a shader or layout that does not compile through its
    /// error scopes: call this inside [`crate::scoped`] to get it as a
    /// [`crate::GpuError::Validation`].
    pub fn new(device: &wgpu::Device, label: &str, source: &str, bindings: &[Binding]) -> Self {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupLayoutEntry {
                binding: i as u32,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: match *b {
                    Binding::Read | Binding::ReadWrite => wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage {
                            read_only: *b == Binding::Read,
                        },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    Binding::Uniform { size } | Binding::DynamicUniform { size } => {
                        wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Uniform,
                            has_dynamic_offset: matches!(b, Binding::DynamicUniform { .. }),
                            min_binding_size: wgpu::BufferSize::new(size),
                        }
                    }
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
        Self {
            layout,
            pipeline,
            bindings: bindings.to_vec(),
        }
    }

    /// The pipeline, for `ComputePass::set_pipeline`.
    pub fn pipeline(&self) -> &wgpu::ComputePipeline {
        &self.pipeline
    }

    /// The layout of bind group 0.
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// A bind group of `buffers` in binding order: storage buffers and
    /// whole uniforms bound entire, a dynamic uniform bound as one struct
    /// from offset 0 (the offset is given to `set_bind_group`).
    ///
    /// A count that differs from the kernel's bindings is reported by wgpu
    /// as a validation error (see [`crate::scoped`]).
    pub fn bind(&self, device: &wgpu::Device, buffers: &[&wgpu::Buffer]) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(i, buffer)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: match self.bindings.get(i) {
                    Some(Binding::DynamicUniform { size }) => {
                        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer,
                            offset: 0,
                            size: wgpu::BufferSize::new(*size),
                        })
                    }
                    _ => buffer.as_entire_binding(),
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
