//! wgpu error scopes around allocation and submission, and reading buffers
//! back, with what wgpu reports turned into [`GpuError`] values.

use crate::GpuError;

/// Runs `f` inside out-of-memory and validation error scopes: errors wgpu
/// reports become typed values instead of wgpu's default panic.
///
/// `what` names the operation and `bytes` what it allocates (an estimate is
/// fine) in the error. An error `f` returns itself is passed through; a wgpu
/// error takes precedence over it, since it is usually the cause.
///
/// # Errors
/// [`GpuError::OutOfMemory`], [`GpuError::DeviceLost`] (a validation error
/// that says the device is lost) or [`GpuError::Validation`], converted into
/// the caller's error type; or `f`'s own error.
pub fn scoped<T, E: From<GpuError>>(
    device: &wgpu::Device,
    what: &'static str,
    bytes: u64,
    f: impl FnOnce() -> Result<T, E>,
) -> Result<T, E> {
    let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = f();
    let invalid = pollster::block_on(validation.pop());
    let out_of_memory = pollster::block_on(oom.pop());
    if out_of_memory.is_some() {
        return Err(GpuError::OutOfMemory { what, bytes }.into());
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
        }
        .into());
    }
    result
}

/// Waits for the queue and copies out the first `bytes` bytes of a
/// `MAP_READ` buffer, then unmaps it.
///
/// # Errors
/// [`GpuError::DeviceLost`] when the device is lost while waiting or
/// mapping; `what` names the operation in the error.
pub fn read_back(
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
