//! Reading the image back: the output texture copied into the read-back
//! buffer (rows padded to `COPY_BYTES_PER_ROW_ALIGNMENT`), mapped, and
//! unpadded into an [`image::RgbaImage`].

use soak_gpu::{GpuError, read_back};

use super::error::RenderError;
use super::targets::Targets;

/// Step 6 of a frame, after the passes: copies the output into the
/// read-back buffer, rows padded to `COPY_BYTES_PER_ROW_ALIGNMENT`.
pub(super) fn copy_out(encoder: &mut wgpu::CommandEncoder, t: &Targets) {
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: &t.output,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &t.readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(t.padded_row),
                rows_per_image: Some(t.height),
            },
        },
        wgpu::Extent3d {
            width: t.width,
            height: t.height,
            depth_or_array_layers: 1,
        },
    );
}

/// Waits for the submitted frame and reads the padded rows back.
pub(super) fn read_padded(device: &wgpu::Device, t: &Targets) -> Result<Vec<u8>, RenderError> {
    Ok(read_back(
        device,
        &t.readback,
        u64::from(t.padded_row) * u64::from(t.height),
        "reading the image back",
    )?)
}

/// The image in padded rows `data` of `t`, without the padding.
pub(super) fn unpad(t: &Targets, data: &[u8]) -> Result<image::RgbaImage, RenderError> {
    let (w, h) = (t.width, t.height);
    let row = t.padded_row as usize;
    let mut pixels = Vec::with_capacity((4 * w * h) as usize);
    for y in 0..h as usize {
        pixels.extend_from_slice(&data[y * row..y * row + 4 * w as usize]);
    }
    image::RgbaImage::from_raw(w, h, pixels).ok_or(
        GpuError::Validation {
            what: "reading the image back",
            message: "the readback has the wrong size".into(),
        }
        .into(),
    )
}
