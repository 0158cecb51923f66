#![doc = include_str!("../README.md")]

pub use soak_bake as bake;
pub use soak_graph as graph;
pub use soak_hydro as hydro;
pub use soak_rapier as rapier;
pub use soak_shade as shade;
pub use soak_wet as wet;

/// The types most users need, from every crate.
pub mod prelude {
    pub use soak_bake::prelude::*;
    pub use soak_hydro::prelude::*;
    pub use soak_rapier::prelude::*;
}
