//! The cone-of-normals unit in hardware equals the fixed-point model class
//! for class, in rust-hdl, Icarus and Verilator, on random patches and
//! eyes, each class a fixed 4 clocks after its patch (the teapot at 32 to
//! 512 patches is in tests/shared_testdata.rs,
//! run by scripts/test-shared.sh).

use nalgebra::Point3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::cone_unit::{expected, inputs_for, run_emitted, run_rusthdl};
use tritri_cosim::simulator::Simulator;
use tritri_geom::bezier::cone_fixed::Facing;
use tritri_geom::bezier::BezierPatch;

#[test]
fn random_patches_agree_in_rust_hdl_icarus_and_verilator() {
    let mut rng = ChaCha8Rng::seed_from_u64(16);
    for w in [16usize, 24] {
        let patches: Vec<BezierPatch> = (0..40)
            .map(|_| {
                let tilt = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
                let net = std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        let (x, y) = (i as f64, j as f64);
                        Point3::new(x, y, tilt[0] * x + tilt[1] * y + rng.gen_range(-0.3..0.3))
                    })
                });
                BezierPatch { net }
            })
            .collect();
        let eyes: Vec<Point3<f64>> = (0..5)
            .map(|_| {
                Point3::new(
                    rng.gen_range(-20.0..20.0),
                    rng.gen_range(-20.0..20.0),
                    rng.gen_range(-20.0..20.0),
                )
            })
            .collect();
        let inputs = inputs_for(&patches, &eyes, w).unwrap();
        let want = expected(&inputs);
        let classes = [Facing::Front, Facing::Back, Facing::Silhouette]
            .map(|c| want.iter().filter(|&&f| f == c).count());
        eprintln!(
            "W = {w}: {} inputs, front / back / silhouette {classes:?}",
            inputs.len()
        );
        assert!(classes.iter().all(|&n| n > 0), "every class is exercised");
        assert_eq!(run_rusthdl(w, &inputs).unwrap(), want, "rust-hdl, W = {w}");
        assert_eq!(
            run_emitted(w, &inputs, Simulator::Icarus).unwrap(),
            want,
            "Icarus, W = {w}"
        );
        assert_eq!(
            run_emitted(w, &inputs, Simulator::Verilator).unwrap(),
            want,
            "Verilator, W = {w}"
        );
    }
}
