//! Pins the beach scene (thesis Fig. 7.11; `examples/beach.rs` at full
//! resolution) at a small resolution: rounded liquid totals and fill
//! histograms of the sand, the rock and the crate after fixed step counts.

use serde::Serialize;
use soak_wet::LiquidStats;
use soak_wet::scenes::{Beach, BeachOptions};

#[derive(Serialize)]
struct Body {
    name: &'static str,
    stats: LiquidStats,
}

#[derive(Serialize)]
struct Frame {
    step: usize,
    time: f64,
    bodies: Vec<Body>,
}

#[test]
fn beach_liquid_after_fixed_steps() {
    let mut beach = Beach::new(BeachOptions::small()).unwrap();
    let mut frames = Vec::new();
    for step in 1..=300 {
        beach.step().unwrap();
        if step % 100 == 0 {
            frames.push(Frame {
                step,
                time: (beach.time * 1e3).round() / 1e3,
                bodies: beach
                    .bodies
                    .iter()
                    .map(|b| Body {
                        name: b.name,
                        stats: b.wetting.stats(&b.atlas).unwrap().rounded(3),
                    })
                    .collect(),
            });
        }
    }
    insta::assert_yaml_snapshot!(frames);
}
