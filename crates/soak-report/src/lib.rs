#![doc = include_str!("../README.md")]

pub mod accuracy;
pub mod chart;
mod gpu;
pub mod scaling;
pub mod stress;

pub use gpu::{Gpu, GpuError};
