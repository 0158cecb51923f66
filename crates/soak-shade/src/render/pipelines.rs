//! Bind group layouts and render pipelines, compiled once per
//! [`Renderer`](super::Renderer). WGSL is composed from the optics library
//! and the shaders beside this file.

use std::borrow::Cow;

use crate::optics_table::WET_OPTICS_WGSL;

const FRAME: &str = include_str!("../../shaders/frame.wgsl");
const SURFACE: &str = include_str!("../../shaders/surface.wgsl");
const SHADOW: &str = include_str!("../../shaders/shadow.wgsl");
const WATER: &str = include_str!("../../shaders/water.wgsl");
const SKY: &str = include_str!("../../shaders/sky.wgsl");
const ARROW: &str = include_str!("../../shaders/arrow.wgsl");
const SUBSURFACE: &str = include_str!("../../shaders/subsurface.wgsl");
const TONEMAP: &str = include_str!("../../shaders/tonemap.wgsl");

/// Linear radiance while drawing.
pub(crate) const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Depth while drawing and in the shadow map.
pub(crate) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The image read back: sRGB-encoded by the tone-mapping shader.
pub(crate) const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// The subsurface irradiance and blur targets.
pub(crate) const SUBSURFACE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Liquid textures.
pub(crate) const LIQUID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;
/// Albedo textures (sRGB-encoded RGBA8).
pub(crate) const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// Every WGSL module the renderer compiles, by name, fully composed: for
/// validation in tests and for reading.
pub fn shader_sources() -> Vec<(&'static str, String)> {
    vec![
        ("surface", [WET_OPTICS_WGSL, FRAME, SURFACE].join("\n")),
        ("shadow", SHADOW.to_string()),
        ("water", [WET_OPTICS_WGSL, FRAME, WATER].join("\n")),
        ("sky", [WET_OPTICS_WGSL, FRAME, SKY].join("\n")),
        ("arrow", [WET_OPTICS_WGSL, FRAME, ARROW].join("\n")),
        ("subsurface", SUBSURFACE.to_string()),
        ("tonemap", TONEMAP.to_string()),
    ]
}

pub(crate) struct Pipelines {
    pub frame_layout: wgpu::BindGroupLayout,
    pub matrices_layout: wgpu::BindGroupLayout,
    pub object_layout: wgpu::BindGroupLayout,
    pub water_layout: wgpu::BindGroupLayout,
    pub blur_layout: wgpu::BindGroupLayout,
    pub post_layout: wgpu::BindGroupLayout,
    pub sky: wgpu::RenderPipeline,
    pub surface: wgpu::RenderPipeline,
    pub cap_mask: wgpu::RenderPipeline,
    pub irradiance: wgpu::RenderPipeline,
    pub shadow: wgpu::RenderPipeline,
    pub water: wgpu::RenderPipeline,
    pub arrow: wgpu::RenderPipeline,
    pub blur_sum: wgpu::RenderPipeline,
    pub blur_accumulate: wgpu::RenderPipeline,
    pub post: wgpu::RenderPipeline,
}

fn uniform(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture(binding: u32, sample_type: wgpu::TextureSampleType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

fn sampler(binding: u32, ty: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(ty),
        count: None,
    }
}

const MESH_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Uint32];
const SHADOW_ATTRIBUTES: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x3];
const WATER_ATTRIBUTES: [wgpu::VertexAttribute; 2] = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
const ARROW_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3];

struct Stage<'a> {
    module: &'a wgpu::ShaderModule,
    vertex: &'a str,
    fragment: Option<&'a str>,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    layouts: &'a [&'a wgpu::BindGroupLayout],
    target: Option<wgpu::ColorTargetState>,
    depth: Option<wgpu::DepthStencilState>,
    cull: Option<wgpu::Face>,
    samples: u32,
}

fn pipeline(device: &wgpu::Device, label: &str, s: Stage) -> wgpu::RenderPipeline {
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> = s.layouts.iter().map(|l| Some(*l)).collect();
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    let has_target = s.target.is_some();
    let targets = [s.target];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: s.module,
            entry_point: Some(s.vertex),
            compilation_options: Default::default(),
            buffers: s.buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            strip_index_format: None,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: s.cull,
            unclipped_depth: false,
            polygon_mode: wgpu::PolygonMode::Fill,
            conservative: false,
        },
        depth_stencil: s.depth,
        multisample: wgpu::MultisampleState {
            count: s.samples,
            mask: !0,
            alpha_to_coverage_enabled: false,
        },
        fragment: s.fragment.map(|entry| wgpu::FragmentState {
            module: s.module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets: if has_target { &targets } else { &[] },
        }),
        multiview_mask: None,
        cache: None,
    })
}

fn depth(write: bool, compare: wgpu::CompareFunction, bias: wgpu::DepthBiasState) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias,
    }
}

fn target(format: wgpu::TextureFormat, blend: Option<wgpu::BlendState>) -> Option<wgpu::ColorTargetState> {
    Some(wgpu::ColorTargetState {
        format,
        blend,
        write_mask: wgpu::ColorWrites::ALL,
    })
}

impl Pipelines {
    pub(crate) fn new(device: &wgpu::Device, samples: u32) -> Self {
        use wgpu::ShaderStages as S;
        let float = wgpu::TextureSampleType::Float { filterable: true };
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[
                uniform(0, S::VERTEX_FRAGMENT),
                texture(1, wgpu::TextureSampleType::Depth),
                sampler(2, wgpu::SamplerBindingType::Comparison),
            ],
        });
        let matrices_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame matrices"),
            entries: &[uniform(0, S::VERTEX_FRAGMENT)],
        });
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("object"),
            entries: &[
                uniform(0, S::VERTEX_FRAGMENT),
                texture(1, float),
                texture(2, float),
                texture(3, float),
                sampler(4, wgpu::SamplerBindingType::Filtering),
            ],
        });
        let water_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("water"),
            entries: &[uniform(0, S::VERTEX_FRAGMENT)],
        });
        let unfiltered = wgpu::TextureSampleType::Float { filterable: false };
        let blur_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("subsurface blur"),
            entries: &[
                texture(0, unfiltered),
                texture(1, unfiltered),
                uniform(2, S::FRAGMENT),
            ],
        });
        let post_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tone map"),
            entries: &[texture(0, unfiltered), uniform(1, S::FRAGMENT)],
        });

        let sources = shader_sources();
        let module = |name: &str| {
            let (label, source) = sources.iter().find(|(n, _)| *n == name).expect("known shader");
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(source)),
            })
        };
        let surface_module = module("surface");
        let shadow_module = module("shadow");
        let water_module = module("water");
        let sky_module = module("sky");
        let arrow_module = module("arrow");
        let blur_module = module("subsurface");
        let post_module = module("tonemap");

        let no_bias = wgpu::DepthBiasState::default();
        let mesh_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: 36,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &MESH_ATTRIBUTES,
        })];
        let shadow_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: 36,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &SHADOW_ATTRIBUTES,
        })];
        let water_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: 24,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &WATER_ATTRIBUTES,
        })];
        let arrow_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: 36,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &ARROW_ATTRIBUTES,
        })];
        let premultiplied = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
        };
        let additive = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        };

        let sky = pipeline(
            device,
            "sky",
            Stage {
                module: &sky_module,
                vertex: "vs_sky",
                fragment: Some("fs_sky"),
                buffers: &[],
                layouts: &[&frame_layout],
                target: target(HDR_FORMAT, None),
                depth: Some(depth(false, wgpu::CompareFunction::Always, no_bias)),
                cull: None,
                samples,
            },
        );
        let surface = pipeline(
            device,
            "surface",
            Stage {
                module: &surface_module,
                vertex: "vs_main",
                fragment: Some("fs_main"),
                buffers: &mesh_buffers,
                layouts: &[&frame_layout, &object_layout],
                target: target(HDR_FORMAT, None),
                depth: Some(depth(true, wgpu::CompareFunction::Less, no_bias)),
                cull: Some(wgpu::Face::Back),
                samples,
            },
        );
        // An open container's caps: depth only, both sides.
        let cap_mask = pipeline(
            device,
            "cap mask",
            Stage {
                module: &surface_module,
                vertex: "vs_main",
                fragment: Some("fs_mask"),
                buffers: &mesh_buffers,
                layouts: &[&frame_layout, &object_layout],
                target: Some(wgpu::ColorTargetState {
                    format: HDR_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::empty(),
                }),
                depth: Some(depth(true, wgpu::CompareFunction::Less, no_bias)),
                cull: None,
                samples,
            },
        );
        let irradiance = pipeline(
            device,
            "subsurface irradiance",
            Stage {
                module: &surface_module,
                vertex: "vs_texture_space",
                fragment: Some("fs_irradiance"),
                buffers: &mesh_buffers,
                layouts: &[&frame_layout, &object_layout],
                target: target(SUBSURFACE_FORMAT, None),
                depth: None,
                cull: None,
                samples: 1,
            },
        );
        let shadow = pipeline(
            device,
            "shadow",
            Stage {
                module: &shadow_module,
                vertex: "vs_shadow",
                fragment: None,
                buffers: &shadow_buffers,
                layouts: &[&matrices_layout, &object_layout],
                target: None,
                depth: Some(depth(
                    true,
                    wgpu::CompareFunction::Less,
                    wgpu::DepthBiasState {
                        constant: 2,
                        slope_scale: 1.5,
                        clamp: 0.0,
                    },
                )),
                cull: None,
                samples: 1,
            },
        );
        let water = pipeline(
            device,
            "water",
            Stage {
                module: &water_module,
                vertex: "vs_water",
                fragment: Some("fs_water"),
                buffers: &water_buffers,
                layouts: &[&frame_layout, &water_layout],
                target: target(HDR_FORMAT, Some(premultiplied)),
                depth: Some(depth(false, wgpu::CompareFunction::Less, no_bias)),
                cull: None,
                samples,
            },
        );
        let arrow = pipeline(
            device,
            "arrows",
            Stage {
                module: &arrow_module,
                vertex: "vs_arrow",
                fragment: Some("fs_arrow"),
                buffers: &arrow_buffers,
                layouts: &[&frame_layout],
                target: target(HDR_FORMAT, None),
                depth: Some(depth(true, wgpu::CompareFunction::Less, no_bias)),
                cull: Some(wgpu::Face::Back),
                samples,
            },
        );
        let blur = |label, blend| {
            pipeline(
                device,
                label,
                Stage {
                    module: &blur_module,
                    vertex: "vs_blur",
                    fragment: Some("fs_blur"),
                    buffers: &[],
                    layouts: &[&blur_layout],
                    target: target(SUBSURFACE_FORMAT, blend),
                    depth: None,
                    cull: None,
                    samples: 1,
                },
            )
        };
        let blur_sum = blur("subsurface blur u", None);
        let blur_accumulate = blur("subsurface blur v", Some(additive));
        let post = pipeline(
            device,
            "tone map",
            Stage {
                module: &post_module,
                vertex: "vs_post",
                fragment: Some("fs_post"),
                buffers: &[],
                layouts: &[&post_layout],
                target: target(OUTPUT_FORMAT, None),
                depth: None,
                cull: None,
                samples: 1,
            },
        );
        Self {
            frame_layout,
            matrices_layout,
            object_layout,
            water_layout,
            blur_layout,
            post_layout,
            sky,
            surface,
            cap_mask,
            irradiance,
            shadow,
            water,
            arrow,
            blur_sum,
            blur_accumulate,
            post,
        }
    }
}
