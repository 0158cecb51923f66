//! The interactive waves' solver on the GPU against the CPU's: the same
//! exact step (f32 on the device), a hump spreading under a pressure
//! patch, and what the GPU solver refuses.
#![cfg(feature = "gpu")]

use soak_hydro::gpu::{GpuHydroError, GpuWaves, test_device};
use soak_hydro::{InteractiveWaves, WaveRegion};

const G: f64 = 9.81;

fn region(cells: usize) -> WaveRegion {
    WaveRegion {
        centre: [1.0, -2.0],
        size: 32.0,
        cells,
    }
}

/// A hump let go while a patch presses nearby, 90 steps of 1/30 s on both:
/// the GPU's elevation within 1e-5 of the largest, everywhere, and the
/// potential as close (f32 on the device, f64 on the CPU).
#[test]
fn the_gpu_steps_the_waves_as_the_cpu_does() {
    let Some((device, queue, _)) = test_device() else {
        return;
    };
    for cells in [64, 128] {
        let mut cpu = InteractiveWaves::new(region(cells), G, 1000.0, 8).unwrap();
        let mut gpu = GpuWaves::new(&device, &queue, region(cells), G, 8).unwrap();
        let n = cells;
        let h: Vec<f64> = (0..n * n)
            .map(|i| {
                let [x, z] = cpu.cell_centre(i % n, i / n);
                0.05 * (-((x - 1.0).powi(2) + (z + 2.0).powi(2)) / 0.5).exp()
            })
            .collect();
        cpu.set_state(&h, &vec![0.0; n * n]).unwrap();
        gpu.set_state(&h, &vec![0.0; n * n]).unwrap();
        cpu.add_gaussian(5.0, 0.0, 0.4, 0.03);
        gpu.set_pressure(cpu.pressure_mut()).unwrap();
        for _ in 0..90 {
            cpu.step(1.0 / 30.0).unwrap();
            gpu.step(1.0 / 30.0).unwrap();
        }
        let (gh, gphi) = gpu.state().unwrap();
        assert!(gh.iter().chain(&gphi).all(|v| v.is_finite()));
        assert_eq!(gpu.heights().unwrap(), gh);
        let (ch, cphi) = (cpu.heights().to_vec(), cpu.state().phi);
        let largest = |v: &[f64]| v.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let worst = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
        let (eh, ephi) = (
            worst(&gh, &ch) / largest(&ch),
            worst(&gphi, &cphi) / largest(&cphi),
        );
        println!("{cells}²: elevation within {eh:.2e} of its largest, potential within {ephi:.2e}");
        assert!(eh < 1e-5 && ephi < 1e-5, "{eh} {ephi}");
        assert!((gpu.time() - cpu.time()).abs() < 1e-12);
    }
}

/// Cells that are not a power of two, a step that is not finite and > 0,
/// fields of the wrong size or not finite are refused by name.
#[test]
fn the_gpu_waves_refuse_what_they_cannot_step() {
    let Some((device, queue, _)) = test_device() else {
        return;
    };
    let err = GpuWaves::new(&device, &queue, region(96), G, 8).unwrap_err();
    assert!(matches!(err, GpuHydroError::Waves(_)), "{err}");
    assert!(err.to_string().contains("power of two"), "{err}");
    assert!(GpuWaves::new(&device, &queue, region(64), f64::NAN, 8).is_err());
    let mut gpu = GpuWaves::new(&device, &queue, region(64), G, 8).unwrap();
    assert!(gpu.step(f64::NAN).is_err());
    assert!(gpu.step(0.0).is_err());
    assert!(gpu.set_pressure(&[0.0; 10]).is_err());
    let mut bad = vec![0.0; 64 * 64];
    bad[7] = f64::INFINITY;
    let err = gpu.set_state(&bad, &vec![0.0; 64 * 64]).unwrap_err();
    assert!(err.to_string().contains("7"), "{err}");
    // Nothing was stepped.
    assert_eq!(gpu.time(), 0.0);
    assert!(gpu.heights().unwrap().iter().all(|h| *h == 0.0));
}
