//! Getting a headless device, naming adapters, and turning wgpu's error
//! reports into [`RenderError`] values.

use super::error::RenderError;

pub use soak_hydro::gpu::{adapter_label, is_software};

/// A device and queue on the first adapter wgpu offers, without a window:
/// [`soak_hydro::gpu::headless_device`], with its error as a
/// [`RenderError`].
///
/// `WGPU_BACKEND=vulkan|gl` picks a backend (Mesa's lavapipe or llvmpipe
/// work headless). A convenience for tests, tools and examples: the
/// renderer takes a device, so engines pass their own.
pub fn headless_device() -> Result<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo), RenderError> {
    Ok(soak_hydro::gpu::headless_device()?)
}

/// Runs `f` inside out-of-memory and validation error scopes: errors wgpu
/// reports become typed values instead of the default panic.
pub(crate) fn scoped<T>(
    device: &wgpu::Device,
    what: &'static str,
    bytes: u64,
    f: impl FnOnce() -> Result<T, RenderError>,
) -> Result<T, RenderError> {
    let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = f();
    let invalid = pollster::block_on(validation.pop());
    let out_of_memory = pollster::block_on(oom.pop());
    if out_of_memory.is_some() {
        return Err(RenderError::OutOfMemory { what, bytes });
    }
    if let Some(e) = invalid {
        let message = e.to_string();
        return Err(if message.to_ascii_lowercase().contains("lost") {
            RenderError::DeviceLost {
                what,
                reason: message,
            }
        } else {
            RenderError::Validation { what, message }
        });
    }
    result
}

/// Waits for the queue and reads the first `bytes` bytes of a `MAP_READ`
/// buffer.
pub(crate) fn read_back(
    device: &wgpu::Device,
    staging: &wgpu::Buffer,
    bytes: u64,
    what: &'static str,
) -> Result<Vec<u8>, RenderError> {
    if bytes == 0 {
        return Ok(Vec::new());
    }
    let slice = staging.slice(..bytes);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    let lost = |reason: String| RenderError::DeviceLost { what, reason };
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| lost(e.to_string()))?;
    rx.recv()
        .map_err(|e| lost(e.to_string()))?
        .map_err(|e| lost(e.to_string()))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| lost(e.to_string()))?
        .to_vec();
    staging.unmap();
    Ok(data)
}
