//! Liquid-graph files (TOML, or JSON when the text starts with `{`) →
//! `soak_graph::parse_graph` → a flooding behind a permeable box wall → a
//! few steps half under water. Nothing may panic; nodes stay finite, within
//! [0, capacity], and the ledger balances.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use soak_graph::{Flooding, FlowOptions, Format, Permeability};
use soak_hydro::Water;

const MAX_NODES: usize = 64;
const MAX_EDGES: usize = 256;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (format, path) = if text.trim_start().starts_with('{') {
        (Format::Json, Path::new("fuzz.json"))
    } else {
        (Format::Toml, Path::new("fuzz.toml"))
    };
    let graph = match soak_graph::parse_graph(text, format, path) {
        Ok(g) => g,
        Err(e) => {
            let message = e.to_string();
            assert!(message.contains("fuzz."), "{message}");
            return;
        }
    };
    if graph.node_count() > MAX_NODES || graph.edge_count() > MAX_EDGES {
        return;
    }
    // Text → graph → text → graph gives the same graph.
    let again = soak_graph::parse_graph(&soak_graph::to_toml(&graph), Format::Toml, path)
        .unwrap_or_else(|e| panic!("a parsed graph does not round-trip through TOML: {e}"));
    assert_eq!(again.node_count(), graph.node_count());
    assert_eq!(again.edge_count(), graph.edge_count());

    let atlas = soak_fuzz::small_atlas();
    let permeability = Permeability::uniform(atlas, 1e-6).expect("valid kappa");
    let mut flow = match Flooding::for_atlas(atlas, graph, permeability, FlowOptions::default()) {
        Ok(f) => f,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return;
        }
    };
    let water = Water::calm(0.0);
    let dt = 0.05;
    for k in 0..4 {
        let pose = Isometry3::from_parts(
            Translation3::new(0.0, -0.2 + 0.1 * k as f64, 0.0),
            UnitQuaternion::from_euler_angles(0.3 * k as f64, 0.0, 0.1),
        );
        if let Err(e) = flow.step(atlas, &pose, &water, k as f64 * dt, dt) {
            assert!(!e.to_string().is_empty());
            return;
        }
        for (i, n) in flow.graph().nodes().enumerate() {
            assert!(
                n.liquid.is_finite() && n.liquid >= 0.0 && n.liquid <= n.capacity * (1.0 + 1e-12),
                "node {i}: {n:?}"
            );
        }
        let err = flow.conservation_error();
        assert!(
            err.is_finite() && err < 1e-9,
            "conservation error {err:e} after step {k}"
        );
    }
});
