//! The render passes of a frame, in the order they run: the sun's shadow
//! map, the texture-space subsurface term, the scene (sky, surfaces,
//! water), the force arrows over everything with the MSAA resolve, and the
//! tone map into the output. Each takes what the frame uploaded and records
//! into the frame's command encoder.

use super::pipelines::Pipelines;
use super::targets::{ShadowMap, Targets};
use super::upload::GpuObject;

/// The water grid of a frame, ready to draw.
pub(super) struct WaterDraw {
    pub(super) vertices: wgpu::Buffer,
    pub(super) indices: wgpu::Buffer,
    /// Indices in view (0 when none of the water is), the liquid inside
    /// open containers (`inner` of them) first, then the sea.
    pub(super) count: u32,
    /// Indices of the liquid inside open containers, at the start.
    pub(super) inner: u32,
    pub(super) bind: wgpu::BindGroup,
}

/// The force arrows of a frame, ready to draw.
pub(super) struct ArrowDraw {
    pub(super) vertices: wgpu::Buffer,
    pub(super) count: u32,
}

/// Pass 1, the shadow map: the casters' depth seen from the sun.
pub(super) fn shadow_pass(
    encoder: &mut wgpu::CommandEncoder,
    p: &Pipelines,
    shadow_map: &ShadowMap,
    matrices_bind: &wgpu::BindGroup,
    objects: &[GpuObject],
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("shadow"),
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &shadow_map.view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(&p.shadow);
    pass.set_bind_group(0, matrices_bind, &[]);
    for o in objects.iter().filter(|o| o.casts_shadow && o.count > 0) {
        pass.set_bind_group(1, &o.bind, &[]);
        pass.set_vertex_buffer(0, o.vertices.slice(..));
        pass.draw(0..o.count, 0..1);
    }
}

/// Passes 2, subsurface: per object with the term, the irradiance in
/// texture space, then per Gaussian a blur along u and one along v that
/// adds into the result.
pub(super) fn subsurface_passes(
    encoder: &mut wgpu::CommandEncoder,
    p: &Pipelines,
    frame_bind: &wgpu::BindGroup,
    objects: &[GpuObject],
) {
    for o in objects {
        let Some(sss) = &o.subsurface else { continue };
        {
            let mut pass = color_pass(encoder, "subsurface irradiance", &sss.irradiance, true);
            pass.set_pipeline(&p.irradiance);
            pass.set_bind_group(0, frame_bind, &[]);
            pass.set_bind_group(1, &o.bind, &[]);
            pass.set_vertex_buffer(0, o.vertices.slice(..));
            pass.draw(0..o.front, 0..1);
        }
        for (k, (u, v)) in sss.blurs.iter().enumerate() {
            {
                let mut pass = color_pass(encoder, "subsurface blur u", &sss.scratch, true);
                pass.set_pipeline(&p.blur_sum);
                pass.set_bind_group(0, u, &[]);
                pass.draw(0..3, 0..1);
            }
            let mut pass = color_pass(encoder, "subsurface blur v", &sss.result, k == 0);
            pass.set_pipeline(&p.blur_accumulate);
            pass.set_bind_group(0, v, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}

/// The colour attachment the scene is drawn into (the MSAA target when
/// there is one) and the view it resolves into.
fn scene_colour(t: &Targets) -> (&wgpu::TextureView, Option<&wgpu::TextureView>) {
    match &t.msaa {
        Some(msaa) => (msaa, Some(&t.hdr)),
        None => (&t.hdr, None),
    }
}

/// Pass 3, the scene: sky, objects, water.
pub(super) fn scene_pass(
    encoder: &mut wgpu::CommandEncoder,
    p: &Pipelines,
    t: &Targets,
    frame_bind: &wgpu::BindGroup,
    objects: &[GpuObject],
    water: Option<&WaterDraw>,
) {
    let (colour, _) = scene_colour(t);
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("scene"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: colour,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &t.depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_bind_group(0, frame_bind, &[]);
    pass.set_pipeline(&p.sky);
    pass.draw(0..3, 0..1);
    pass.set_pipeline(&p.surface);
    for o in objects.iter().filter(|o| o.count > 0) {
        pass.set_bind_group(1, &o.bind, &[]);
        pass.set_vertex_buffer(0, o.vertices.slice(..));
        pass.draw(0..o.count, 0..1);
    }
    // The liquid inside open containers, then their caps into the depth
    // buffer alone (the sea does not show inside them), then the sea.
    // Nothing of the water may be in view (a camera under it, looking down).
    let water = water.filter(|w| w.count > 0);
    if let Some(w) = water.filter(|w| w.inner > 0) {
        pass.set_pipeline(&p.water);
        pass.set_bind_group(1, &w.bind, &[]);
        pass.set_vertex_buffer(0, w.vertices.slice(..));
        pass.set_index_buffer(w.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..w.inner, 0, 0..1);
    }
    if objects.iter().any(|o| o.caps > 0) {
        pass.set_pipeline(&p.cap_mask);
        for o in objects.iter().filter(|o| o.caps > 0) {
            pass.set_bind_group(1, &o.bind, &[]);
            pass.set_vertex_buffer(0, o.vertices.slice(..));
            pass.draw(o.count..o.count + o.caps, 0..1);
        }
    }
    if let Some(w) = water.filter(|w| w.count > w.inner) {
        pass.set_pipeline(&p.water);
        pass.set_bind_group(1, &w.bind, &[]);
        pass.set_vertex_buffer(0, w.vertices.slice(..));
        pass.set_index_buffer(w.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(w.inner..w.count, 0, 0..1);
    }
}

/// Pass 4, arrows over everything (depth cleared), and the MSAA resolve:
/// the pass runs with or without arrows.
pub(super) fn arrow_pass(
    encoder: &mut wgpu::CommandEncoder,
    p: &Pipelines,
    t: &Targets,
    frame_bind: &wgpu::BindGroup,
    arrows: Option<&ArrowDraw>,
) {
    let (colour, resolve) = scene_colour(t);
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("arrows"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: colour,
            depth_slice: None,
            resolve_target: resolve,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &t.depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    if let Some(a) = arrows {
        pass.set_pipeline(&p.arrow);
        pass.set_bind_group(0, frame_bind, &[]);
        pass.set_vertex_buffer(0, a.vertices.slice(..));
        pass.draw(0..a.count, 0..1);
    }
}

/// Pass 5, tone map: the resolved radiance into the output.
pub(super) fn tone_map_pass(
    encoder: &mut wgpu::CommandEncoder,
    p: &Pipelines,
    t: &Targets,
    post_bind: &wgpu::BindGroup,
) {
    let view = t.output.create_view(&Default::default());
    let mut pass = color_pass(encoder, "tone map", &view, true);
    pass.set_pipeline(&p.post);
    pass.set_bind_group(0, post_bind, &[]);
    pass.draw(0..3, 0..1);
}

/// A pass with one colour attachment, cleared to transparent or loaded,
/// and no depth.
fn color_pass<'a>(
    encoder: &'a mut wgpu::CommandEncoder,
    label: &'static str,
    view: &'a wgpu::TextureView,
    clear: bool,
) -> wgpu::RenderPass<'a> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: if clear {
                    wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                } else {
                    wgpu::LoadOp::Load
                },
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
