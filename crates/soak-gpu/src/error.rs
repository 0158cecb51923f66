//! What can go wrong on a device, as values.

/// A device-level GPU failure: no adapter, a refused device, a lost device,
/// memory, validation, or a buffer above the device's binding limit.
///
/// The GPU paths of soak wrap it in their own errors (`GpuHydroError`,
/// `GpuWetError`, `RenderError`) next to what is specific to them.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GpuError {
    /// No adapter on any enabled backend.
    #[error(
        "no GPU adapter found ({reason}); on Debian install mesa-vulkan-drivers and libvulkan1 \
         (lavapipe) or libegl1, libegl-mesa0 and libgl1-mesa-dri (llvmpipe), or pick a backend \
         with WGPU_BACKEND=vulkan|gl"
    )]
    NoAdapter {
        /// wgpu's reason.
        reason: String,
    },
    /// The adapter refused the device request.
    #[error("requesting a device from {adapter} failed: {reason}")]
    RequestDevice {
        /// The adapter's label ([`crate::adapter_label`]).
        adapter: String,
        /// wgpu's reason.
        reason: String,
    },
    /// The device was lost (driver reset, destroyed device).
    #[error("the GPU device was lost while {what}: {reason}")]
    DeviceLost {
        /// The operation.
        what: &'static str,
        /// wgpu's reason.
        reason: String,
    },
    /// The device ran out of memory.
    #[error("out of GPU memory while {what} ({bytes} bytes requested)")]
    OutOfMemory {
        /// The operation.
        what: &'static str,
        /// Bytes that operation allocated (an estimate where the operation
        /// allocates several buffers).
        bytes: u64,
    },
    /// wgpu rejected an operation (a bug in soak, or a device below the
    /// WebGPU baseline or below what the operation needs).
    #[error("wgpu rejected {what}: {message}")]
    Validation {
        /// The operation.
        what: &'static str,
        /// wgpu's message.
        message: String,
    },
    /// A buffer that cannot be split would exceed the device's storage binding limit.
    #[error(
        "{what}: {needed} bytes needed in one storage binding, above the limit of {limit} bytes \
         (max_storage_buffer_binding_size); evaluate fewer bodies per batch"
    )]
    TooLarge {
        /// The buffer.
        what: &'static str,
        /// Bytes it needs.
        needed: u64,
        /// The limit in force.
        limit: u64,
    },
    /// The limit in force cannot hold even one work item.
    #[error("a storage binding limit of {limit} bytes is below the minimum of {minimum} bytes")]
    LimitTooSmall {
        /// The limit asked for.
        limit: u64,
        /// The smallest workable limit.
        minimum: u64,
    },
}
