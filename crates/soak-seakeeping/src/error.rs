//! What can go wrong.

/// A radiation problem that cannot be set up or solved.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum SeakeepingError {
    /// Nothing of the body is under water.
    #[error("the body has no wetted surface (no panel below y = 0)")]
    NoWettedSurface,
    /// A panel reaches above the still water plane.
    #[error("panel {panel} reaches {height} m above the still water plane y = 0")]
    PanelAboveWater {
        /// The panel's index.
        panel: usize,
        /// Its highest vertex's height, m.
        height: f64,
    },
    /// A mesh vertex that is not a finite point.
    #[error("mesh `{mesh}`: vertex {vertex} is not finite")]
    BadMesh {
        /// The mesh's name.
        mesh: String,
        /// The vertex.
        vertex: usize,
    },
    /// A triangle naming a vertex the mesh does not have.
    #[error("mesh `{mesh}`: triangle {triangle} names vertex {vertex}, which it does not have")]
    BadTriangle {
        /// The mesh's name.
        mesh: String,
        /// The triangle.
        triangle: usize,
        /// The vertex index it names.
        vertex: usize,
    },
    /// A physical parameter out of range.
    #[error("{name} must be positive and finite, got {value}")]
    BadParameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The body is too heavy to float: it would displace more than its
    /// whole volume, or within 0.1 % of it (neutral: no water-plane to
    /// float on, where linear theory about a rest has nothing to hold).
    #[error("the body sinks: floating would take {displaced} m³ of water, it encloses {volume} m³")]
    Sinks {
        /// The volume its mass would displace, m³.
        displaced: f64,
        /// Its whole volume, m³.
        volume: f64,
    },
    /// The panel solution breaks reciprocity: the infinite-frequency
    /// added mass, symmetric in theory, is not (a panel so badly shaped
    /// or placed that its potential is wrong by orders of magnitude).
    #[error(
        "the panel solution is not reciprocal: the infinite-frequency added mass of modes {i} and {j} differs from its transpose by {ratio:.2} of their scale √(A_ii A_jj) (more than 0.2): the wetted hull's panels are degenerate; more panels, or a cleaner mesh near the waterline, may cure it"
    )]
    NotReciprocal {
        /// The row's mode (0–2 surge, heave, sway; 3–5 their rotations).
        i: usize,
        /// The column's mode.
        j: usize,
        /// `|A_ij − A_ji| / √(A_ii A_jj)`.
        ratio: f64,
    },
    /// The panel system is singular at this frequency.
    #[error("the panel system is singular at ω = {omega} rad/s")]
    Singular {
        /// The frequency, rad/s.
        omega: f64,
    },
}
