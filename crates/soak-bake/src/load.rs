//! Loading meshes from Wavefront OBJ, glTF 2.0 (`.gltf`, `.glb`) and `builtin:` names.
//!
//! The UV convention is described on [`load_mesh`].

use std::io::BufRead;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix4, Point2, Point3};

use crate::builtin;
use crate::error::LoadError;
use crate::mesh::{Mesh, SourceNumbering};

/// Loads a mesh from a file path (`.obj`, `.gltf`, `.glb`) or a `builtin:` name.
///
/// The mesh is returned as stored; validate it (or bake it, which validates)
/// before use. Several objects or primitives in one file are merged, with
/// glTF node transforms applied.
///
/// UVs follow glTF's convention everywhere in soak: `(0, 0)` is the top-left
/// corner of an image and `v` grows downwards. OBJ's `v` (which grows
/// upwards) is flipped on load, so painted textures line up for both formats.
pub fn load_mesh(source: &str) -> Result<Mesh, LoadError> {
    if source.starts_with("builtin:") {
        return builtin::parse(source);
    }
    let path = Path::new(source);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => {
            let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
                path: path.to_path_buf(),
                source,
            })?;
            load_obj_bytes(&bytes, path)
        }
        Some("gltf" | "glb") => {
            let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
                path: path.to_path_buf(),
                source,
            })?;
            load_gltf_bytes(&bytes, path, path.parent())
        }
        _ => Err(LoadError::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

fn name_of(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Parses Wavefront OBJ text. `path` names the mesh in messages; material
/// libraries are not read. Polygons are triangulated; `v` is flipped to soak's
/// UV convention (see [`load_mesh`]).
pub fn load_obj_bytes(bytes: &[u8], path: &Path) -> Result<Mesh, LoadError> {
    // A position that is not finite, named as the file numbers it (its
    // line, and its vertex as faces count them from 1): the parser reads
    // `nan` and `inf` as numbers, and the mesh it builds renumbers the
    // vertices.
    //
    // The same pass records the file's numbering for later messages: the
    // first vertex number at each position (as the parser reads it, f32),
    // and each face's line once per triangle it makes.
    let mut vertex = 0usize;
    let mut file_vertex: std::collections::HashMap<[u32; 3], u32> = std::collections::HashMap::new();
    let mut face_lines: Vec<u32> = Vec::new();
    for (line_no, line) in bytes.lines().enumerate() {
        let Ok(line) = line else { break };
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {}
            Some("f") => {
                let corners = words.count();
                face_lines.extend(std::iter::repeat_n(line_no as u32 + 1, corners.saturating_sub(2)));
                continue;
            }
            _ => continue,
        }
        vertex += 1;
        let xyz: Vec<f32> = words
            .clone()
            .take(3)
            .filter_map(|w| w.parse::<f32>().ok())
            .collect();
        if let [x, y, z] = xyz[..] {
            file_vertex
                .entry([x.to_bits(), y.to_bits(), z.to_bits()])
                .or_insert(vertex as u32);
        }
        if words
            .take(3)
            .any(|w| w.parse::<f64>().is_ok_and(|x| !x.is_finite()))
        {
            return Err(LoadError::Obj {
                path: path.to_path_buf(),
                reason: format!(
                    "line {}: vertex {vertex} `{}` is not a finite position",
                    line_no + 1,
                    line.trim()
                ),
            });
        }
    }
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &opts, |_| {
        Err(tobj::LoadError::GenericFailure)
    })
    .map_err(|e| LoadError::Obj {
        path: path.to_path_buf(),
        reason: diagnose_obj(bytes, &e),
    })?;
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    let mut all_uvs = true;
    let mut triangles = Vec::new();
    let mut vertices = Vec::new();
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        let n = m.positions.len() / 3;
        for k in 0..n {
            let key = [0, 1, 2].map(|i| m.positions[3 * k + i].to_bits());
            vertices.push(file_vertex.get(&key).copied().unwrap_or(0));
            positions.push(Point3::new(
                m.positions[3 * k] as f64,
                m.positions[3 * k + 1] as f64,
                m.positions[3 * k + 2] as f64,
            ));
        }
        if m.texcoords.len() == 2 * n && n > 0 {
            for k in 0..n {
                uvs.push(Point2::new(
                    m.texcoords[2 * k] as f64,
                    1.0 - m.texcoords[2 * k + 1] as f64,
                ));
            }
        } else {
            all_uvs = false;
        }
        for t in m.indices.chunks(3) {
            if t.len() == 3 {
                triangles.push([base + t[0], base + t[1], base + t[2]]);
            }
        }
    }
    if triangles.is_empty() {
        return Err(LoadError::Obj {
            path: path.to_path_buf(),
            reason: "no faces".into(),
        });
    }
    let triangle_count = triangles.len();
    let mut mesh = Mesh::new(name_of(path), positions, all_uvs.then_some(uvs), triangles);
    // Faces the parser skipped or split otherwise than `n − 2` would shift
    // every line after them: then no numbering rather than a wrong one.
    if face_lines.len() == triangle_count {
        mesh.source = Some(SourceNumbering { vertices, face_lines });
    }
    Ok(mesh)
}

/// Finds the line behind an OBJ parser error, so the message names it.
fn diagnose_obj(bytes: &[u8], err: &tobj::LoadError) -> String {
    let (mut nv, mut nvt, mut nvn) = (0i64, 0i64, 0i64);
    for (line_no, line) in bytes.lines().enumerate() {
        let Ok(line) = line else {
            return format!("{err} (line {} is not UTF-8)", line_no + 1);
        };
        let mut words = line.split_whitespace();
        let tag = words.next().unwrap_or("");
        let line_no = line_no + 1;
        let numbers_ok = |w: std::str::SplitWhitespace<'_>| w.take(3).all(|x| x.parse::<f32>().is_ok());
        match tag {
            "v" => {
                if !numbers_ok(words.clone()) || words.clone().count() < 3 {
                    return format!("line {line_no}: vertex position `{line}` is not three numbers");
                }
                nv += 1;
            }
            "vt" => {
                if !numbers_ok(words.clone()) || words.clone().count() < 1 {
                    return format!("line {line_no}: texture coordinate `{line}` is not numbers");
                }
                nvt += 1;
            }
            "vn" => nvn += 1,
            "f" => {
                let corners: Vec<&str> = words.collect();
                if corners.len() < 3 {
                    return format!("line {line_no}: face `{line}` has fewer than 3 corners");
                }
                for c in corners {
                    for (k, (idx, count, what)) in c
                        .split('/')
                        .zip([(nv, "vertex"), (nvt, "texture coordinate"), (nvn, "normal")])
                        .map(|(s, (n, w))| (s, n, w))
                        .enumerate()
                    {
                        if idx.is_empty() && k > 0 {
                            continue;
                        }
                        let Ok(i) = idx.parse::<i64>() else {
                            return format!("line {line_no}: face corner `{c}` is not a valid index");
                        };
                        let resolved = if i < 0 { count + i + 1 } else { i };
                        if resolved < 1 || resolved > count {
                            return format!(
                                "line {line_no}: face refers to {what} {i}, but only {count} are defined before it"
                            );
                        }
                    }
                }
            }
            _ => {}
        }
    }
    format!("{err}")
}

/// Parses a glTF 2.0 file (`.gltf` JSON or `.glb` binary). External buffers
/// are resolved against `base`. Triangles of every primitive in the default
/// scene are merged, node transforms applied; the first texture coordinate set
/// is used if every primitive has one.
pub fn load_gltf_bytes(bytes: &[u8], path: &Path, base: Option<&Path>) -> Result<Mesh, LoadError> {
    let gerr = |reason: String| LoadError::Gltf {
        path: path.to_path_buf(),
        reason,
    };
    let gltf = parse_gltf(bytes, path)?;
    let buffers = gltf::import_buffers(&gltf.document, base, gltf.blob.clone())
        .map_err(|e| gerr(format!("cannot load buffers: {e}")))?;
    let doc = &gltf.document;
    let mut out = GltfOut::default();
    let roots: Vec<(gltf::Node<'_>, Matrix4<f64>)> = match doc.default_scene().or_else(|| doc.scenes().next())
    {
        Some(scene) => scene.nodes().map(|n| (n, Matrix4::identity())).collect(),
        None => Vec::new(),
    };
    if roots.is_empty() {
        for mesh in doc.meshes() {
            read_gltf_mesh(&mesh, &Matrix4::identity(), &buffers, path, &mut out)?;
        }
    } else {
        let mut stack = roots;
        let mut visited = 0usize;
        while let Some((node, parent)) = stack.pop() {
            visited += 1;
            if visited > 1_000_000 {
                return Err(gerr("node hierarchy too deep or cyclic".into()));
            }
            let local = Matrix4::from_iterator(node.transform().matrix().iter().flatten().map(|&v| v as f64));
            let world = parent * local;
            if let Some(mesh) = node.mesh() {
                read_gltf_mesh(&mesh, &world, &buffers, path, &mut out)?;
            }
            for child in node.children() {
                stack.push((child, world));
            }
        }
    }
    if out.triangles.is_empty() {
        return Err(gerr("no triangle primitives".into()));
    }
    let uvs = out.all_uvs.then_some(out.uvs);
    Ok(Mesh::new(name_of(path), out.positions, uvs, out.triangles))
}

/// `gltf::Gltf::from_slice`, minus its panic: glTF's validation indexes the
/// accessor array with each primitive's POSITION accessor unchecked, so an
/// index past the end is caught here first, naming the mesh and primitive.
fn parse_gltf(bytes: &[u8], path: &Path) -> Result<gltf::Gltf, LoadError> {
    let gerr = |reason: String| LoadError::Gltf {
        path: path.to_path_buf(),
        reason,
    };
    // glTF's GLB reader subtracts the 12-byte header from the declared
    // length unchecked.
    if let Some(declared) = bytes
        .strip_prefix(b"glTF")
        .and_then(|rest| rest.get(4..8))
        .and_then(|b| <[u8; 4]>::try_from(b).ok())
        .map(u32::from_le_bytes)
        && declared < 12
    {
        return Err(gerr(format!(
            "GLB header declares a length of {declared} bytes, less than the 12-byte header"
        )));
    }
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| gerr(e.to_string()))?;
    let json = document.into_json();
    let accessors = json.accessors.len();
    let position = gltf::json::validation::Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (mesh, m) in json.meshes.iter().enumerate() {
        for (primitive, p) in m.primitives.iter().enumerate() {
            if let Some(index) = p.attributes.get(&position)
                && index.value() >= accessors
            {
                return Err(LoadError::GltfPrimitive {
                    path: path.to_path_buf(),
                    mesh,
                    primitive,
                    reason: format!(
                        "POSITION refers to accessor {}, but there are only {accessors} accessors",
                        index.value()
                    ),
                });
            }
        }
    }
    // glTF's buffer import percent-decodes a relative URI and unwraps the
    // result as UTF-8.
    for (i, buffer) in json.buffers.iter().enumerate() {
        if let Some(uri) = &buffer.uri
            && !uri.contains(':')
            && std::str::from_utf8(&percent_decode(uri.as_bytes())).is_err()
        {
            return Err(gerr(format!(
                "buffer {i}: URI `{uri}` does not percent-decode to UTF-8"
            )));
        }
    }
    let document = gltf::Document::from_json(json).map_err(|e| gerr(e.to_string()))?;
    Ok(gltf::Gltf { document, blob })
}

/// `%XX` escapes decoded to bytes; a `%` not followed by two hex digits
/// stays as it is (as glTF's URI decoding does).
fn percent_decode(bytes: &[u8]) -> Vec<u8> {
    let hex = |b: u8| (b as char).to_digit(16);
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%'
            && let (Some(h), Some(l)) = (
                bytes.get(i + 1).copied().and_then(hex),
                bytes.get(i + 2).copied().and_then(hex),
            )
        {
            out.push((h * 16 + l) as u8);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    out
}

/// Checks what glTF's accessor reader assumes without checking (it panics,
/// or reads the wrong bytes, otherwise): the element type, at least one
/// element, no sparse storage, a stride no smaller than an element, and an
/// extent inside the buffer view and the view inside its buffer.
fn check_accessor(
    acc: &gltf::Accessor<'_>,
    dims: gltf::accessor::Dimensions,
    types: &[gltf::accessor::DataType],
    buffers: &[gltf::buffer::Data],
) -> Result<(), String> {
    let index = acc.index();
    if acc.dimensions() != dims || !types.contains(&acc.data_type()) {
        return Err(format!(
            "accessor {index} holds {:?} of {:?}, expected {dims:?} of one of {types:?}",
            acc.dimensions(),
            acc.data_type()
        ));
    }
    if acc.count() == 0 {
        return Err(format!("accessor {index} has no elements"));
    }
    if acc.sparse().is_some() {
        return Err(format!("accessor {index} is sparse, which soak does not read"));
    }
    let Some(view) = acc.view() else {
        return Err(format!("accessor {index} has no buffer view"));
    };
    let buffer = view.buffer().index();
    let Some(data) = buffers.get(buffer) else {
        return Err(format!("accessor {index} refers to missing buffer {buffer}"));
    };
    if view
        .offset()
        .checked_add(view.length())
        .is_none_or(|end| end > data.0.len())
    {
        return Err(format!(
            "accessor {index}: buffer view {} ({} bytes at {}) extends past buffer {buffer} ({} bytes)",
            view.index(),
            view.length(),
            view.offset(),
            data.0.len()
        ));
    }
    let size = acc.size();
    let stride = view.stride().unwrap_or(size);
    let end = stride
        .checked_mul(acc.count() - 1)
        .and_then(|x| x.checked_add(size))
        .and_then(|x| x.checked_add(acc.offset()));
    if stride < size || end.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "accessor {index} ({} elements of {size} bytes, stride {stride}, offset {}) does not fit buffer view {} ({} bytes)",
            acc.count(),
            acc.offset(),
            view.index(),
            view.length()
        ));
    }
    Ok(())
}

#[derive(Default)]
struct GltfOut {
    positions: Vec<Point3<f64>>,
    uvs: Vec<Point2<f64>>,
    all_uvs: bool,
    any: bool,
    triangles: Vec<[u32; 3]>,
}

fn read_gltf_mesh(
    mesh: &gltf::Mesh<'_>,
    world: &Matrix4<f64>,
    buffers: &[gltf::buffer::Data],
    path: &Path,
    out: &mut GltfOut,
) -> Result<(), LoadError> {
    let perr = |primitive: usize, reason: String| LoadError::GltfPrimitive {
        path: PathBuf::from(path),
        mesh: mesh.index(),
        primitive,
        reason,
    };
    let mirrored = world.fixed_view::<3, 3>(0, 0).determinant() < 0.0;
    for (pi, prim) in mesh.primitives().enumerate() {
        if prim.mode() != gltf::mesh::Mode::Triangles {
            return Err(perr(
                pi,
                format!("mode {:?} is not supported (only triangles)", prim.mode()),
            ));
        }
        for (sem, acc) in prim.attributes() {
            if let Some(view) = acc.view()
                && buffers.get(view.buffer().index()).is_none()
            {
                return Err(perr(pi, format!("attribute {sem:?} refers to a missing buffer")));
            }
        }
        {
            use gltf::accessor::{DataType, Dimensions};
            let checks = [
                (
                    "POSITION",
                    prim.get(&gltf::Semantic::Positions),
                    Dimensions::Vec3,
                    &[DataType::F32][..],
                ),
                (
                    "TEXCOORD_0",
                    prim.get(&gltf::Semantic::TexCoords(0)),
                    Dimensions::Vec2,
                    &[DataType::F32, DataType::U8, DataType::U16][..],
                ),
                (
                    "indices",
                    prim.indices(),
                    Dimensions::Scalar,
                    &[DataType::U8, DataType::U16, DataType::U32][..],
                ),
            ];
            for (what, acc, dims, types) in checks {
                if let Some(acc) = acc {
                    check_accessor(&acc, dims, types, buffers)
                        .map_err(|r| perr(pi, format!("{what} {r}")))?;
                }
            }
        }
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let Some(pos) = reader.read_positions() else {
            return Err(perr(
                pi,
                "has no POSITION attribute or its buffer is missing".into(),
            ));
        };
        let base = out.positions.len();
        for p in pos {
            let q = world.transform_point(&Point3::new(p[0] as f64, p[1] as f64, p[2] as f64));
            out.positions.push(q);
        }
        let n = out.positions.len() - base;
        match reader.read_tex_coords(0) {
            Some(tc) => {
                let before = out.uvs.len();
                out.uvs
                    .extend(tc.into_f32().map(|t| Point2::new(t[0] as f64, t[1] as f64)));
                if out.uvs.len() - before != n {
                    return Err(perr(
                        pi,
                        format!("has {} UVs for {n} positions", out.uvs.len() - before),
                    ));
                }
                out.all_uvs = !out.any || out.all_uvs;
            }
            None => out.all_uvs = false,
        }
        out.any = true;
        let indices: Vec<u32> = match reader.read_indices() {
            Some(ix) => ix.into_u32().collect(),
            None => (0..n as u32).collect(),
        };
        if !indices.len().is_multiple_of(3) {
            return Err(perr(
                pi,
                format!("index count {} is not a multiple of 3", indices.len()),
            ));
        }
        for t in indices.chunks(3) {
            if let Some(&bad) = t.iter().find(|&&i| i as usize >= n) {
                return Err(perr(pi, format!("index {bad} is out of range for {n} vertices")));
            }
            let (a, b, c) = (t[0] + base as u32, t[1] + base as u32, t[2] + base as u32);
            out.triangles.push(if mirrored { [a, c, b] } else { [a, b, c] });
        }
    }
    Ok(())
}
