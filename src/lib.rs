//! Textured meshes that float, drift, take on water, sink, get wet and dry,
//! in real time, inside [Rapier](https://rapier.rs) simulations.
//!
//! soak turns surface integrals into sums over texels: once per mesh it
//! bakes, from the mesh's UV map, where every covered texel sits on the
//! surface and how much oriented area it carries ([`bake`]). Mass
//! properties, submerged volume, centre of buoyancy, pressure forces and
//! drag then become data-parallel loops over texels ([`hydro`]), on the CPU
//! or the GPU, with the texture resolution as the one accuracy and cost
//! knob. [`rapier`] drives rapier3d bodies with them; [`graph`] lets water
//! into hulls through their permeable parts; [`wet`] soaks liquid into
//! surfaces and dries them; [`shade`] renders wet surfaces. Every quantity
//! is in SI units (m, kg, s, N) and every number has an exact or analytic
//! reference in the tests.
//!
//! # Using it from Rapier
//!
//! Register a Rapier body with a baked atlas and the effects it should
//! feel, then step the world through the [`ForceGenerator`](rapier::ForceGenerator):
//!
//! ```rust
#![doc = include_str!("../examples/readme.rs")]
//! ```
//!
//! Build with `--release`, or give the dependencies optimisations in debug
//! builds (`[profile.dev.package."*"] opt-level = 2` in your `Cargo.toml`):
//! the per-texel loops are some hundreds of times slower unoptimised.
//!
//! A body's [`Effects`](rapier::Effects) name everything soak does to it,
//! each off unless asked for: buoyancy, drag, water entering its hull
//! (`with_flooding`) and liquid soaking into its surface (`with_wetting`).
//! [`ForceGenerator::draft`](rapier::ForceGenerator::draft) and
//! [`SoakBody`](rapier::SoakBody)'s accessors read a body's draft,
//! submerged volume and fraction, centre of buoyancy and applied forces.
//! Scene files (TOML) describe whole simulations: see
//! [`rapier::scene`] and the `soak` command.

pub mod guide;

#[doc(inline)]
pub use soak_bake as bake;
/// Bevy: the plugin over bevy_rapier3d (the `bevy` feature).
#[cfg(feature = "bevy")]
#[doc(inline)]
pub use soak_bevy as bevy;
#[doc(inline)]
pub use soak_driver as driver;
#[doc(inline)]
pub use soak_graph as graph;
#[doc(inline)]
pub use soak_hydro as hydro;
#[doc(inline)]
pub use soak_rapier as rapier;
/// soak measured against its references (the `report` feature): the
/// stability matrix, the accuracy report, the scaling bench, charts.
#[cfg(feature = "report")]
#[doc(inline)]
pub use soak_report as report;
/// Seakeeping coefficients of any mesh: added mass, wave damping and
/// excitation against frequency by a panel method, and the radiation
/// force's memory in the time domain.
#[doc(inline)]
pub use soak_seakeeping as seakeeping;
#[doc(inline)]
pub use soak_shade as shade;
/// The live window of `soak view`, and the frames of `soak render`
/// (the `view` feature).
#[cfg(feature = "view")]
#[doc(inline)]
pub use soak_view as view;
#[doc(inline)]
pub use soak_wet as wet;

/// The f64 linear algebra soak's core types speak (points, vectors,
/// isometries): `soak::nalgebra::Point3` for [`hydro::Surface::velocity`],
/// say, without a dependency of your own. [`rapier::convert`] turns
/// Rapier's glam types into these and back.
pub use nalgebra;

/// Any of soak's errors (and any other) for a program's `main` and the
/// functions it calls: `?` turns each into one, and returned from `main`
/// it prints its message and the chain of causes beneath it ("Error: …
/// Caused by: …") where the errors' own `Debug` would print their
/// structure. It is [`anyhow::Error`].
pub use anyhow::Error;

/// `.context("…")` on a `Result` or an `Option`, for a program: the error
/// (or the missing value) becomes a [`soak::Error`](Error) that says what
/// was being done. It is [`anyhow::Context`].
pub use anyhow::Context;

/// `Result<T, soak::Error>`: what a program's `main` returns (see
/// [`Error`]).
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// The types most users need, from every crate.
pub mod prelude {
    pub use soak_bake::prelude::*;
    pub use soak_hydro::prelude::*;
    pub use soak_rapier::prelude::*;
}
