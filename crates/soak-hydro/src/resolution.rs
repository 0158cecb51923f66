//! Accuracy you ask for: the coarsest atlas whose buoyancy meets a
//! tolerance, found by measuring, at bake time, its error against the
//! exact clipping of the same mesh.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeError, BakeOptions, Mesh};

use crate::error::HydroError;
use crate::hydrostatics::body_state::BodyState;
use crate::hydrostatics::evaluation::evaluate;
use crate::hydrostatics::options::HydroOptions;
use crate::mass::MassModel;
use crate::reference::{ClipPlane, submerged_part};
use crate::water::Water;

/// The atlas sides [`bake_to_tolerance`] tries, coarsest first.
pub const AUTO_RESOLUTIONS: [u32; 7] = [16, 32, 64, 128, 256, 512, 1024];

/// Water levels per orientation at which [`bake_to_tolerance`] measures.
const LEVELS: usize = 9;

/// The resolution [`bake_to_tolerance`] chose, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolutionChoice {
    /// The atlas side chosen, texels.
    pub resolution: u32,
    /// The tolerance asked for (fraction of the body's volume, and of its
    /// bounding-box diagonal for the centre of buoyancy).
    pub tolerance: f64,
    /// The worst error of the chosen atlas: the larger of
    /// `|V_s − V_exact| / V_body` and `|C_B − C_B,exact| / diagonal` over
    /// the levels and orientations measured.
    pub error: f64,
    /// Every side tried, with its error, coarsest first.
    pub tried: Vec<(u32, f64)>,
}

/// Why no resolution could be chosen.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ResolutionError {
    /// The tolerance is not a finite positive number.
    #[error("tolerance {value} must be finite and positive")]
    Tolerance {
        /// Its value.
        value: f64,
    },
    /// Even the finest atlas tried misses the tolerance.
    #[error(
        "tolerance {tolerance:.1e} not reached: the finest atlas tried ({resolution}²) is off by {reached:.1e}"
    )]
    Unreached {
        /// The tolerance asked for.
        tolerance: f64,
        /// The finest atlas tried.
        resolution: u32,
        /// Its error.
        reached: f64,
    },
    /// The mesh could not be baked.
    #[error(transparent)]
    Bake(#[from] BakeError),
    /// An evaluation failed.
    #[error(transparent)]
    Hydro(#[from] HydroError),
}

/// The worst error of `atlas` against the exact clipping of `mesh`, over
/// [`LEVELS`] water levels from just wet to just submerged, upright and at
/// a tilt.
fn worst_error(mesh: &Mesh, atlas: &Atlas) -> Result<f64, ResolutionError> {
    let mass = MassModel::Solid { density: 1.0 }.mass_properties(atlas)?;
    let volume = mesh.volume().abs().max(f64::MIN_POSITIVE);
    let diagonal = mesh.diagonal().max(f64::MIN_POSITIVE);
    let mut worst = 0.0f64;
    for rotation in [
        UnitQuaternion::identity(),
        UnitQuaternion::from_euler_angles(0.41, 0.27, 0.13),
    ] {
        let pose = Isometry3::from_parts(Vector3::zeros().into(), rotation);
        let (lo, hi) = mesh
            .positions
            .iter()
            .map(|p| (pose * p).y)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), y| {
                (l.min(y), h.max(y))
            });
        for k in 1..=LEVELS {
            let level = lo + (hi - lo) * k as f64 / (LEVELS + 1) as f64;
            let exact = submerged_part(mesh, &pose, &ClipPlane::horizontal(level));
            let texels = evaluate(
                atlas,
                &Water::calm(level),
                &BodyState::at_rest(pose),
                &mass,
                0.0,
                &HydroOptions::default(),
            )?;
            worst = worst.max((texels.submerged_volume - exact.volume).abs() / volume);
            if exact.volume > 0.01 * volume {
                worst = worst.max((texels.center_of_buoyancy - exact.centroid).norm() / diagonal);
            }
        }
    }
    Ok(worst)
}

/// Bakes `mesh` at the coarsest side of [`AUTO_RESOLUTIONS`] whose
/// submerged volume and centre of buoyancy are within `tolerance` of the
/// exact clipping of the mesh (of its volume, and of its bounding-box
/// diagonal), at nine water levels upright and at a tilt; `options` gives
/// the rest (tile size, moment matching), its width and height replaced.
///
/// The error falls with the resolution as the texels' sampling error does,
/// so the search stops at the first side that meets the tolerance. Each
/// side tried is baked and measured: a tight tolerance on a large mesh
/// costs a few bakes.
///
/// # Errors
/// [`ResolutionError::Tolerance`] for a tolerance that is not finite and
/// positive, [`ResolutionError::Unreached`] when the finest side misses
/// it, and the mesh's bake errors.
///
/// # Example
/// ```
/// use soak_bake::{BakeOptions, builtin};
/// use soak_hydro::bake_to_tolerance;
///
/// let mesh = builtin::cuboid(1.0, 0.6, 0.8);
/// let (atlas, choice) = bake_to_tolerance(&mesh, 1e-3, BakeOptions::square(0))?;
/// assert!(choice.error <= 1e-3);
/// assert_eq!(atlas.width(), choice.resolution);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn bake_to_tolerance(
    mesh: &Mesh,
    tolerance: f64,
    options: BakeOptions,
) -> Result<(Atlas, ResolutionChoice), ResolutionError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(ResolutionError::Tolerance { value: tolerance });
    }
    let mut tried = Vec::new();
    for n in AUTO_RESOLUTIONS {
        let atlas = Atlas::bake(
            mesh,
            BakeOptions {
                width: n,
                height: n,
                ..options
            },
        )?;
        let error = worst_error(mesh, &atlas)?;
        tried.push((n, error));
        if error <= tolerance {
            return Ok((
                atlas,
                ResolutionChoice {
                    resolution: n,
                    tolerance,
                    error,
                    tried,
                },
            ));
        }
    }
    let (resolution, reached) = tried.last().copied().unwrap_or((0, f64::NAN));
    Err(ResolutionError::Unreached {
        tolerance,
        resolution,
        reached,
    })
}
