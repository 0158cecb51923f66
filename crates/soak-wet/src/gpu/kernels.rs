//! The compute pipelines: WGSL composed from soak-hydro's buffer layouts and
//! water surfaces ([`soak_hydro::gpu::wgsl`]) and the kernels beside this
//! file.

use soak_gpu::{Binding, GpuError, Kernel, scoped};
use soak_hydro::gpu::wgsl::{BINDINGS as HYDRO_BINDINGS, WATER_SURFACE as WATER};

use super::layout::Params;

const BINDINGS: &str = include_str!("../../shaders/bindings.wgsl");
const EXCHANGE: &str = include_str!("../../shaders/exchange.wgsl");
const GATHER: &str = include_str!("../../shaders/gather.wgsl");
const SUBSTEP: &str = include_str!("../../shaders/substep.wgsl");
const SCATTER: &str = include_str!("../../shaders/scatter.wgsl");
const SMOOTH: &str = include_str!("../../shaders/smooth.wgsl");
const FINISH: &str = include_str!("../../shaders/finish.wgsl");
const ACTIVITY: &str = include_str!("../../shaders/activity.wgsl");
const DELTA: &str = include_str!("../../shaders/delta.wgsl");
const RESIDUAL: &str = include_str!("../../shaders/residual.wgsl");

/// The WGSL of each kernel, as compiled (for tools that validate shaders).
pub fn kernel_sources() -> Vec<(&'static str, String)> {
    vec![
        (
            "wet_exchange",
            [HYDRO_BINDINGS, WATER, BINDINGS, EXCHANGE].concat(),
        ),
        ("wet_gather", [BINDINGS, GATHER].concat()),
        ("wet_substep", [BINDINGS, SUBSTEP].concat()),
        ("wet_finish", [BINDINGS, FINISH].concat()),
        ("wet_activity", [BINDINGS, ACTIVITY].concat()),
        ("wet_delta", [BINDINGS, SMOOTH, DELTA].concat()),
        ("wet_residual", [BINDINGS, RESIDUAL].concat()),
        ("wet_scatter", [BINDINGS, SCATTER].concat()),
    ]
}

pub(crate) struct Kernels {
    pub exchange: Kernel,
    pub gather: Kernel,
    pub substep: Kernel,
    pub finish: Kernel,
    pub activity: Kernel,
    pub delta: Kernel,
    pub residual: Kernel,
    pub scatter: Kernel,
}

impl Kernels {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, GpuError> {
        use Binding::{Read, ReadWrite};
        // The last binding of every kernel: the step's `Params`.
        let params = Binding::Uniform {
            size: size_of::<Params>() as u64,
        };
        let sources = kernel_sources();
        scoped(device, "compiling the wetting kernels", 0, || {
            let make = |i: usize, slots: &[Binding]| Kernel::new(device, sources[i].0, &sources[i].1, slots);
            Ok(Self {
                exchange: make(0, &[Read, ReadWrite, Read, Read, Read, Read, Read, params]),
                gather: make(1, &[Read, Read, Read, Read, Read, ReadWrite, ReadWrite, params]),
                substep: make(2, &[Read, ReadWrite, Read, Read, Read, params]),
                finish: make(3, &[Read, Read, Read, ReadWrite, params]),
                activity: make(4, &[Read, Read, Read, ReadWrite, params]),
                delta: make(5, &[Read, Read, Read, Read, Read, Read, ReadWrite, params]),
                residual: make(6, &[Read, Read, Read, Read, Read, ReadWrite, params]),
                scatter: make(7, &[Read, ReadWrite, Read, Read, Read, Read, Read, params]),
            })
        })
    }
}
