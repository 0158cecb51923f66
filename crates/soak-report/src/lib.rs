#![doc = include_str!("../README.md")]

pub mod accuracy;
pub mod chart;
pub mod demo;
mod gpu;
pub mod scaling;
pub mod stress;

pub use gpu::{Gpu, GpuError};
