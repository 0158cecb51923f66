//! A Bevy mesh as a soak mesh, and the bake of a soak mesh into an atlas
//! (off the main thread).

use std::sync::Arc;

use bevy::mesh::{Indices, PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::Mesh;
use nalgebra::{Point2, Point3};
use soak_bake::{Atlas, BakeOptions, UnwrapOptions};

use crate::error::FloatingErrorKind;

/// A Bevy triangle mesh (positions, first UV channel, triangles) as a
/// soak mesh named `name`.
pub(crate) fn soak_mesh(name: &str, mesh: &Mesh) -> Result<soak_bake::Mesh, FloatingErrorKind> {
    let bad = |reason: String| FloatingErrorKind::MeshAsset {
        name: name.to_string(),
        reason,
    };
    if mesh.primitive_topology() != PrimitiveTopology::TriangleList {
        return Err(bad(format!(
            "its topology is {:?}, not a triangle list",
            mesh.primitive_topology()
        )));
    }
    let positions: Vec<Point3<f64>> = match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => p
            .iter()
            .map(|v| Point3::new(v[0] as f64, v[1] as f64, v[2] as f64))
            .collect(),
        Some(other) => {
            return Err(bad(format!(
                "its positions are {:?}, not Float32x3",
                other.enum_variant_name()
            )));
        }
        None => return Err(bad("it has no positions".into())),
    };
    let uvs = match mesh.attribute(Mesh::ATTRIBUTE_UV_0) {
        Some(VertexAttributeValues::Float32x2(uv)) if uv.len() == positions.len() => {
            Some(uv.iter().map(|v| Point2::new(v[0] as f64, v[1] as f64)).collect())
        }
        _ => None,
    };
    let n = positions.len();
    let indices: Vec<u32> = match mesh.indices() {
        Some(Indices::U16(i)) => i.iter().map(|&i| i as u32).collect(),
        Some(Indices::U32(i)) => i.clone(),
        None => (0..n as u32).collect(),
    };
    if !indices.len().is_multiple_of(3) {
        return Err(bad(format!(
            "{} indices is not a whole number of triangles",
            indices.len()
        )));
    }
    if let Some((k, &i)) = indices.iter().enumerate().find(|&(_, &i)| i as usize >= n) {
        return Err(bad(format!("index {k} is vertex {i}, past its {n} vertices")));
    }
    let triangles = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    Ok(soak_bake::Mesh::new(name, positions, uvs, triangles))
}

/// Bakes `mesh` into an atlas `resolution` texels a side: its own UVs if
/// they make a valid atlas, else an unwrapped one.
pub(crate) fn bake(
    name: &str,
    mesh: &soak_bake::Mesh,
    resolution: u32,
) -> Result<Arc<Atlas>, FloatingErrorKind> {
    let mesh_error = |source| FloatingErrorKind::Mesh {
        name: name.to_string(),
        source,
    };
    soak_bake::validate_topology(mesh).map_err(mesh_error)?;
    let unwrapped;
    let mesh = if soak_bake::validate_uvs(mesh).is_ok() {
        mesh
    } else {
        unwrapped = soak_bake::unwrap(mesh, UnwrapOptions::default())
            .map_err(mesh_error)?
            .0;
        &unwrapped
    };
    Atlas::bake(mesh, BakeOptions::square(resolution))
        .map(Arc::new)
        .map_err(|source| FloatingErrorKind::Bake {
            name: name.to_string(),
            source,
        })
}
