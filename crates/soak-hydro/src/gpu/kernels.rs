//! The compute pipelines: WGSL composed from the buffer layouts and water
//! surfaces of [`super::wgsl`] and the kernels beside this file.

use soak_gpu::{Binding, Kernel, scoped};

use super::error::GpuHydroError;
use super::layout::Dispatch;
use super::wgsl::{BINDINGS, WATER_SURFACE as WATER};

const BUOYANCY: &str = include_str!("../../shaders/buoyancy.wgsl");
const REDUCE: &str = include_str!("../../shaders/reduce.wgsl");
const MASS: &str = include_str!("../../shaders/mass.wgsl");
const DEFORM: &str = include_str!("../../shaders/deform.wgsl");
const SEA: &str = include_str!("../../shaders/sea.wgsl");
const SEA_MODES: &str = include_str!("../../shaders/sea_modes.wgsl");
const SEA_UNPACK: &str = include_str!("../../shaders/sea_unpack.wgsl");

/// The WGSL of each kernel, as compiled (for tools that validate shaders).
pub fn kernel_sources() -> Vec<(&'static str, String)> {
    vec![
        ("buoyancy", [BINDINGS, WATER, BUOYANCY].concat()),
        ("reduce_hydro", reduce_source(super::layout::HYDRO_SLOTS, 3)),
        ("mass", [BINDINGS, MASS].concat()),
        (
            "reduce_mass",
            reduce_source(super::layout::MASS_SLOTS, super::layout::MASS_SLOTS),
        ),
        ("deform", [BINDINGS, DEFORM].concat()),
        ("sea_modes", [SEA, SEA_MODES].concat()),
        ("sea_fft", super::waves::FFT.to_string()),
        ("sea_unpack", [SEA, SEA_UNPACK].concat()),
    ]
}

fn reduce_source(slots: u32, count_slot: u32) -> String {
    format!("{BINDINGS}\nconst SLOTS: u32 = {slots}u;\nconst COUNT_SLOT: u32 = {count_slot}u;\n{REDUCE}")
}

pub(crate) struct Kernels {
    pub buoyancy: Kernel,
    pub reduce_hydro: Kernel,
    pub mass: Kernel,
    pub reduce_mass: Kernel,
    pub deform: Kernel,
    /// A spectral sea's tile: its layers of coefficients, an FFT stage,
    /// its fields laid out for the buoyancy kernel ([`super::sea`]).
    pub sea_modes: Kernel,
    pub sea_fft: Kernel,
    pub sea_unpack: Kernel,
}

impl Kernels {
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, GpuHydroError> {
        use Binding::{Read, ReadWrite};
        // The last binding of every kernel: one `Dispatch` at a dynamic offset.
        let dispatch = Binding::DynamicUniform {
            size: size_of::<Dispatch>() as u64,
        };
        let sea = Binding::DynamicUniform {
            size: size_of::<super::sea::SeaUniform>() as u64,
        };
        let stage = Binding::DynamicUniform {
            size: size_of::<super::waves::Stage>() as u64,
        };
        let sources = kernel_sources();
        scoped(device, "compiling the hydrostatics kernels", 0, || {
            let make = |i: usize, slots: &[Binding]| Kernel::new(device, sources[i].0, &sources[i].1, slots);
            Ok(Self {
                buoyancy: make(0, &[Read, Read, Read, Read, Read, Read, ReadWrite, dispatch]),
                reduce_hydro: make(1, &[Read, Read, ReadWrite, dispatch]),
                mass: make(2, &[Read, Read, Read, ReadWrite, dispatch]),
                reduce_mass: make(3, &[Read, Read, ReadWrite, dispatch]),
                deform: make(4, &[ReadWrite, Read, Read, Read, ReadWrite, Read, dispatch]),
                sea_modes: make(5, &[Read, ReadWrite, sea]),
                sea_fft: make(6, &[Read, ReadWrite, stage]),
                sea_unpack: make(7, &[Read, ReadWrite, sea]),
            })
        })
    }
}
