//! Shared by the GPU tests: a headless device per test, and the CI rule.
#![allow(dead_code)]

use nalgebra::{Point2, Point3};
use soak_bake::Mesh;

/// A device, queue and adapter description.
pub type Device = (wgpu::Device, wgpu::Queue, wgpu::AdapterInfo);

/// A headless device of its own for each test (wgpu's GL backend
/// serialises a device's work behind one context lock). `None`, with a
/// notice, when there is no adapter; a failure under `CI=true`.
pub fn device() -> Option<Device> {
    soak_shade::render::test_device()
}

/// A flat square plate of side `side` (m) in the xz plane at y = 0, facing
/// +y, with UVs `u = x/side + ½`, `v = z/side + ½`: the left half of the
/// liquid texture (u < ½) is the plate's −x half.
pub fn plate(side: f64) -> Mesh {
    let h = side / 2.0;
    Mesh::new(
        "plate",
        vec![
            Point3::new(-h, 0.0, -h),
            Point3::new(h, 0.0, -h),
            Point3::new(h, 0.0, h),
            Point3::new(-h, 0.0, h),
        ],
        Some(vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ]),
        // Counter-clockwise seen from +y.
        vec![[0, 2, 1], [0, 3, 2]],
    )
}

/// Saves `image` as `NAME.png` in the directory `SOAK_TEST_IMAGES` names,
/// if it is set: to look at what a test rendered.
pub fn keep(image: &image::RgbaImage, name: &str) {
    if let Some(dir) = std::env::var_os("SOAK_TEST_IMAGES") {
        let dir = std::path::PathBuf::from(dir);
        let _ = std::fs::create_dir_all(&dir);
        image
            .save(dir.join(format!("{name}.png")))
            .expect("save test image");
    }
}
