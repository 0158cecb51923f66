//! wgpu error scopes around allocation and submission, mapped to
//! [`GpuError`] (the same mapping as soak-hydro's GPU path).

use soak_hydro::gpu::GpuError;

/// Runs `f` inside out-of-memory and validation error scopes: errors wgpu
/// reports become typed values instead of the default panic.
pub(crate) fn scoped<T>(
    device: &wgpu::Device,
    what: &'static str,
    bytes: u64,
    f: impl FnOnce() -> Result<T, GpuError>,
) -> Result<T, GpuError> {
    let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = f();
    let invalid = pollster::block_on(validation.pop());
    let out_of_memory = pollster::block_on(oom.pop());
    if out_of_memory.is_some() {
        return Err(GpuError::OutOfMemory { what, bytes });
    }
    if let Some(e) = invalid {
        let message = e.to_string();
        return Err(if message.to_ascii_lowercase().contains("lost") {
            GpuError::DeviceLost {
                what,
                reason: message,
            }
        } else {
            GpuError::Validation { what, message }
        });
    }
    result
}

/// Waits for the queue and reads `bytes` bytes from a `MAP_READ` buffer.
pub(crate) fn read_back(
    device: &wgpu::Device,
    staging: &wgpu::Buffer,
    bytes: u64,
    what: &'static str,
) -> Result<Vec<u8>, GpuError> {
    if bytes == 0 {
        return Ok(Vec::new());
    }
    let slice = staging.slice(..bytes);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    let lost = |reason: String| GpuError::DeviceLost { what, reason };
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
