//! What to draw: a [`RenderScene`] of textured, wetting meshes with poses, a
//! camera, a sun and sky, optional water and force arrows.

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::Mesh;

use super::camera::Camera;
use super::subsurface::Subsurface;
use crate::wet_material::WetMaterial;

/// A liquid texture: W×H liquid saturations in `[0, 1]` laid over the mesh's
/// UV square, row 0 at the top (`v = 0`, glTF's convention, as
/// [`soak_bake::Atlas::sample_image`] reads images).
pub type LiquidImage = image::ImageBuffer<image::Luma<f32>, Vec<f32>>;

/// An object's dry diffuse albedo.
#[derive(Debug, Clone, PartialEq)]
pub enum Albedo {
    /// One linear RGB albedo, fractions in `[0, 1]`.
    Constant([f64; 3]),
    /// An sRGB-encoded RGBA8 image over the UV square (row 0 at `v = 0`),
    /// multiplied by `tint` (linear RGB in `[0, 1]`; alpha ignored).
    Texture {
        /// The image.
        image: Arc<image::RgbaImage>,
        /// Linear RGB factor in `[0, 1]`.
        tint: [f64; 3],
    },
}

impl Default for Albedo {
    /// A light grey, 0.5.
    fn default() -> Self {
        Albedo::Constant([0.5; 3])
    }
}

impl Albedo {
    /// A texture with no tint.
    pub fn texture(image: impl Into<Arc<image::RgbaImage>>) -> Self {
        Albedo::Texture {
            image: image.into(),
            tint: [1.0; 3],
        }
    }
}

/// One mesh in the scene.
#[derive(Debug, Clone)]
pub struct RenderObject {
    /// A name for error messages.
    pub name: String,
    /// The mesh, object space (normals are computed: smooth within
    /// [`RenderObject::crease_degrees`], hard across sharper edges).
    pub mesh: Arc<Mesh>,
    /// Object-to-world transform.
    pub pose: Isometry3<f64>,
    /// Dry albedo.
    pub albedo: Albedo,
    /// Liquid saturation over the UV square; `None` is dry.
    pub liquid: Option<Arc<LiquidImage>>,
    /// How the material looks as it wets.
    pub material: WetMaterial,
    /// A segment id per triangle, for [`DebugView::Segments`] (e.g. the
    /// liquid graph's segmentation); `None` colours each triangle apart.
    pub segments: Option<Arc<Vec<u32>>>,
    /// Largest angle between adjacent faces, in degrees, that is shaded
    /// smooth (default 50°).
    pub crease_degrees: f64,
    /// Whether the object casts shadows (default true).
    pub casts_shadow: bool,
    /// For an open container ([`Mesh::openings`]): the world height of the
    /// liquid's surface inside it, m, drawn as water where the plane cuts
    /// its walls; `None` when it holds none.
    pub inner_water: Option<f64>,
}

impl RenderObject {
    /// A dry object with a 0.5 grey albedo and clear-water material.
    pub fn new(mesh: impl Into<Arc<Mesh>>, pose: Isometry3<f64>) -> Self {
        let mesh = mesh.into();
        Self {
            name: mesh.name.clone(),
            mesh,
            pose,
            albedo: Albedo::default(),
            liquid: None,
            material: WetMaterial::default(),
            segments: None,
            crease_degrees: 50.0,
            casts_shadow: true,
            inner_water: None,
        }
    }

    /// With the liquid inside an open container standing at world height
    /// `level`, m (see [`RenderObject::inner_water`]).
    pub fn with_inner_water(mut self, level: f64) -> Self {
        self.inner_water = Some(level);
        self
    }

    /// With a name.
    pub fn with_name(mut self, name: impl Into<String>) -> Self {
        self.name = name.into();
        self
    }

    /// With an albedo.
    pub fn with_albedo(mut self, albedo: Albedo) -> Self {
        self.albedo = albedo;
        self
    }

    /// With a liquid texture.
    pub fn with_liquid(mut self, liquid: impl Into<Arc<LiquidImage>>) -> Self {
        self.liquid = Some(liquid.into());
        self
    }

    /// With a wet material.
    pub fn with_material(mut self, material: WetMaterial) -> Self {
        self.material = material;
        self
    }

    /// With per-triangle segment ids.
    pub fn with_segments(mut self, segments: impl Into<Arc<Vec<u32>>>) -> Self {
        self.segments = Some(segments.into());
        self
    }
}

/// A distant light (the sun).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionalLight {
    /// Unit vector from the scene towards the light (normalised when
    /// rendering).
    pub direction: Vector3<f64>,
    /// Irradiance on a surface facing the light, linear RGB in relative
    /// units (the image is `exposure ×` radiance).
    pub irradiance: [f64; 3],
}

impl Default for DirectionalLight {
    /// A warm sun 50° above the horizon, irradiance 2.6.
    fn default() -> Self {
        Self::from_angles(50.0, 35.0, [2.6, 2.45, 2.25])
    }
}

impl DirectionalLight {
    /// A light at `elevation_deg` above the horizon and `azimuth_deg` from
    /// +x towards +z, with the given irradiance.
    pub fn from_angles(elevation_deg: f64, azimuth_deg: f64, irradiance: [f64; 3]) -> Self {
        let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
        Self {
            direction: Vector3::new(e.cos() * a.cos(), e.sin(), e.cos() * a.sin()),
            irradiance,
        }
    }
}

/// The environment: a sky dome above the horizon and a uniform ground
/// below, as radiances (linear RGB, relative units). It lights every
/// surface (irradiance `π·mix(ground, sky mean, (1 + n_y)/2)`), is
/// reflected by wet films and water, and is the background.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Environment {
    /// Radiance straight up.
    pub zenith: [f64; 3],
    /// Radiance at the horizon (the sky blends as `√(d_y)` towards the zenith).
    pub horizon: [f64; 3],
    /// Radiance from below the horizon.
    pub ground: [f64; 3],
}

impl Default for Environment {
    /// A clear blue sky over a dim ground.
    fn default() -> Self {
        Self {
            zenith: [0.16, 0.26, 0.46],
            horizon: [0.42, 0.48, 0.55],
            ground: [0.12, 0.11, 0.10],
        }
    }
}

impl Environment {
    /// The same radiance in every direction: irradiance `π·radiance` on
    /// any surface.
    pub fn uniform(radiance: [f64; 3]) -> Self {
        Self {
            zenith: radiance,
            horizon: radiance,
            ground: radiance,
        }
    }

    /// Cosine-weighted mean radiance of the sky hemisphere:
    /// `horizon + 0.8 (zenith − horizon)` for the `√(d_y)` blend.
    pub fn sky_mean(&self) -> [f64; 3] {
        std::array::from_fn(|i| self.horizon[i] + 0.8 * (self.zenith[i] - self.horizon[i]))
    }
}

/// The water's shape.
#[derive(Debug, Clone, PartialEq)]
pub enum WaterShape {
    /// The horizontal plane `y = level` (m).
    Plane {
        /// Height, m.
        level: f64,
    },
    /// A Gerstner sea at time `time` (s), drawn as a displaced grid
    /// ([`soak_hydro::Gerstner::particle`]).
    Gerstner {
        /// The sea.
        sea: soak_hydro::Gerstner,
        /// Time, s.
        time: f64,
    },
    /// A spectral sea's tile evaluated at one time, drawn as a displaced
    /// grid repeating the tile ([`soak_hydro::SeaFields::particle_at`]:
    /// each vertex the surface particle at rest under it, choppy
    /// displacement and all).
    Spectral {
        /// The tile's fields (their time is the drawing's).
        fields: std::sync::Arc<soak_hydro::SeaFields>,
    },
    /// Interactive waves (the waves bodies make,
    /// [`soak_hydro::InteractiveWaves::snapshot`]) on `base`, a plane or a
    /// sea: the base's grid raised by the waves' elevation, drawn at least
    /// [`INTERACTIVE_RESOLUTION`] vertices a side so that a wake shows.
    Interactive {
        /// The water under the waves.
        base: Box<WaterShape>,
        /// The waves' elevation.
        waves: soak_hydro::WaveHeights,
    },
}

/// The fewest grid vertices a side [`WaterShape::Interactive`] is drawn
/// with (the grid is finest round the camera's target: about 4 cm apart
/// there and 20 cm half-way out at the default extent).
pub const INTERACTIVE_RESOLUTION: u32 = 512;

/// The water surface: shape and look. Fresnel-shaded (reflects the sky and
/// the sun), semi-transparent (objects below show through, darkened).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderWater {
    /// Plane or waves.
    pub shape: WaterShape,
    /// Scattering colour of the water body, linear RGB in `[0, 1]`.
    pub colour: [f64; 3],
    /// Opacity of the water body seen at normal incidence, `[0, 1]`
    /// (Fresnel reflection adds to it at grazing angles).
    pub opacity: f64,
    /// Refractive index relative to air (water: 1.333).
    pub refractive_index: f64,
    /// Perceptual roughness of the surface for the sun's glint, `[0, 1]`.
    pub roughness: f64,
    /// Half side of the square of water drawn around the camera target, m.
    pub extent: f64,
    /// Grid vertices per side (a moving sea), spaced finer near the centre.
    pub resolution: u32,
}

impl RenderWater {
    /// Still water at `level` (m) with the default look.
    pub fn plane(level: f64) -> Self {
        Self::with_shape(WaterShape::Plane { level })
    }

    /// A Gerstner sea at time `time` (s) with the default look.
    pub fn gerstner(sea: soak_hydro::Gerstner, time: f64) -> Self {
        Self::with_shape(WaterShape::Gerstner { sea, time })
    }

    /// A spectral sea's tile evaluated at one time
    /// ([`soak_hydro::SpectralSea::fields`]) with the default look.
    pub fn spectral(fields: std::sync::Arc<soak_hydro::SeaFields>) -> Self {
        Self::with_shape(WaterShape::Spectral { fields })
    }

    /// The same water with interactive waves on it (see
    /// [`WaterShape::Interactive`]).
    pub fn with_waves(mut self, waves: soak_hydro::WaveHeights) -> Self {
        self.shape = WaterShape::Interactive {
            base: Box::new(self.shape),
            waves,
        };
        self.resolution = self.resolution.max(INTERACTIVE_RESOLUTION);
        self
    }

    fn with_shape(shape: WaterShape) -> Self {
        Self {
            shape,
            colour: [0.03, 0.12, 0.14],
            opacity: 0.72,
            refractive_index: 1.333,
            roughness: 0.18,
            extent: 160.0,
            resolution: 128,
        }
    }
}

/// A force (or any vector) drawn as a 3-D arrow on top of the scene, as the
/// thesis' Fig. 7.3 draws weight (red) and buoyancy (green).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arrow {
    /// Tail, world, m.
    pub origin: Point3<f64>,
    /// Tail to tip, world, m (scale forces to lengths first).
    pub vector: Vector3<f64>,
    /// Linear RGB colour.
    pub colour: [f64; 3],
    /// Shaft radius, m; the head is 2.2 times wider.
    pub radius: f64,
}

impl Arrow {
    /// Red, for a weight.
    pub const WEIGHT_COLOUR: [f64; 3] = [0.85, 0.06, 0.04];
    /// Green, for buoyancy.
    pub const BUOYANCY_COLOUR: [f64; 3] = [0.08, 0.75, 0.10];

    /// An arrow from `origin` along `vector` with a shaft radius of 3 % of
    /// its length (at least 1 cm).
    pub fn new(origin: Point3<f64>, vector: Vector3<f64>, colour: [f64; 3]) -> Self {
        Self {
            origin,
            vector,
            colour,
            radius: (0.03 * vector.norm()).max(0.01),
        }
    }

    /// A force `force` (N) applied at `point`, drawn `metres_per_newton`
    /// long per newton.
    pub fn force(point: Point3<f64>, force: Vector3<f64>, metres_per_newton: f64, colour: [f64; 3]) -> Self {
        Self::new(point, force * metres_per_newton, colour)
    }

    /// A weight (red) at the centre of mass.
    pub fn weight(center_of_mass: Point3<f64>, force: Vector3<f64>, metres_per_newton: f64) -> Self {
        Self::force(center_of_mass, force, metres_per_newton, Self::WEIGHT_COLOUR)
    }

    /// A buoyancy (green) at the centre of buoyancy.
    pub fn buoyancy(center_of_buoyancy: Point3<f64>, force: Vector3<f64>, metres_per_newton: f64) -> Self {
        Self::force(
            center_of_buoyancy,
            force,
            metres_per_newton,
            Self::BUOYANCY_COLOUR,
        )
    }

    /// With a shaft radius, m.
    pub fn with_radius(mut self, radius: f64) -> Self {
        self.radius = radius;
        self
    }
}

/// What the image shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum DebugView {
    /// The shaded scene.
    #[default]
    Shaded,
    /// Each object's liquid saturation in pseudo-colour (blue dry, red
    /// saturated; thesis Fig. 7.14, right column), with a little shading
    /// to show the shape.
    Liquid,
    /// Each segment (or triangle) in its own colour.
    Segments,
    /// World-space normals as colours (`0.5 + 0.5 n`).
    Normals,
}

/// How linear radiance becomes an 8-bit sRGB pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum ToneMap {
    /// Khronos PBR Neutral: colours below ≈ 0.76 pass almost unchanged,
    /// highlights roll off without hue shifts.
    #[default]
    Neutral,
    /// `exposure × radiance`, clamped to `[0, 1]`: pixel values are linear
    /// in radiance (for measurements).
    Linear,
}

/// Everything one frame needs.
///
/// Plain data: a scene file, a simulation or a demo fills these in and
/// hands them to [`Renderer::render`](super::Renderer::render). Colours are
/// linear RGB unless a field says otherwise; lengths are metres in the
/// world frame (y up).
#[derive(Debug, Clone)]
pub struct RenderScene {
    /// The eye.
    pub camera: Camera,
    /// The sun.
    pub light: DirectionalLight,
    /// Sky and ground.
    pub environment: Environment,
    /// Water, if any.
    pub water: Option<RenderWater>,
    /// The meshes.
    pub objects: Vec<RenderObject>,
    /// Arrows drawn on top.
    pub arrows: Vec<Arrow>,
    /// What to show.
    pub view: DebugView,
    /// Factor on radiance before tone mapping.
    pub exposure: f64,
    /// Tone mapping.
    pub tone_map: ToneMap,
    /// Whether ±½ LSB of ordered noise is added before 8-bit quantisation
    /// (removes banding in smooth gradients; default true).
    pub dither: bool,
    /// Whether objects cast shadows from the sun (shadow map; default true).
    pub shadows: bool,
    /// Texture-space subsurface scattering of the wet term; `None` (the
    /// default) shades every texel locally.
    pub subsurface: Option<Subsurface>,
}

impl RenderScene {
    /// An empty scene seen by `camera`, default sun and sky.
    pub fn new(camera: Camera) -> Self {
        Self {
            camera,
            light: DirectionalLight::default(),
            environment: Environment::default(),
            water: None,
            objects: Vec::new(),
            arrows: Vec::new(),
            view: DebugView::Shaded,
            exposure: 1.0,
            tone_map: ToneMap::Neutral,
            dither: true,
            shadows: true,
            subsurface: None,
        }
    }
}
