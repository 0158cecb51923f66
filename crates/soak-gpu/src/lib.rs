#![doc = include_str!("../README.md")]

mod device;
mod error;
mod kernel;
mod scope;

pub use device::{adapter_label, headless_device, is_software, test_device};
pub use error::GpuError;
pub use kernel::{Binding, Kernel};
pub use scope::{read_back, scoped};
