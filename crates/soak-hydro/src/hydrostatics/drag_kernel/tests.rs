//! The drag kernel's unit tests.

use super::*;
use nalgebra::UnitQuaternion;
use soak_bake::{BakeOptions, builtin};

/// The AVX2 kernel (where the processor has it) and the portable one
/// with fused multiply-adds give the same sums, and the portable one
/// without them the same but for rounding, over ranges of every length
/// modulo the lanes and with every combination of closed forms added, in
/// one list or in several of one call.
#[test]
fn the_avx2_and_portable_kernels_agree() {
    let atlas = Atlas::bake(&builtin::boat(4.0, 1.2, 0.6), BakeOptions::square(64)).unwrap();
    let rot = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.4)
        .to_rotation_matrix()
        .into_inner();
    let drag = Drag {
        coefficient: 0.9,
        linear: 7.0,
    };
    let p = LocalDrag::new(
        &drag,
        1000.0,
        0.05,
        &Vector3::new(0.1, -1.0, 0.2),
        &rot,
        &Vector3::new(0.01, -0.02, 0.03),
        &Vector3::new(0.4, -0.2, 0.3),
        &Vector3::new(0.3, 0.1, -0.5),
        &Vector3::zeros(),
    );
    let n = atlas.len();
    let t = DragColumns {
        xs: atlas.local_positions().columns(0..n),
        avs: atlas.area_vectors().columns(0..n),
    };
    let ranges = [0..5, 5..6, 6..37, 37..39, 39..n];
    for (linear, quadratic) in [(false, false), (true, false), (false, true), (true, true)] {
        let added = Added { linear, quadratic };
        let (mut fused, mut plain) = (DragLanes::default(), DragLanes::default());
        for r in &ranges {
            drag_lanes_generic::<true, true, true>(&mut fused, &t, r.clone(), &p, added);
            drag_lanes_generic::<false, true, true>(&mut plain, &t, r.clone(), &p, added);
        }
        let mut dispatched = DragLanes::default();
        drag_lanes::<true, true>(&mut dispatched, &t, &[(&ranges[..], added)], &p);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
            assert_eq!(fused, dispatched);
        }
        // Fused or not, the same sums but for rounding.
        for (f, q) in fused
            .iso
            .iter()
            .chain(&fused.gg)
            .zip(plain.iso.iter().chain(&plain.gg))
        {
            for k in 0..LANES {
                assert!((f[k] - q[k]).abs() <= 1e-12 * (1.0 + q[k].abs()), "{f:?} {q:?}");
            }
        }
    }
    // Lists of every combination in one call: each range as the
    // portable kernel takes it, one after the other.
    let combos = [(false, false), (true, false), (false, true), (true, true)]
        .map(|(linear, quadratic)| Added { linear, quadratic });
    let split: [&[std::ops::Range<usize>]; 4] = [
        &[0..3, 3..9],
        &[9..10, 10..17],
        &[17..23, 30..31],
        &[31..40, 40..n],
    ];
    let lists: Vec<RangeList> = split.into_iter().zip(combos).collect();
    let mut one_call = DragLanes::default();
    drag_lanes::<true, true>(&mut one_call, &t, &lists, &p);
    let mut in_turn = DragLanes::default();
    for (ranges, added) in &lists {
        for r in ranges.iter() {
            drag_lanes_generic::<true, true, true>(&mut in_turn, &t, r.clone(), &p, *added);
        }
    }
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
        assert_eq!(one_call, in_turn);
    }
    assert!(one_call.iso.iter().flatten().any(|&v| v != 0.0));
}
