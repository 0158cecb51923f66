//! A run as an animated glTF 2.0 binary (`.glb`), for Blender or any glTF
//! viewer: each body a node with its mesh, its translation and rotation
//! sampled at the recorded times (linear interpolation between them).
//!
//! Record poses as a run goes ([`Recording::push`], from the poses Rapier
//! hands back) or take a [`Simulation`](crate::Simulation)'s recorded
//! samples ([`Recording::from_samples`]), then write the file:
//!
//! ```
//! use rapier3d::prelude::*;
//! use soak_bake::builtin;
//! use soak_rapier::export::Recording;
//!
//! let mut run = Recording::new();
//! let crate_ = run.add_body("crate", builtin::cuboid(1.0, 0.6, 0.8));
//! for k in 0..=60 {
//!     let t = k as f64 / 60.0;
//!     let pose = Pose::from_translation(Vector::new(0.0, -0.1 * t as f32, 0.0));
//!     run.push(crate_, t, &pose)?;
//! }
//! let glb: Vec<u8> = run.to_glb();
//! assert_eq!(&glb[..4], b"glTF");
//! # Ok::<(), soak_rapier::export::ExportError>(())
//! ```
//!
//! The meshes are written as they are given (f32 positions, triangles; no
//! normals, which a viewer then computes flat, as the glTF specification
//! asks). The liquid soaked into a wet body's surface can go with it
//! ([`Recording::set_liquid`], per vertex, e.g. from [`vertex_fill`]):
//! as vertex colours (`COLOR_0`, [`liquid_colour`]: light grey where dry
//! to dark blue where saturated, linear in the fill fraction, so the
//! fraction reads back from the red channel). It is one state, the last
//! one: glTF animates nodes and morph weights,
//! not vertex colours or textures. The liquid inside a hull is not
//! written.

use std::io::Write;

use rapier3d::math::Pose;
use serde_json::{Value, json};
use soak_bake::{Atlas, Mesh};

/// What an export refuses.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A body index [`Recording::add_body`] did not return.
    #[error("no body {0} in the recording")]
    UnknownBody(usize),
    /// A time not after the body's last one, or not finite.
    #[error("body `{body}`: time {t} s is not after its last sample ({last} s)")]
    Time {
        /// The body's name.
        body: String,
        /// The time pushed, s.
        t: f64,
        /// The last time recorded, s.
        last: f64,
    },
    /// A pose with a coordinate that is not a number.
    #[error("body `{body}`: a pose at t = {t} s is not finite")]
    Pose {
        /// The body's name.
        body: String,
        /// The time pushed, s.
        t: f64,
    },
    /// Liquid for a number of vertices other than the body's mesh has, or
    /// a fill fraction outside `[0, 1]`.
    #[error("body `{body}`: {message}")]
    Liquid {
        /// The body's name.
        body: String,
        /// What is wrong.
        message: String,
    },
    /// Writing the file.
    #[error("writing the glTF file: {0}")]
    Io(#[from] std::io::Error),
}

/// One body's mesh and its sampled poses.
#[derive(Clone, Debug)]
struct Track {
    name: String,
    mesh: Mesh,
    times: Vec<f32>,
    translations: Vec<[f32; 3]>,
    rotations: Vec<[f32; 4]>,
    /// Fill fraction per vertex, where the body is wet.
    liquid: Option<Vec<f32>>,
}

/// Bodies, their meshes and their poses over time: an animated glTF scene.
#[derive(Clone, Debug, Default)]
pub struct Recording {
    tracks: Vec<Track>,
}

impl Recording {
    /// An empty recording.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a body drawn with `mesh` (its own frame, m, as Rapier's body
    /// frame); returns its index for [`Recording::push`].
    pub fn add_body(&mut self, name: impl Into<String>, mesh: Mesh) -> usize {
        self.tracks.push(Track {
            name: name.into(),
            mesh,
            times: Vec::new(),
            translations: Vec::new(),
            rotations: Vec::new(),
            liquid: None,
        });
        self.tracks.len() - 1
    }

    /// Gives body `body` the liquid soaked into its surface: `fill`, the
    /// fraction of saturation in `[0, 1]` at each vertex of its mesh (see
    /// [`vertex_fill`]).
    ///
    /// # Errors
    /// An unknown body, a length other than the mesh's vertex count, a
    /// fraction outside `[0, 1]`.
    pub fn set_liquid(&mut self, body: usize, fill: Vec<f32>) -> Result<(), ExportError> {
        let track = self.tracks.get_mut(body).ok_or(ExportError::UnknownBody(body))?;
        let wrong = |message: String| ExportError::Liquid {
            body: track.name.clone(),
            message,
        };
        if fill.len() != track.mesh.positions.len() {
            return Err(wrong(format!(
                "liquid for {} vertices, the mesh has {}",
                fill.len(),
                track.mesh.positions.len()
            )));
        }
        if let Some((i, f)) = fill.iter().enumerate().find(|(_, f)| !(0.0..=1.0).contains(*f)) {
            return Err(wrong(format!("vertex {i}: fill fraction {f} is not in [0, 1]")));
        }
        track.liquid = Some(fill);
        Ok(())
    }

    /// Records body `body`'s pose at time `t` (s, after its last sample):
    /// Rapier's [`Pose`] (glam, f32), as a rigid body hands it back
    /// (`world.bodies[handle].position()`); [`crate::convert::to_pose`]
    /// makes one from soak's f64 isometry.
    ///
    /// # Errors
    /// An unknown body, a time not after the last one, a pose that is not
    /// finite.
    pub fn push(&mut self, body: usize, t: f64, pose: &Pose) -> Result<(), ExportError> {
        let track = self.tracks.get_mut(body).ok_or(ExportError::UnknownBody(body))?;
        let last = track.times.last().map_or(f64::NEG_INFINITY, |&l| f64::from(l));
        if !(t.is_finite() && t as f32 > last as f32) {
            return Err(ExportError::Time {
                body: track.name.clone(),
                t,
                last,
            });
        }
        let (p, q) = (pose.translation, pose.rotation);
        let (translation, rotation) = ([p.x, p.y, p.z], [q.x, q.y, q.z, q.w]);
        if !translation.iter().chain(&rotation).all(|v| v.is_finite()) {
            return Err(ExportError::Pose {
                body: track.name.clone(),
                t,
            });
        }
        track.times.push(t as f32);
        track.translations.push(translation);
        track.rotations.push(rotation);
        Ok(())
    }

    /// The recording of a [`Simulation`](crate::Simulation)'s samples
    /// ([`Simulation::samples`](crate::Simulation::samples)), the bodies
    /// drawn with `meshes` (one per body of the scene, in its order).
    ///
    /// # Errors
    /// As [`Recording::push`]: samples out of order or not finite.
    pub fn from_samples(
        names: &[String],
        meshes: Vec<Mesh>,
        samples: &[crate::Sample],
    ) -> Result<Self, ExportError> {
        let mut run = Self::new();
        for (name, mesh) in names.iter().zip(meshes) {
            run.add_body(name.clone(), mesh);
        }
        for s in samples {
            let [x, y, z] = s.position.map(|v| v as f32);
            let [qx, qy, qz, qw] = s.rotation.map(|v| v as f32);
            let pose = Pose::from_parts(
                rapier3d::math::Vector::new(x, y, z),
                rapier3d::math::Rotation::from_xyzw(qx, qy, qz, qw),
            );
            run.push(s.body, s.t, &pose)?;
        }
        Ok(run)
    }

    /// The number of bodies.
    pub fn len(&self) -> usize {
        self.tracks.len()
    }

    /// Whether there is no body.
    pub fn is_empty(&self) -> bool {
        self.tracks.is_empty()
    }

    /// The glTF binary (`.glb`) of the recording.
    pub fn to_glb(&self) -> Vec<u8> {
        let mut bin = Vec::new();
        let mut views = Vec::new();
        let mut accessors = Vec::new();
        // Appends `bytes` as a buffer view (4-byte aligned) and an accessor
        // of `count` elements of `kind`; returns the accessor's index.
        let mut add = |bytes: Vec<u8>, component: u32, count: usize, kind: &str, extra: Value| {
            while !bin.len().is_multiple_of(4) {
                bin.push(0);
            }
            views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len()}));
            bin.extend_from_slice(&bytes);
            let mut accessor = json!({
                "bufferView": views.len() - 1,
                "componentType": component,
                "count": count,
                "type": kind,
            });
            if let (Value::Object(a), Value::Object(e)) = (&mut accessor, extra) {
                a.extend(e);
            }
            accessors.push(accessor);
            accessors.len() - 1
        };
        const FLOAT: u32 = 5126;
        const UNSIGNED_INT: u32 = 5125;
        let floats = |v: &mut dyn Iterator<Item = f32>| v.flat_map(f32::to_le_bytes).collect::<Vec<u8>>();

        let (mut meshes, mut nodes, mut channels, mut samplers) = (vec![], vec![], vec![], vec![]);
        for (i, track) in self.tracks.iter().enumerate() {
            let positions: Vec<[f32; 3]> = track
                .mesh
                .positions
                .iter()
                .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                .collect();
            let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
            for p in &positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            let position = add(
                floats(&mut positions.iter().flatten().copied()),
                FLOAT,
                positions.len(),
                "VEC3",
                json!({"min": lo, "max": hi}),
            );
            let indices: Vec<u8> = track
                .mesh
                .triangles
                .iter()
                .flatten()
                .flat_map(|i| i.to_le_bytes())
                .collect();
            let indices = add(
                indices,
                UNSIGNED_INT,
                3 * track.mesh.triangles.len(),
                "SCALAR",
                json!({}),
            );
            let mut attributes = json!({"POSITION": position});
            if let Some(fill) = &track.liquid {
                let colours: Vec<[f32; 4]> = fill.iter().map(|&f| liquid_colour(f)).collect();
                attributes["COLOR_0"] = json!(add(
                    floats(&mut colours.iter().flatten().copied()),
                    FLOAT,
                    colours.len(),
                    "VEC4",
                    json!({}),
                ));
            }
            meshes.push(json!({
                "name": track.mesh.name,
                "primitives": [{"attributes": attributes, "indices": indices, "mode": 4}],
            }));
            let mut node = json!({"name": track.name, "mesh": i});
            if let (Some(t), Some(r)) = (track.translations.first(), track.rotations.first()) {
                node["translation"] = json!(t);
                node["rotation"] = json!(r);
            }
            nodes.push(node);
            if track.times.is_empty() {
                continue;
            }
            let (t0, t1) = (track.times[0], track.times[track.times.len() - 1]);
            let input = add(
                floats(&mut track.times.iter().copied()),
                FLOAT,
                track.times.len(),
                "SCALAR",
                json!({"min": [t0], "max": [t1]}),
            );
            let translations = floats(&mut track.translations.iter().flatten().copied());
            let rotations = floats(&mut track.rotations.iter().flatten().copied());
            for (path, values, kind) in [
                ("translation", translations, "VEC3"),
                ("rotation", rotations, "VEC4"),
            ] {
                let output = add(values, FLOAT, track.times.len(), kind, json!({}));
                samplers.push(json!({"input": input, "output": output, "interpolation": "LINEAR"}));
                channels.push(json!({"sampler": samplers.len() - 1, "target": {"node": i, "path": path}}));
            }
        }
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let mut gltf = json!({
            "asset": {"version": "2.0", "generator": "soak"},
            "scene": 0,
            "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
            "nodes": nodes,
            "meshes": meshes,
            "accessors": accessors,
            "bufferViews": views,
            "buffers": [{"byteLength": bin.len()}],
        });
        if !channels.is_empty() {
            gltf["animations"] = json!([{"name": "soak run", "channels": channels, "samplers": samplers}]);
        }
        let mut text = serde_json::to_vec(&gltf).expect("a JSON value serialises");
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let total = 12 + 8 + text.len() + 8 + bin.len();
        let mut glb = Vec::with_capacity(total);
        let word = |v: usize| u32::try_from(v).expect("a glTF binary under 4 GiB").to_le_bytes();
        glb.extend_from_slice(b"glTF");
        glb.extend_from_slice(&2u32.to_le_bytes());
        glb.extend_from_slice(&word(total));
        glb.extend_from_slice(&word(text.len()));
        glb.extend_from_slice(b"JSON");
        glb.extend_from_slice(&text);
        glb.extend_from_slice(&word(bin.len()));
        glb.extend_from_slice(b"BIN\0");
        glb.extend_from_slice(&bin);
        glb
    }

    /// Writes the glTF binary to `out`.
    ///
    /// # Errors
    /// Writing.
    pub fn write_glb(&self, mut out: impl Write) -> Result<(), ExportError> {
        out.write_all(&self.to_glb())?;
        out.flush()?;
        Ok(())
    }
}

/// The vertex colour of a fill fraction `f`: linear RGBA from a light grey
/// (dry, 0.8 in each channel) to a dark blue (saturated; red 0.05), so
/// `f = (0.8 − r) / 0.75`.
pub fn liquid_colour(f: f32) -> [f32; 4] {
    let f = f.clamp(0.0, 1.0);
    let mix = |dry: f32, wet: f32| dry + f * (wet - dry);
    [mix(0.8, 0.05), mix(0.8, 0.15), mix(0.8, 0.6), 1.0]
}

/// The fill fraction (liquid over `saturation`, clamped to `[0, 1]`) at
/// each vertex of the mesh `atlas` was baked from, from `liquid`, the
/// liquid per texel in atlas order (m, as
/// [`SoakBody::liquid`](crate::SoakBody::liquid) gives it): each texel
/// weighs on its triangle's three vertices by its area times its
/// barycentric coordinate; a vertex no texel weighs on takes the mean of
/// its triangles' other vertices, and is dry if none has any.
pub fn vertex_fill(atlas: &Atlas, liquid: &[f64], saturation: f64) -> Vec<f32> {
    let n = atlas.vertex_count();
    let (mut sum, mut weight) = (vec![0.0f64; n], vec![0.0f64; n]);
    let triangles = atlas.triangles();
    for (((&t, b), &area), &h) in atlas
        .triangle_ids()
        .iter()
        .zip(atlas.barycentrics())
        .zip(atlas.areas())
        .zip(liquid)
    {
        let Some(tri) = triangles.get(t as usize) else {
            continue;
        };
        let f = if saturation > 0.0 {
            (h / saturation).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (l1, l2) = (f64::from(b[0]), f64::from(b[1]));
        for (&v, l) in tri.iter().zip([1.0 - l1 - l2, l1, l2]) {
            let w = f64::from(area) * l.max(0.0);
            if let (Some(s), Some(wv)) = (sum.get_mut(v as usize), weight.get_mut(v as usize)) {
                *s += w * f;
                *wv += w;
            }
        }
    }
    let own: Vec<Option<f64>> = sum
        .iter()
        .zip(&weight)
        .map(|(s, w)| (*w > 0.0).then(|| (s / w).clamp(0.0, 1.0)))
        .collect();
    // A vertex no texel weighs on (a pole, a corner of triangles too small
    // for a texel) takes the mean of its triangles' other vertices'.
    let (mut near, mut count) = (vec![0.0f64; n], vec![0u32; n]);
    for tri in triangles {
        for &v in tri {
            if own.get(v as usize).is_some_and(Option::is_none) {
                for &o in tri {
                    if let Some(Some(f)) = own.get(o as usize) {
                        near[v as usize] += f;
                        count[v as usize] += 1;
                    }
                }
            }
        }
    }
    own.iter()
        .enumerate()
        .map(|(v, f)| match f {
            Some(f) => *f as f32,
            None if count[v] > 0 => (near[v] / f64::from(count[v])) as f32,
            None => 0.0,
        })
        .collect()
}
