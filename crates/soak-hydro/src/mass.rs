//! Mass properties from the texel atlas by the divergence theorem.

use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::error::HydroError;

/// Texels per chunk of the deterministic parallel reductions.
pub(crate) const CHUNK: usize = 4096;

/// Volume moments of the solid bounded by the atlas, about its origin `o`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VolumeMoments {
    /// Reference point `o`, object space, m.
    pub origin: Point3<f64>,
    /// `∫ dV`, m³.
    pub volume: f64,
    /// `∫ (x − o) dV`, m⁴.
    pub first: Vector3<f64>,
    /// `∫ (x − o)(x − o)ᵀ dV`, m⁵.
    pub second: Matrix3<f64>,
}

/// Mass, centre of mass and inertia of a body, object frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MassProperties {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass, object space, m.
    pub center_of_mass: Point3<f64>,
    /// Inertia tensor about the centre of mass, object axes, kg·m².
    pub inertia: Matrix3<f64>,
}

/// Principal moments and axes of an inertia tensor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalInertia {
    /// Principal moments, kg·m², ascending.
    pub moments: Vector3<f64>,
    /// Rotation from the principal frame to the object frame.
    pub frame: UnitQuaternion<f64>,
}

impl MassProperties {
    /// Mass properties of a point mass `m` (kg) at `p` (m).
    pub fn point(mass: f64, p: Point3<f64>) -> Self {
        Self {
            mass,
            center_of_mass: p,
            inertia: Matrix3::zeros(),
        }
    }

    /// Mass properties of a body with no mass.
    pub fn zero() -> Self {
        Self::point(0.0, Point3::origin())
    }

    /// Inertia about another point `p` (m) by the parallel-axis theorem, kg·m².
    pub fn inertia_about(&self, p: &Point3<f64>) -> Matrix3<f64> {
        self.inertia + parallel_axis(self.mass, &(self.center_of_mass - p))
    }

    /// Combines two bodies rigidly attached (both in the same frame) about
    /// their common centre of mass.
    pub fn combine(&self, other: &Self) -> Self {
        let mass = self.mass + other.mass;
        if mass <= 0.0 {
            return Self::zero();
        }
        let c = Point3::from(
            (self.center_of_mass.coords * self.mass + other.center_of_mass.coords * other.mass) / mass,
        );
        Self {
            mass,
            center_of_mass: c,
            inertia: self.inertia_about(&c) + other.inertia_about(&c),
        }
    }

    /// Principal moments and axes (symmetric eigen decomposition), for
    /// handing to a physics engine. Tiny negative rounding is clamped to 0.
    pub fn principal(&self) -> PrincipalInertia {
        let sym = 0.5 * (self.inertia + self.inertia.transpose());
        let eig = sym.symmetric_eigen();
        let mut order = [0usize, 1, 2];
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let mut axes = Matrix3::from_columns(&[
            eig.eigenvectors.column(order[0]).into_owned(),
            eig.eigenvectors.column(order[1]).into_owned(),
            eig.eigenvectors.column(order[2]).into_owned(),
        ]);
        if axes.determinant() < 0.0 {
            axes.set_column(2, &(-axes.column(2)));
        }
        let rot = nalgebra::Rotation3::from_matrix_unchecked(axes);
        PrincipalInertia {
            moments: Vector3::new(
                eig.eigenvalues[order[0]].max(0.0),
                eig.eigenvalues[order[1]].max(0.0),
                eig.eigenvalues[order[2]].max(0.0),
            ),
            frame: UnitQuaternion::from_rotation_matrix(&rot),
        }
    }

    /// Whether every value is finite and the mass is non-negative.
    pub fn is_finite(&self) -> bool {
        self.mass.is_finite()
            && self.mass >= 0.0
            && self.center_of_mass.iter().all(|c| c.is_finite())
            && self.inertia.iter().all(|c| c.is_finite())
    }
}

/// `m (|d|² I − d dᵀ)`: the inertia of a point mass `m` at offset `d`.
pub fn parallel_axis(mass: f64, d: &Vector3<f64>) -> Matrix3<f64> {
    mass * (Matrix3::identity() * d.norm_squared() - d * d.transpose())
}

/// Inertia tensor `tr(S) I − S` of a second moment `S = ∫ x xᵀ dm`.
pub fn inertia_from_second_moment(s: &Matrix3<f64>) -> Matrix3<f64> {
    Matrix3::identity() * s.trace() - s
}

#[inline]
fn texel(atlas: &Atlas, i: usize) -> (Vector3<f64>, Vector3<f64>) {
    let x = atlas.local_positions().get(i);
    let a = atlas.area_vectors().get(i);
    (
        Vector3::new(x[0] as f64, x[1] as f64, x[2] as f64),
        Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64),
    )
}

/// Sums `f` over the texels in fixed chunks, in a fixed order: the result is
/// bit-identical for any thread count.
pub(crate) fn chunked_sum<T, F>(n: usize, zero: T, f: F) -> T
where
    T: Send + Sync + Copy + std::ops::Add<Output = T>,
    F: Fn(std::ops::Range<usize>) -> T + Sync,
{
    crate::parallel::par_map(n.div_ceil(CHUNK), |c| f(c * CHUNK..((c + 1) * CHUNK).min(n)))
        .into_iter()
        .fold(zero, |a, b| a + b)
}

#[derive(Clone, Copy)]
struct Sums([f64; 10]);

impl std::ops::Add for Sums {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        for k in 0..10 {
            self.0[k] += o.0[k];
        }
        self
    }
}

/// Volume moments of the solid bounded by the atlas (closed mesh), about
/// the atlas origin.
///
/// By the divergence theorem, with `x` a texel position relative to the
/// atlas origin `o` and `A` its area vector, the solid's volume integrals
/// are sums over texels (f64): `V = (1/3) Σ x·A`, `∫x dV = Σ (x²/2) A_x`
/// (and likewise y, z), `∫x² dV = Σ (x³/3) A_x`, `∫xy dV = Σ (x²y/2) A_x`,
/// `∫yz dV = Σ (y²z/2) A_y`, `∫zx dV = Σ (z²x/2) A_z`.
pub fn volume_moments(atlas: &Atlas) -> VolumeMoments {
    let s = chunked_sum(atlas.len(), Sums([0.0; 10]), |r| {
        let mut s = [0.0f64; 10];
        for i in r {
            let (x, a) = texel(atlas, i);
            s[0] += x.dot(&a);
            s[1] += 0.5 * x.x * x.x * a.x;
            s[2] += 0.5 * x.y * x.y * a.y;
            s[3] += 0.5 * x.z * x.z * a.z;
            s[4] += x.x * x.x * x.x * a.x;
            s[5] += x.y * x.y * x.y * a.y;
            s[6] += x.z * x.z * x.z * a.z;
            s[7] += 0.5 * x.x * x.x * x.y * a.x;
            s[8] += 0.5 * x.y * x.y * x.z * a.y;
            s[9] += 0.5 * x.z * x.z * x.x * a.z;
        }
        Sums(s)
    })
    .0;
    let (sxx, syy, szz) = (s[4] / 3.0, s[5] / 3.0, s[6] / 3.0);
    let (sxy, syz, szx) = (s[7], s[8], s[9]);
    VolumeMoments {
        origin: atlas.origin(),
        volume: s[0] / 3.0,
        first: Vector3::new(s[1], s[2], s[3]),
        second: Matrix3::new(sxx, sxy, szx, sxy, syy, syz, szx, syz, szz),
    }
}

impl VolumeMoments {
    /// Mass properties of the solid filled with uniform `density` (kg/m³).
    pub fn solid(&self, density: f64) -> MassProperties {
        let mass = density * self.volume;
        if self.volume <= 0.0 {
            return MassProperties::point(0.0, self.origin);
        }
        let c = self.first / self.volume;
        let io = inertia_from_second_moment(&(self.second * density));
        MassProperties {
            mass,
            center_of_mass: self.origin + c,
            inertia: io - parallel_axis(mass, &c),
        }
    }
}

/// How a body's mass is distributed.
///
/// Mass properties come from the texel atlas by the divergence theorem:
/// [`volume_moments`] for a solid, [`shell`] for a shell.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum MassModel {
    /// Uniform solid of the given density, kg/m³.
    Solid {
        /// Density, kg/m³.
        density: f64,
    },
    /// Mass on the surface with a uniform areal density, kg/m². A hollow body
    /// (its buoyancy comes from the enclosed volume all the same).
    Shell {
        /// Areal density, kg/m².
        areal_density: f64,
    },
    /// Mass on the surface with a per-texel areal density (kg/m², one value
    /// per atlas texel), e.g. from a texture that may change every frame.
    ShellTexture {
        /// Areal density per texel, kg/m².
        areal_density: Vec<f32>,
    },
    /// Thin walls of a material of `density` (kg/m³) and `thickness` (m):
    /// a shell of areal density `density × thickness`, the model of an open
    /// container's single-sided mesh (a bucket, a rowing boat). The walls'
    /// own volume is left out of the displacement (thin walls).
    Walls {
        /// Density of the wall material, kg/m³.
        density: f64,
        /// Wall thickness, m.
        thickness: f64,
    },
    /// Mass properties worked out elsewhere, object frame: e.g. the solid
    /// walls of a thick-walled container, from its own closed mesh, while
    /// its atlas is the filled shape ([`soak_bake::cap_cavities`]).
    Given {
        /// Mass (kg, > 0), centre of mass (m) and inertia about it (kg·m²);
        /// boxed, so the other models stay small.
        properties: Box<MassProperties>,
    },
}

impl MassModel {
    /// Mass properties of `atlas` under this model, object frame.
    pub fn mass_properties(&self, atlas: &Atlas) -> Result<MassProperties, HydroError> {
        match self {
            MassModel::Solid { density } => {
                check_density("solid", *density)?;
                if atlas.has_openings() {
                    return Err(HydroError::OpenSolid);
                }
                Ok(volume_moments(atlas).solid(*density))
            }
            MassModel::Shell { areal_density } => {
                check_density("areal", *areal_density)?;
                Ok(shell(atlas, |_| *areal_density))
            }
            MassModel::Walls { density, thickness } => {
                check_density("wall", *density)?;
                check_thickness(*thickness)?;
                Ok(shell(atlas, |_| density * thickness))
            }
            MassModel::Given { properties } => check_given(properties),
            MassModel::ShellTexture { areal_density } => {
                if areal_density.len() != atlas.len() {
                    return Err(HydroError::ChannelLength {
                        what: "areal density texture",
                        len: areal_density.len(),
                        texels: atlas.len(),
                    });
                }
                if let Some(texel) = areal_density.iter().position(|d| !(d.is_finite() && *d >= 0.0)) {
                    return Err(HydroError::ChannelValue {
                        what: "areal density",
                        texel,
                        value: areal_density[texel],
                    });
                }
                Ok(shell(atlas, |i| areal_density[i] as f64))
            }
        }
    }
}

pub(crate) fn check_given(p: &MassProperties) -> Result<MassProperties, HydroError> {
    if p.is_finite() && p.mass > 0.0 {
        Ok(*p)
    } else {
        Err(HydroError::GivenMass {
            properties: format!("{p:?}"),
        })
    }
}

pub(crate) fn check_thickness(value: f64) -> Result<(), HydroError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(HydroError::Thickness { value })
    }
}

fn check_density(what: &'static str, value: f64) -> Result<(), HydroError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(HydroError::Density { what, value })
    }
}

/// Thin-shell mass properties with areal density `sigma(i)` (kg/m²) at texel `i`.
///
/// A shell puts mass `σ_i a_i` at each texel (`a_i` its area); the caps of
/// an open mesh's atlas ([`Atlas::is_opening`]) carry none.
pub fn shell(atlas: &Atlas, sigma: impl Fn(usize) -> f64 + Sync) -> MassProperties {
    let s = chunked_sum(atlas.len(), Sums([0.0; 10]), |r| {
        let mut s = [0.0f64; 10];
        for i in r {
            if atlas.is_opening(i) {
                continue;
            }
            let (x, _) = texel(atlas, i);
            let m = sigma(i) * atlas.areas()[i] as f64;
            s[0] += m;
            s[1] += m * x.x;
            s[2] += m * x.y;
            s[3] += m * x.z;
            s[4] += m * x.x * x.x;
            s[5] += m * x.y * x.y;
            s[6] += m * x.z * x.z;
            s[7] += m * x.x * x.y;
            s[8] += m * x.y * x.z;
            s[9] += m * x.z * x.x;
        }
        Sums(s)
    })
    .0;
    let mass = s[0];
    let o = atlas.origin();
    if mass <= 0.0 {
        return MassProperties::point(0.0, o);
    }
    let c = Vector3::new(s[1], s[2], s[3]) / mass;
    let second = Matrix3::new(s[4], s[7], s[9], s[7], s[5], s[8], s[9], s[8], s[6]);
    MassProperties {
        mass,
        center_of_mass: o + c,
        inertia: inertia_from_second_moment(&second) - parallel_axis(mass, &c),
    }
}
