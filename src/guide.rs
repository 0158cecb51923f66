//! The guide: soak chapter by chapter. Every Rust block in it is compiled
//! and run as a test (`cargo test --doc -p soak`), so what it shows works;
//! the lines a block needs but does not show (imports, a world) are hidden
//! on this page and shown in the chapter's source (`docs/guide/`).
//!
//! | chapter | what it covers |
//! |---|---|
//! | [`rapier`] | a Rapier world's bodies floating: register, effects, step, results, save |
//! | [`bevy`] | the Bevy plugin (the `bevy` feature) |
//! | [`engines`] | any engine: the driver and its two traits |
//! | [`recipes`] | a sea from code, unwrapping, f64 and glam, drag, a run for Blender |
//! | [`command`] | the `soak` command |
//! | [`pictures`] | the live window, rendered stills, glTF runs |
//! | [`wetting`] | wet surfaces |
//! | [`containers`] | open containers, holes and damage |
//! | [`dynamics`] | added mass, slamming, the waves bodies make |
//! | [`accuracy`] | every path's error against exact references |
//! | [`performance`] | what each path costs, and against Jolt |
//! | [`hard_cases`] | the stability matrix, bad input, determinism, saved state |

#[doc = include_str!("../docs/guide/rapier.md")]
pub mod rapier {}

#[cfg(feature = "bevy")]
#[doc = include_str!("../docs/guide/bevy.md")]
pub mod bevy {}

/// Using it from Bevy: the `bevy` feature's chapter (build the
/// documentation with `--features bevy`, as docs.rs does).
#[cfg(not(feature = "bevy"))]
pub mod bevy {}

#[doc = include_str!("../docs/guide/engines.md")]
pub mod engines {}

#[doc = include_str!("../docs/guide/recipes.md")]
pub mod recipes {}

#[doc = include_str!("../docs/guide/command.md")]
pub mod command {}

#[doc = include_str!("../docs/guide/pictures.md")]
pub mod pictures {}

#[doc = include_str!("../docs/guide/wetting.md")]
pub mod wetting {}

#[doc = include_str!("../docs/guide/containers.md")]
pub mod containers {}

#[doc = include_str!("../docs/guide/dynamics.md")]
pub mod dynamics {}

#[doc = include_str!("../docs/guide/accuracy.md")]
pub mod accuracy {}

#[doc = include_str!("../docs/guide/performance.md")]
pub mod performance {}

#[doc = include_str!("../docs/guide/hard_cases.md")]
pub mod hard_cases {}
