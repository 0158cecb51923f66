//! Scene TOML → `LoadedScene::from_str` → (clamped) `Simulation::from_scene`
//! → a few steps.
//!
//! The scene is clamped before it is built so an execution stays cheap:
//! at most 4 bodies, `builtin:` meshes with at most 24 segments (other
//! meshes become `builtin:box`), atlases of at most 32², at most 8 steps,
//! graph files only from `data/graphs/`, the height field from
//! `fuzz/heightfield.csv`, interactive waves of at most 64² cells. Nothing may panic; when every number is in a
//! physical range, every body must stay finite.
#![no_main]

use std::path::{Path, PathBuf};

use libfuzzer_sys::fuzz_target;
use soak_rapier::scene::{GraphSpec, MassSpec, ResolutionSpec, WaterKind};
use soak_rapier::{Backend, LoadedScene, Simulation};

const MAX_BODIES: usize = 4;
const MAX_SEGMENTS: u64 = 24;
const MAX_RESOLUTION: u32 = 32;
const MAX_STEPS: u64 = 8;
const GRAPHS: &[&str] = &[
    "boat.toml",
    "communicating_vessels.json",
    "fig4_5_barrier.toml",
    "fig4_5_cascade.toml",
    "fig4_5_u_tube.toml",
];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Whether every `:`-separated number of a builtin name is small enough,
/// and (second) whether its sizes are physical (1 cm … 100 m).
fn builtin_cost(name: &str) -> (bool, bool) {
    let mut cheap = true;
    let mut physical = true;
    for part in name.split(':').skip(2) {
        for t in part.split('x') {
            if let Ok(n) = t.parse::<u64>() {
                cheap &= n <= MAX_SEGMENTS;
            }
            if let Ok(v) = t.parse::<f64>() {
                physical &= (1e-2..=1e2).contains(&v);
            }
        }
    }
    (cheap, physical)
}

fn within(v: &[f64], bound: f64) -> bool {
    v.iter().all(|x| x.abs() <= bound)
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = repo().join("data/scenes/fuzz.toml");
    let mut loaded = match LoadedScene::from_str(text, &path) {
        Ok(l) => l,
        Err(e) => {
            assert!(e.to_string().contains("fuzz.toml"), "{e}");
            return;
        }
    };
    let s = &mut loaded.scene;
    let mut physical = s.dt >= 1e-4 && within(&s.gravity, 100.0);
    s.bodies.truncate(MAX_BODIES);
    if s.backend == Backend::Gpu {
        s.backend = Backend::Tiled;
    }
    // Interactive waves: at most 64 cells a side (a fuzz run's budget; the
    // limit on what a scene may ask for is the loader's to check).
    if let Some(w) = &mut s.waves {
        w.cells = w.cells.min(64);
    }
    if s.water.kind == WaterKind::HeightField {
        s.water.file = Some(repo().join("fuzz/heightfield.csv").display().to_string());
    }
    physical &= s.water.density.is_none_or(|d| (0.1..=1e5).contains(&d));
    physical &= within(&s.water.current.unwrap_or_default(), 100.0);
    physical &= within(&[s.water.level.unwrap_or(0.0)], 1e3);
    physical &= s
        .water
        .spacing
        .is_none_or(|sp| sp.iter().all(|v| (1e-2..=1e3).contains(v)));
    physical &= s.water.origin.is_none_or(|o| within(&o, 1e4));
    for b in &mut s.bodies {
        if !b.mesh.starts_with("builtin:") {
            b.mesh = "builtin:box".into();
        }
        let (cheap, sizes) = builtin_cost(&b.mesh);
        if !cheap {
            return;
        }
        physical &= sizes;
        // `"auto"` bakes up to 1024²: too slow for a fuzz run; a fixed side
        // is capped.
        b.resolution = match b.resolution {
            ResolutionSpec::Texels(n) => ResolutionSpec::Texels(n.min(MAX_RESOLUTION)),
            ResolutionSpec::Auto(_) => ResolutionSpec::Texels(MAX_RESOLUTION),
        };
        match &mut b.graph {
            Some(GraphSpec::File(f)) => {
                let name = f.strip_prefix("../graphs/").unwrap_or("");
                if GRAPHS.contains(&name) {
                    *f = repo().join("data/graphs").join(name).display().to_string();
                } else {
                    b.graph = None;
                    b.permeability.clear();
                }
            }
            Some(GraphSpec::Auto(a)) => a.clusters = a.clusters.min(3),
            Some(GraphSpec::Cavity(_)) | None => {}
        }
        physical &= match b.mass {
            MassSpec::Solid { density } => (1.0..=1e5).contains(&density),
            MassSpec::Shell { areal_density } => (1e-2..=1e4).contains(&areal_density),
            MassSpec::Walls { density, thickness } => {
                (1.0..=1e5).contains(&density) && (1e-4..=1.0).contains(&thickness)
            }
        };
        physical &= within(&b.position, 1e4)
            && within(&b.linear_velocity, 100.0)
            && within(&b.angular_velocity, 100.0)
            && b.drag.is_none_or(|d| d.coefficient <= 1e3 && d.linear <= 1e4)
            && b.permeability
                .iter()
                .all(|h| h.kappa.is_none_or(|k| k <= 1e-3) && within(&h.centre, 1e3));
    }
    let mut sim = match Simulation::from_scene(&loaded) {
        Ok(sim) => sim,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return;
        }
    };
    sim.record(true);
    for _ in 0..sim.total_steps().min(MAX_STEPS) {
        if let Err(e) = sim.step() {
            assert!(!e.to_string().is_empty());
            return;
        }
    }
    if physical {
        for r in sim.report() {
            let finite = r
                .position
                .iter()
                .chain(&r.linear_velocity)
                .chain(&r.angular_velocity)
                .all(|v| v.is_finite());
            assert!(
                finite && !r.non_finite,
                "body `{}` went non-finite: {r:?}",
                r.name
            );
        }
    }
});
