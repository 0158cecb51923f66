//! Loading OBJ and glTF files, and the errors real malformed files get.

use std::path::PathBuf;

use soak_bake::{
    Atlas, BakeOptions, LoadError, MeshProblem, UnwrapOptions, cap_openings, load_mesh, load_obj_bytes,
    unwrap, validate, validate_topology,
};

fn data(name: &str) -> String {
    let p: PathBuf = [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", name]
        .iter()
        .collect();
    p.to_string_lossy().into_owned()
}

#[test]
fn obj_gltf_and_glb_load_the_same_tetrahedron() {
    let obj = load_mesh(&data("tetra.obj")).unwrap();
    let gltf = load_mesh(&data("tetra.gltf")).unwrap();
    let glb = load_mesh(&data("tetra.glb")).unwrap();
    for m in [&obj, &gltf, &glb] {
        validate(m).unwrap();
        assert_eq!(m.triangles.len(), 4);
        assert!((m.volume() - 1.0 / 6.0).abs() < 1e-7);
    }
    // The glTF node translates by +2 in y.
    assert!((gltf.bounds().0.y - 2.0).abs() < 1e-7);
    assert_eq!(gltf.positions, glb.positions);
    // OBJ's upward v is flipped to soak's (glTF's) convention on load.
    let (uo, ug) = (obj.uvs.unwrap(), gltf.uvs.unwrap());
    for (a, b) in uo.iter().zip(&ug) {
        assert!((a - b).norm() < 1e-6, "{a} vs {b}");
    }
}

#[test]
fn obj_round_trip_of_every_builtin() {
    let dir = std::env::temp_dir().join(format!("soak-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["builtin:sphere:0.5:24:12", "builtin:torus", "builtin:boat"] {
        let mesh = load_mesh(name).unwrap();
        let path = dir.join("m.obj");
        std::fs::write(&path, mesh.to_obj()).unwrap();
        let back = load_mesh(path.to_str().unwrap()).unwrap();
        validate(&back).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(back.triangles.len(), mesh.triangles.len());
        let a = Atlas::bake(&back, BakeOptions::square(128)).unwrap();
        assert!((a.volume() - mesh.volume()).abs() / mesh.volume() < 1e-5);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn truncated_obj_names_the_file_and_line() {
    let e = load_mesh(&data("bad/truncated.obj")).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, LoadError::Obj { .. }), "{e:?}");
    assert!(msg.contains("truncated.obj") && msg.contains("line 3"), "{msg}");
}

#[test]
fn obj_with_a_bad_number_names_the_line() {
    let msg = load_mesh(&data("bad/not_a_number.obj")).unwrap_err().to_string();
    assert!(
        msg.contains("not_a_number.obj") && msg.contains("line 4"),
        "{msg}"
    );
}

#[test]
fn obj_with_a_nan_names_the_files_line_and_vertex() {
    // The third `v` line (line 4 of the file) holds a NaN: the file's
    // vertex 3, whatever the loaded mesh's numbering.
    let text = "# tetrahedron\nv 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
    let msg = load_obj_bytes(text.as_bytes(), "nan.obj".as_ref())
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("nan.obj") && msg.contains("line 4: vertex 3 `v nan 1 0` is not a finite position"),
        "{msg}"
    );
    let inf = text.replace("v 0 0 1", "v 0 0 -inf");
    let msg = load_obj_bytes(inf.as_bytes(), "inf.obj".as_ref())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("line 4: vertex 3 `v nan"), "{msg}");
    let inf = text
        .replace("v nan 1 0", "v 0 1 0")
        .replace("v 0 0 1", "v 0 0 -inf");
    let msg = load_obj_bytes(inf.as_bytes(), "inf.obj".as_ref())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("line 5: vertex 4 `v 0 0 -inf`"), "{msg}");
}

#[test]
fn obj_uv_index_out_of_range_names_the_line() {
    let msg = load_mesh(&data("bad/uv_index_out_of_range.obj"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("uv_index_out_of_range.obj"), "{msg}");
    assert!(
        msg.contains("line 29") && msg.contains("texture coordinate 19"),
        "{msg}"
    );
}

#[test]
fn obj_with_a_hole_loads_but_does_not_validate() {
    let mesh = load_mesh(&data("bad/hole.obj")).unwrap();
    let e = validate(&mesh).unwrap_err();
    assert!(matches!(e.problem, MeshProblem::OpenEdge { .. }));
    // Named in the file's terms: its first face (line 26, `f 1/1 2/2 3/3`)
    // has the open edge from its vertex 2 to its vertex 3.
    assert!(
        e.to_string()
            .starts_with("mesh `hole.obj` the face on line 26 has an open edge between vertices 2 and 3"),
        "{e}"
    );
    // It says how an open container is read.
    assert!(e.to_string().contains("`--open`, or `open = true`"), "{e}");
}

#[test]
fn gltf_with_a_missing_buffer_names_it() {
    let e = load_mesh(&data("bad/missing_buffer.gltf")).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, LoadError::Gltf { .. }), "{e:?}");
    assert!(
        msg.contains("missing_buffer.gltf") && msg.contains("buffer"),
        "{msg}"
    );
}

#[test]
fn missing_file_and_unknown_format() {
    assert!(matches!(load_mesh(&data("nope.obj")), Err(LoadError::Io { .. })));
    assert!(matches!(
        load_mesh(&data("tetra.stl")),
        Err(LoadError::UnknownFormat { .. })
    ));
}

#[test]
fn builtin_names_and_their_errors() {
    for ok in [
        "builtin:sphere",
        "builtin:sphere:0.5",
        "builtin:sphere:0.5:32",
        "builtin:box:4x1x1",
        "builtin:box:2",
        "builtin:cylinder:0.3:2",
        "builtin:capsule:0.2:0.6:32",
        "builtin:torus:1:0.2",
        "builtin:boat:6x2x1",
        "builtin:dumbbell",
    ] {
        let m = load_mesh(ok).unwrap_or_else(|e| panic!("{ok}: {e}"));
        assert_eq!(m.name, ok);
        validate(&m).unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    for bad in [
        "builtin:cube",
        "builtin:sphere:-1",
        "builtin:sphere:abc",
        "builtin:box:1x2",
        "builtin:torus:0.2:0.5",
        "builtin:sphere:1:2:3:4",
        "builtin:sphere:1:100000",
    ] {
        let e = load_mesh(bad).unwrap_err();
        assert!(matches!(e, LoadError::Builtin { .. }), "{bad}: {e:?}");
        assert!(e.to_string().contains(bad), "{bad}: {e}");
    }
}

/// Found by fuzzing (the gltf target): glTF's own validation indexed the
/// accessor array with the POSITION accessor unchecked and panicked.
#[test]
fn gltf_with_position_accessor_past_the_end_is_an_error() {
    assert_first_primitive_refused(
        "gltf_position_accessor_past_the_end.gltf",
        "POSITION refers to accessor 0",
    );
}

/// Loading `data/bad/FILE` is a `GltfPrimitive` error for mesh 0,
/// primitive 0, whose message names the file and says `what`.
fn assert_first_primitive_refused(file: &str, what: &str) {
    let e = load_mesh(&data(&format!("bad/{file}"))).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(
            e,
            LoadError::GltfPrimitive {
                mesh: 0,
                primitive: 0,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(msg.contains(file) && msg.contains(what), "{msg}");
}

/// Found by fuzzing (the gltf target): glTF's accessor reader asserts that
/// an accessor's element size matches the type read from it, so TEXCOORD_0
/// pointing at a VEC3 accessor panicked (and read the wrong bytes in release).
#[test]
fn gltf_with_vec3_texture_coordinates_is_an_error() {
    assert_first_primitive_refused(
        "gltf_texcoord_accessor_vec3.gltf",
        "TEXCOORD_0 accessor 0 holds Vec3",
    );
}

/// The other assumptions of glTF's accessor reader, checked before reading:
/// at least one element, and an extent inside the buffer view.
#[test]
fn gltf_accessors_that_do_not_fit_their_view_are_errors() {
    let text = std::fs::read_to_string(data("bad/gltf_texcoord_accessor_vec3.gltf")).unwrap();
    let fixed = text.replace(",\"TEXCOORD_0\":0", "");
    let path = std::path::Path::new("t.gltf");
    assert!(soak_bake::load_gltf_bytes(fixed.as_bytes(), path, None).is_ok());
    for (from, to, expect) in [
        (
            "\"count\":3",
            "\"count\":4",
            "does not fit buffer view 0 (36 bytes)",
        ),
        ("\"count\":3", "\"count\":0", "has no elements"),
        (
            "\"count\":3",
            "\"count\":3,\"byteOffset\":4",
            "does not fit buffer view 0",
        ),
    ] {
        let bad = fixed.replace(from, to);
        let e = soak_bake::load_gltf_bytes(bad.as_bytes(), path, None).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("t.gltf") && msg.contains("POSITION accessor 0") && msg.contains(expect),
            "{to}: {msg}"
        );
    }
}

/// Found by fuzzing (the gltf target): glTF's GLB reader subtracted the
/// 12-byte header from the declared length unchecked, so a length under 12
/// overflowed (a panic in debug builds).
#[test]
fn glb_with_a_length_shorter_than_its_header_is_an_error() {
    let bytes = b"glTF\x02\x00\x00\x00\x04\x00\x00\x00\x00\x00\x00\x00JSON";
    let e = soak_bake::load_gltf_bytes(bytes, std::path::Path::new("short.glb"), None).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, LoadError::Gltf { .. }), "{e:?}");
    assert!(
        msg.contains("short.glb") && msg.contains("declares a length of 4 bytes"),
        "{msg}"
    );
}

/// Found by fuzzing (the gltf target): glTF's buffer import percent-decodes
/// a relative buffer URI and unwrapped the result as UTF-8, so `%AD`
/// panicked.
#[test]
fn gltf_with_a_buffer_uri_that_is_not_utf8_is_an_error() {
    let text = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"a%AD.bin"}]}"#;
    let e = soak_bake::load_gltf_bytes(text, std::path::Path::new("uri.gltf"), None).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, LoadError::Gltf { .. }), "{e:?}");
    assert!(
        msg.contains("uri.gltf") && msg.contains("buffer 0: URI `a%AD.bin` does not percent-decode to UTF-8"),
        "{msg}"
    );
    // Valid escapes still name the file they refer to.
    let ok = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"a%20b.bin"}]}"#;
    let e = soak_bake::load_gltf_bytes(ok, std::path::Path::new("uri.gltf"), None).unwrap_err();
    assert!(!e.to_string().contains("UTF-8"), "{e}");
}

/// A box without its top, its faces' corners split by their texture
/// coordinates (the loader makes one vertex per `v/vt` pair), its last side
/// a quad; the open edge the validation meets first is on line 16, from the
/// file's vertex 5 to its vertex 6.
const OPEN_CRATE: &str = "# an open crate
v 0 0 0
v 1 0 0
v 1 0 1
v 0 0 1
v 0 1 0
v 1 1 0
v 1 1 1
v 0 1 1
vt 0.1 0.1
vt 0.2 0.1
vt 0.2 0.2
vt 0.1 0.2
f 1/1 2/2 3/3
f 1/1 3/3 4/1
f 1/4 5/2 6/3
f 1/4 6/3 2/1
f 2/2 6/3 7/4
f 2/2 7/4 3/1
f 3/1 7/2 8/3
f 3/1 8/3 4/4
f 4/1 8/2 5/3 1/4
";

#[test]
fn an_open_mesh_is_named_in_the_files_own_numbering() {
    let path = PathBuf::from("open_crate.obj");
    let mesh = load_obj_bytes(OPEN_CRATE.as_bytes(), &path).unwrap();
    assert!(mesh.positions.len() > 8, "the loader split the corners");
    let expected = "mesh `open_crate.obj` the face on line 16 has an open edge between vertices 5 and 6 (the file's numbering)";
    let e = validate_topology(&mesh).unwrap_err();
    assert!(e.to_string().starts_with(expected), "{e}");
    assert!(e.to_string().contains("`--open`, or `open = true`"), "{e}");
    // The mesh's own indices stay in the typed problem.
    let MeshProblem::OpenEdge { triangle, a, b } = e.problem else {
        panic!("{e:?}")
    };
    assert_eq!(triangle, 2);
    let source = mesh.source.as_ref().unwrap();
    assert_eq!((source.vertex(a), source.vertex(b)), (Some(5), Some(6)));
    assert_eq!(source.face_line(triangle), Some(16));
    assert_eq!(source.face_lines.len(), 10, "the quad counts twice, on its line");
    assert_eq!(source.face_lines[9], 22);

    // Scaled and unwrapped again (new vertices along new seams), it is
    // still told in the file's terms.
    let scaled = mesh.clone().without_uvs().map_positions(|p| p * 3.0);
    let (unwrapped, _) = unwrap(&scaled, UnwrapOptions::default()).unwrap();
    let e = validate_topology(&unwrapped).unwrap_err();
    assert!(e.to_string().starts_with(expected), "{e}");

    // A mesh made in code has no file: its own indices.
    let mut made = mesh.clone();
    made.source = None;
    let e = validate_topology(&made).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("mesh `open_crate.obj` triangle 2 has an open edge"),
        "{e}"
    );
}

#[test]
fn a_capped_open_mesh_keeps_the_files_numbering() {
    // One side's face turned over: the rims it leaves meet at the file's
    // vertex 7 (two open edges leave it), named so.
    let text = OPEN_CRATE.replace("f 2/2 6/3 7/4", "f 2/2 7/4 6/3");
    let mesh = load_obj_bytes(text.as_bytes(), &PathBuf::from("flipped.obj")).unwrap();
    let e = cap_openings(&mesh).unwrap_err();
    assert_eq!(
        e.to_string(),
        "mesh `flipped.obj` two rims meet at vertex 7 (the file's numbering): the open mesh's boundary is not manifold there"
    );
    // Capped, the crate carries the numbering over.
    let closed =
        cap_openings(&load_obj_bytes(OPEN_CRATE.as_bytes(), &PathBuf::from("c.obj")).unwrap()).unwrap();
    let source = closed.source.as_ref().unwrap();
    assert_eq!(source.vertices.len(), closed.positions.len());
    assert_eq!(source.face_lines.len(), closed.triangles.len());
    // The cap's triangles are soak's; its vertices copy the rim's (5 to 8).
    let first_cap = closed.first_opening_triangle().unwrap() as usize;
    assert!((first_cap..closed.triangles.len()).all(|t| source.face_line(t).is_none()));
    let cap_vertices: Vec<u32> = source.vertices[mesh_len(OPEN_CRATE)..].to_vec();
    let mut sorted = cap_vertices.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, vec![5, 6, 7, 8]);
}

fn mesh_len(text: &str) -> usize {
    load_obj_bytes(text.as_bytes(), &PathBuf::from("x.obj"))
        .unwrap()
        .positions
        .len()
}
