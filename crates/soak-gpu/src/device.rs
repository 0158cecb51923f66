//! Getting a device without a window, and naming adapters in reports.

use crate::GpuError;

/// A device and queue on the first adapter wgpu offers, without a window.
///
/// The instance reads the environment (`WGPU_BACKEND=vulkan|gl` picks a
/// backend, `WGPU_ADAPTER_NAME` an adapter), so CI can run the same tests on
/// Mesa's lavapipe (Vulkan) and llvmpipe (GL). The device gets the adapter's
/// own limits (larger storage bindings than the WebGPU defaults) and no
/// optional feature: the kernels stay within the WebGPU baseline.
///
/// A convenience for tests, tools and benches: soak's GPU functions take a
/// device, so engines pass their own.
///
/// # Errors
/// [`GpuError::NoAdapter`] when wgpu finds no adapter on any enabled
/// backend, [`GpuError::RequestDevice`] when the adapter refuses the device.
pub fn headless_device() -> Result<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo), GpuError> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: None,
        apply_limit_buckets: false,
    }))
    .map_err(|e| GpuError::NoAdapter {
        reason: e.to_string(),
    })?;
    let info = adapter.get_info();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("soak"),
        required_features: wgpu::Features::empty(),
        required_limits: adapter.limits(),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::Performance,
        trace: wgpu::Trace::Off,
    }))
    .map_err(|e| GpuError::RequestDevice {
        adapter: adapter_label(&info),
        reason: e.to_string(),
    })?;
    Ok((device, queue, info))
}

/// Whether the adapter is a software rasteriser on the CPU (llvmpipe,
/// lavapipe, WARP): its timings are not GPU timings.
pub fn is_software(info: &wgpu::AdapterInfo) -> bool {
    info.device_type == wgpu::DeviceType::Cpu
}

/// `"NAME (BACKEND)"`, with `, software` for a CPU adapter: for reports and
/// bench labels.
pub fn adapter_label(info: &wgpu::AdapterInfo) -> String {
    let backend = match info.backend {
        wgpu::Backend::Vulkan => "Vulkan",
        wgpu::Backend::Gl => "GL",
        wgpu::Backend::Metal => "Metal",
        wgpu::Backend::Dx12 => "DX12",
        wgpu::Backend::BrowserWebGpu => "WebGPU",
        _ => "other backend",
    };
    let driver = if info.driver.is_empty() {
        String::new()
    } else {
        format!(", {}", info.driver)
    };
    let software = if is_software(info) { ", software" } else { "" };
    format!("{} ({backend}{driver}{software})", info.name)
}

/// [`headless_device`] for test suites and benches: `None`, with a notice on
/// standard error, when there is no adapter, so GPU tests skip on a machine
/// without one; but under `CI=true` a missing adapter panics, so GPU tests
/// cannot pass in CI by skipping. Announces the adapter once per process.
///
/// Take a device of its own for each test: on wgpu's GL backend a device
/// serialises all its work behind one context lock, which wgpu gives up on
/// after 6 s, and tests running in parallel on one device could trip it.
///
/// # Panics
/// When no device can be had and the environment variable `CI` is `true`.
pub fn test_device() -> Option<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo)> {
    static ANNOUNCE: std::sync::Once = std::sync::Once::new();
    match headless_device() {
        Ok(d) => {
            ANNOUNCE.call_once(|| eprintln!("GPU tests on {}", adapter_label(&d.2)));
            Some(d)
        }
        Err(e) => {
            if std::env::var("CI").as_deref() == Ok("true") {
                panic!("no GPU adapter under CI=true: {e}");
            }
            eprintln!("no GPU adapter: skipping ({e})");
            None
        }
    }
}
