//! The cells of the stability matrix: meshes, relative densities, time
//! steps, scales, waters and effects, the full product and the quick subset.

use serde::Serialize;

/// Relative densities ρ_b/ρ_w of the matrix.
pub const DENSITIES: [f64; 7] = [0.01, 0.1, 0.5, 0.9, 1.0, 2.0, 10.0];
/// Step rates of the matrix, Hz (time steps 1/240, 1/60 and 1/10 s).
pub const RATES: [u32; 3] = [240, 60, 10];
/// Scales of the matrix: each mesh is scaled by these factors (1 mm to 1 km
/// for a unit mesh).
pub const SCALES: [f64; 3] = [1e-3, 1.0, 1e3];

/// A mesh of the matrix.
///
/// The builtins at modest tessellations (a 32² atlas cannot use more), a
/// sliver: a box 200 times longer than it is thick, whose long faces are
/// triangles of aspect ratio 200 that cover almost no texel centre, and
/// three open containers (single-sided meshes whose rims are capped; water
/// comes over them from the `+ingress` level on).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Shape {
    /// `builtin:sphere:0.5:24:12`.
    Sphere,
    /// `builtin:box` (a unit cube).
    Box,
    /// `builtin:cylinder:0.5:1:24`.
    Cylinder,
    /// `builtin:capsule:0.25:0.5:16`.
    Capsule,
    /// `builtin:torus:0.5:0.15:24:12`.
    Torus,
    /// `builtin:boat`.
    Boat,
    /// `builtin:box:2x0.01x0.01`: a 200:1 rod.
    Sliver,
    /// `builtin:open_box` (1 × 0.5 × 1, open at the top), capped.
    OpenBox,
    /// `builtin:bucket:0.3:0.6:24`, capped.
    Bucket,
    /// `builtin:open_boat` (a rowing boat without a deck), capped.
    OpenBoat,
}

impl Shape {
    /// Every mesh of the matrix, in its order.
    pub const ALL: [Shape; 10] = [
        Shape::Sphere,
        Shape::Box,
        Shape::Cylinder,
        Shape::Capsule,
        Shape::Torus,
        Shape::Boat,
        Shape::Sliver,
        Shape::OpenBox,
        Shape::Bucket,
        Shape::OpenBoat,
    ];

    /// Whether the mesh is open (its rims capped before baking).
    pub fn is_open(self) -> bool {
        matches!(self, Shape::OpenBox | Shape::Bucket | Shape::OpenBoat)
    }

    /// The short name in cell names and tables.
    pub fn label(self) -> &'static str {
        match self {
            Shape::Sphere => "sphere",
            Shape::Box => "box",
            Shape::Cylinder => "cylinder",
            Shape::Capsule => "capsule",
            Shape::Torus => "torus",
            Shape::Boat => "boat",
            Shape::Sliver => "sliver",
            Shape::OpenBox => "open_box",
            Shape::Bucket => "bucket",
            Shape::OpenBoat => "open_boat",
        }
    }

    /// The `builtin:` mesh it is baked from.
    pub fn source(self) -> &'static str {
        match self {
            Shape::Sphere => "builtin:sphere:0.5:24:12",
            Shape::Box => "builtin:box",
            Shape::Cylinder => "builtin:cylinder:0.5:1:24",
            Shape::Capsule => "builtin:capsule:0.25:0.5:16",
            Shape::Torus => "builtin:torus:0.5:0.15:24:12",
            Shape::Boat => "builtin:boat",
            Shape::Sliver => "builtin:box:2x0.01x0.01",
            Shape::OpenBox => "builtin:open_box",
            Shape::Bucket => "builtin:bucket:0.3:0.6:24",
            Shape::OpenBoat => "builtin:open_boat",
        }
    }
}

/// The fluid of a cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WaterKind {
    /// Calm water at y = 0.
    Plane,
    /// Two steep Gerstner waves about y = 0.
    Sea,
    /// A static height field with a cliff under the body.
    Cliff,
    /// A spectral sea (JONSWAP) about y = 0, its peak wave as long as the
    /// sea's longer wave.
    Ocean,
}

impl WaterKind {
    /// Every fluid of the matrix, in its order.
    pub const ALL: [WaterKind; 4] = [
        WaterKind::Plane,
        WaterKind::Sea,
        WaterKind::Cliff,
        WaterKind::Ocean,
    ];

    /// The short name in cell names and tables.
    pub fn label(self) -> &'static str {
        match self {
            WaterKind::Plane => "plane",
            WaterKind::Sea => "sea",
            WaterKind::Cliff => "cliff",
            WaterKind::Ocean => "ocean",
        }
    }

    /// Whether the water moves (a Gerstner or a spectral sea).
    pub fn moves(self) -> bool {
        matches!(self, WaterKind::Sea | WaterKind::Ocean)
    }
}

/// The effects of a cell; each level adds to the one before.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// Archimedes buoyancy.
    Buoyancy,
    /// + quadratic drag.
    Drag,
    /// + water entering through a permeable hull into a two-node graph.
    Ingress,
    /// + surface wetting with diffusion at 10× its explicit limit.
    Wetting,
    /// + added mass: the equivalent ellipsoid's, scaled by the submerged
    ///   fraction.
    AddedMass,
    /// + radiation (Cummins' equation from a panel method on the closed
    ///   shape floating at rest, baked as a scene bakes it), which
    ///   supersedes the added mass; a body the panel method cannot float
    ///   (as dense as the water or denser) goes without, as in a scene.
    Radiation,
}

impl Level {
    /// Every level of the matrix, in its order.
    pub const ALL: [Level; 6] = [
        Level::Buoyancy,
        Level::Drag,
        Level::Ingress,
        Level::Wetting,
        Level::AddedMass,
        Level::Radiation,
    ];

    /// The short name in cell names and tables.
    pub fn label(self) -> &'static str {
        match self {
            Level::Buoyancy => "buoyancy",
            Level::Drag => "+drag",
            Level::Ingress => "+ingress",
            Level::Wetting => "+wetting",
            Level::AddedMass => "+added_mass",
            Level::Radiation => "+radiation",
        }
    }
}

/// One cell of the matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// The mesh.
    pub mesh: Shape,
    /// Relative density ρ_b/ρ_w.
    pub density: f64,
    /// Step rate, Hz.
    pub rate: u32,
    /// Scale factor of the mesh.
    pub scale: f64,
    /// The fluid.
    pub water: WaterKind,
    /// The effects.
    pub level: Level,
}

impl Cell {
    /// `mesh/scale/density/1/rate/water/effects`, e.g.
    /// `sliver/1e-3m/0.5/1/60/cliff/buoyancy` (the `1` is the water's
    /// relative density).
    pub fn name(&self) -> String {
        format!(
            "{}/{}/{}/1/{}/{}/{}",
            self.mesh.label(),
            fmt_scale(self.scale),
            self.density,
            self.rate,
            self.water.label(),
            self.level.label()
        )
    }

    /// The cell of the full matrix named `name` ([`Cell::name`]).
    pub fn from_name(name: &str) -> Option<Cell> {
        full_matrix().into_iter().find(|c| c.name() == name)
    }
}

fn fmt_scale(s: f64) -> String {
    if s == 1.0 { "1m".into() } else { format!("{s:e}m") }
}

/// The full product: 10 meshes × 4 waters × 6 levels × 3 scales × 7
/// densities × 3 rates = 15,120 cells.
pub fn full_matrix() -> Vec<Cell> {
    let mut cells = Vec::new();
    for mesh in Shape::ALL {
        for water in WaterKind::ALL {
            for level in Level::ALL {
                for scale in SCALES {
                    for density in DENSITIES {
                        for rate in RATES {
                            cells.push(Cell {
                                mesh,
                                density,
                                rate,
                                scale,
                                water,
                                level,
                            });
                        }
                    }
                }
            }
        }
    }
    cells
}

/// Every mesh × water × effects but radiation (200 cells), each with one (density, time
/// step, scale) taken in turn from a list that pairs the extremes: the
/// lightest and the heaviest bodies, the neutral one, the smallest and
/// largest scales, the shortest and longest steps all appear, on every mesh
/// and in every water.
pub fn quick_matrix() -> Vec<Cell> {
    const PICKS: [(f64, u32, f64); 6] = [
        (0.01, 10, 1e-3),
        (10.0, 240, 1e3),
        (0.5, 60, 1.0),
        (1.0, 10, 1e3),
        (0.01, 240, 1e3),
        (10.0, 10, 1e-3),
    ];
    let mut cells = Vec::new();
    let mut k = 0;
    // The spectral sea, the last water added, takes the picks in an order
    // of its own, so that the other waters' cells are the ones they were.
    let mut k_ocean = 3;
    for mesh in Shape::ALL {
        for water in WaterKind::ALL {
            let k = if water == WaterKind::Ocean {
                &mut k_ocean
            } else {
                &mut k
            };
            // The radiation level is the full matrix's alone (each of its
            // cells bakes the panel method, seconds each; docs/stress.md),
            // and adding it here would change every later pick.
            for level in Level::ALL.into_iter().filter(|&l| l != Level::Radiation) {
                let (density, rate, scale) = PICKS[*k % PICKS.len()];
                *k += 1;
                cells.push(Cell {
                    mesh,
                    density,
                    rate,
                    scale,
                    water,
                    level,
                });
            }
            // Shift the rotation so each mesh meets the picks in another order.
            *k += 1;
        }
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_matrices_have_their_sizes_and_names_round_trip() {
        let full = full_matrix();
        assert_eq!(full.len(), 15120);
        assert_eq!(quick_matrix().len(), 200);
        let mut names: Vec<String> = full.iter().map(Cell::name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), full.len(), "cell names are unique");
        let c = Cell::from_name("sliver/1e-3m/0.5/1/60/cliff/buoyancy").expect("a cell of the matrix");
        assert_eq!(
            (c.mesh, c.scale, c.density, c.rate),
            (Shape::Sliver, 1e-3, 0.5, 60)
        );
        assert_eq!((c.water, c.level), (WaterKind::Cliff, Level::Buoyancy));
        assert!(Cell::from_name("sliver/2m/0.5/1/60/cliff/buoyancy").is_none());
        for q in quick_matrix() {
            assert!(full.contains(&q), "{} is a cell of the full matrix", q.name());
        }
    }
}
