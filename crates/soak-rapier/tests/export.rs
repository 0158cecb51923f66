//! A recording written as a glTF binary reads back, with the `gltf` crate,
//! as the bodies' meshes and poses: every animation sample equals the pose
//! recorded at its time.

use gltf::animation::util::ReadOutputs;
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_rapier::export::{ExportError, Recording, liquid_colour, vertex_fill};

#[test]
fn a_recording_reads_back_as_its_meshes_and_poses() {
    let mut run = Recording::new();
    let meshes = [builtin::cuboid(1.0, 0.6, 0.8), builtin::sphere(0.5, 16, 8)];
    let ids = [
        run.add_body("crate", meshes[0].clone()),
        run.add_body("buoy", meshes[1].clone()),
    ];
    let pose = |k: usize, b: usize| {
        let t = k as f32 / 30.0;
        Pose::from_parts(
            Vector::new(2.0 * b as f32, -0.2 * t, 0.1 * t * t),
            Rotation::from_rotation_x(0.3 * t) * Rotation::from_rotation_y(b as f32 + t),
        )
    };
    for k in 0..=45 {
        for (b, &id) in ids.iter().enumerate() {
            run.push(id, k as f64 / 30.0, &pose(k, b)).unwrap();
        }
    }
    let glb = run.to_glb();
    let (doc, buffers, _) = gltf::import_slice(&glb).expect("a valid glTF binary");

    let nodes: Vec<_> = doc.nodes().collect();
    assert_eq!(nodes.len(), 2);
    for (node, mesh) in nodes.iter().zip(&meshes) {
        let primitive = node.mesh().unwrap().primitives().next().unwrap();
        let reader = primitive.reader(|b| Some(&buffers[b.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        assert_eq!(positions.len(), mesh.positions.len());
        for (p, q) in positions.iter().zip(&mesh.positions) {
            assert!((0..3).all(|k| (f64::from(p[k]) - q[k]).abs() < 1e-6));
        }
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        assert_eq!(
            indices,
            mesh.triangles.iter().flatten().copied().collect::<Vec<_>>()
        );
    }

    let animation = doc.animations().next().expect("one animation");
    let mut checked = 0;
    for channel in animation.channels() {
        let b = channel.target().node().index();
        let reader = channel.reader(|buf| Some(&buffers[buf.index()]));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        assert_eq!(times.len(), 46);
        match reader.read_outputs().unwrap() {
            ReadOutputs::Translations(t) => {
                for (k, (v, time)) in t.zip(&times).enumerate() {
                    assert_eq!(*time, (k as f64 / 30.0) as f32);
                    let want = pose(k, b).translation;
                    assert_eq!(v, [want.x, want.y, want.z]);
                    checked += 1;
                }
            }
            ReadOutputs::Rotations(r) => {
                for (k, q) in r.into_f32().enumerate() {
                    let want = pose(k, b).rotation;
                    assert_eq!(q, [want.x, want.y, want.z, want.w]);
                    checked += 1;
                }
            }
            _ => panic!("only translations and rotations are animated"),
        }
    }
    assert_eq!(checked, 2 * 2 * 46);
}

#[test]
fn a_recording_refuses_what_gltf_cannot_hold() {
    let mut run = Recording::new();
    let b = run.add_body("crate", builtin::cuboid(1.0, 1.0, 1.0));
    run.push(b, 0.0, &Pose::IDENTITY).unwrap();
    assert!(matches!(
        run.push(b, 0.0, &Pose::IDENTITY),
        Err(ExportError::Time { .. })
    ));
    assert!(matches!(
        run.push(b, f64::NAN, &Pose::IDENTITY),
        Err(ExportError::Time { .. })
    ));
    let nan = Pose::from_translation(Vector::new(f32::NAN, 0.0, 0.0));
    assert!(matches!(run.push(b, 1.0, &nan), Err(ExportError::Pose { .. })));
    assert!(matches!(
        run.push(7, 1.0, &Pose::IDENTITY),
        Err(ExportError::UnknownBody(7))
    ));
    // What was refused left the recording as it was: one sample.
    let (doc, _, _) = gltf::import_slice(run.to_glb()).unwrap();
    let count = doc
        .animations()
        .next()
        .unwrap()
        .samplers()
        .next()
        .unwrap()
        .input()
        .count();
    assert_eq!(count, 1);
}

/// The liquid a body carries reads back per vertex, as the vertex colour
/// of its fill fraction (`COLOR_0`, the fraction linear in the red
/// channel); liquid for another vertex count, or outside [0, 1], is
/// refused.
#[test]
fn a_wet_body_carries_its_liquid_per_vertex() {
    let mesh = builtin::cuboid(1.0, 0.6, 0.8);
    let n = mesh.positions.len();
    let mut run = Recording::new();
    let dry = run.add_body("dry", builtin::sphere(0.5, 16, 8));
    let wet = run.add_body("wet", mesh);
    for b in [dry, wet] {
        run.push(b, 0.0, &Pose::IDENTITY).unwrap();
    }
    let fill: Vec<f32> = (0..n).map(|i| i as f32 / (n - 1) as f32).collect();
    assert!(matches!(
        run.set_liquid(wet, fill[1..].to_vec()),
        Err(ExportError::Liquid { .. })
    ));
    let mut bad = fill.clone();
    bad[2] = f32::NAN;
    let e = run.set_liquid(wet, bad).unwrap_err();
    assert!(e.to_string().contains("vertex 2"), "{e}");
    assert!(matches!(
        run.set_liquid(9, fill.clone()),
        Err(ExportError::UnknownBody(9))
    ));
    run.set_liquid(wet, fill.clone()).unwrap();

    let glb = run.to_glb();
    let (doc, buffers, _) = gltf::import_slice(&glb).expect("a valid glTF binary");
    for node in doc.nodes() {
        let primitive = node.mesh().unwrap().primitives().next().unwrap();
        let reader = primitive.reader(|b| Some(&buffers[b.index()]));
        let colours: Option<Vec<[f32; 4]>> = reader.read_colors(0).map(|c| c.into_rgba_f32().collect());
        match node.name() {
            Some("dry") => assert!(colours.is_none(), "a dry body has no liquid"),
            _ => {
                let colours = colours.unwrap();
                assert_eq!(colours.len(), n);
                for (c, f) in colours.iter().zip(&fill) {
                    assert_eq!(*c, liquid_colour(*f));
                    assert!(((0.8 - c[0]) / 0.75 - f).abs() < 1e-6, "{c:?} for {f}");
                }
            }
        }
    }
}

/// A vertex's fill fraction is the liquid of the texels around it: the
/// same everywhere when the liquid is; on a sphere wet below its equator,
/// saturated at the vertices below it and dry above, but for those whose
/// triangles the equator crosses.
#[test]
fn vertex_fill_takes_the_texels_around_each_vertex() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    let saturation = 2e-3;
    let uniform = vec![0.3 * saturation; atlas.len()];
    let fill = vertex_fill(&atlas, &uniform, saturation);
    assert_eq!(fill.len(), mesh.positions.len());
    // The vertices the triangles use (the builder leaves a pole vertex or
    // two unused; those are dry).
    let mut used = vec![false; fill.len()];
    for t in &mesh.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    for (v, f) in fill.iter().enumerate() {
        let want = if used[v] { 0.3 } else { 0.0 };
        assert!((f - want).abs() < 1e-6, "vertex {v}: {f}");
    }
    let below: Vec<f64> = (0..atlas.len())
        .map(|i| {
            if atlas.position(i).y < 0.0 {
                5.0 * saturation
            } else {
                0.0
            }
        })
        .collect();
    let fill = vertex_fill(&atlas, &below, saturation);
    // One ring of the 16 lies 0.1 m from the equator: beyond it, wholly.
    for ((p, f), _) in mesh.positions.iter().zip(&fill).zip(&used).filter(|(_, u)| **u) {
        if p.y < -0.11 {
            assert_eq!(*f, 1.0, "vertex {p} below the equator");
        } else if p.y > 0.11 {
            assert_eq!(*f, 0.0, "vertex {p} above the equator");
        } else {
            assert!((0.0..=1.0).contains(f), "vertex {p}: {f}");
        }
    }
    // No liquid, or no saturation to measure it by: dry.
    let none = vertex_fill(&atlas, &vec![0.0; atlas.len()], saturation);
    assert!(none.iter().all(|&f| f == 0.0));
    assert!(vertex_fill(&atlas, &below, 0.0).iter().all(|&f| f == 0.0));
}
