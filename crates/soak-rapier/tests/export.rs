//! A recording written as a glTF binary reads back, with the `gltf` crate,
//! as the bodies' meshes and poses: every animation sample equals the pose
//! recorded at its time.

use gltf::animation::util::ReadOutputs;
use rapier3d::prelude::*;
use soak_bake::builtin;
use soak_rapier::export::{ExportError, Recording};

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
