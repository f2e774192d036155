//! The patch tessellation unit against its exact fixed-point model
//! (`tritri_geom::bezier::fixed::fixed_grid`): random nets (full-range
//! coordinates, collapsed rows as on the teapot's lid, flat and affine
//! nets), vertex for vertex, in rust-hdl with a reader that stalls and in
//! the emitted Verilog under Verilator and Icarus, and the clocks the
//! unit's timing formula gives.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::patch_tessellator::{run_emitted, run_rusthdl, TessellationRun};
use tritri_cosim::simulator::Simulator;
use tritri_geom::bezier::fixed::{fixed_grid, FixedNet};
use tritri_rtl::bezier::patch_tessellator::tessellation_clocks;

/// Nets that exercise the unit: random at the edges of the coordinate
/// range, a row collapsed to one point, an affine net, all zero.
fn nets(w: usize, count: usize, seed: u64) -> Vec<FixedNet> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let limit = (1i64 << (w - 1)) - 1;
    let mut out: Vec<FixedNet> = (0..count)
        .map(|_| {
            std::array::from_fn(|_| {
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-limit - 1..=limit)))
            })
        })
        .collect();
    let mut collapsed = out[0];
    collapsed[0] = [collapsed[0][0]; 4];
    out.push(collapsed);
    out.push(std::array::from_fn(|a| {
        std::array::from_fn(|b| [a as i64 * 1000 - 1500, b as i64 * 700, (a + b) as i64 - 3])
    }));
    out.push([[[0; 3]; 4]; 4]);
    out.push([[[-limit - 1; 3]; 4]; 4]);
    out.push([[[limit; 3]; 4]; 4]);
    out
}

fn check(runs: &[TessellationRun], nets: &[FixedNet], k: usize, what: &str) {
    let n = 1u64 << k;
    for (run, net) in runs.iter().zip(nets) {
        let want: Vec<(u64, u64, [i64; 3])> = fixed_grid(net, k as u32)
            .into_iter()
            .enumerate()
            .map(|(m, p)| (m as u64 / (n + 1), m as u64 % (n + 1), p))
            .collect();
        assert_eq!(run.vertices, want, "{what}: net {net:?}");
        assert!(run.last_flag_right, "{what}: out_last");
    }
}

#[test]
fn rusthdl_equals_the_fixed_point_model() {
    for (w, k) in [(16, 1), (16, 3), (24, 2), (24, 4)] {
        let nets = nets(w, 12, w as u64);
        let always = run_rusthdl(w, k, &nets, &|_| true);
        check(&always, &nets, k, "rust-hdl");
        for run in &always {
            assert_eq!(
                run.clocks,
                tessellation_clocks(k as u32),
                "W = {w}, K = {k}: clocks"
            );
            // Back to back: the first vertex at edge 2, then one per clock.
            assert!(run.edges.windows(2).all(|e| e[1] == e[0] + 1) && run.edges[0] == 2);
        }
        let stalled = run_rusthdl(w, k, &nets, &|edge| edge % 3 != 1);
        check(
            &stalled,
            &nets,
            k,
            "rust-hdl, a reader ready two clocks in three",
        );
    }
}

#[test]
fn the_emitted_unit_equals_the_model_in_verilator_and_icarus() {
    for (w, k, simulator) in [
        (16, 3, Simulator::Verilator),
        (24, 4, Simulator::Verilator),
        (24, 1, Simulator::Verilator),
        (16, 3, Simulator::Icarus),
    ] {
        let nets = nets(w, 6, 100 + w as u64);
        let runs = run_emitted(w, k, &nets, simulator).unwrap();
        check(&runs, &nets, k, &format!("{simulator:?}"));
        let model = run_rusthdl(w, k, &nets, &|_| true);
        for (hdl, ours) in runs.iter().zip(&model) {
            assert_eq!(
                (hdl.clocks, &hdl.edges),
                (ours.clocks, &ours.edges),
                "{simulator:?}: the same edges as rust-hdl"
            );
        }
    }
}

/// The tessellator with its triangles assembled: two triangles a cell in
/// the model's order (`fixed_triangles`), the pair of vertex (i, j) a clock
/// after it, `out_last` with the last pair, in rust-hdl and in the emitted
/// Verilog under Verilator and Icarus.
#[test]
fn assembled_triangles_equal_the_model() {
    use tritri_cosim::patch_triangles::{
        run_emitted as triangles_emitted, run_rusthdl as triangles_rusthdl,
    };
    use tritri_geom::bezier::fixed::fixed_triangles;
    for (w, k) in [(16, 1), (16, 3), (24, 2), (24, 4)] {
        let nets = nets(w, 6, 300 + w as u64);
        let vertices = run_rusthdl(w, k, &nets, &|_| true);
        let mut runs = vec![("rust-hdl", triangles_rusthdl(w, k, &nets))];
        runs.push((
            "Verilator",
            triangles_emitted(w, k, &nets, Simulator::Verilator).unwrap(),
        ));
        if w == 16 {
            runs.push((
                "Icarus",
                triangles_emitted(w, k, &nets, Simulator::Icarus).unwrap(),
            ));
        }
        let side = (1u64 << k) + 1;
        for (name, runs) in runs {
            for ((run, net), tess) in runs.iter().zip(&nets).zip(&vertices) {
                assert_eq!(
                    run.triangles,
                    fixed_triangles(net, k as u32),
                    "{name}, W = {w}, K = {k}"
                );
                assert!(run.last_flag_right, "{name}: out_last");
                // Each pair a clock after its vertex (i, j >= 1).
                let want: Vec<u64> = tess
                    .edges
                    .iter()
                    .enumerate()
                    .filter(|(m, _)| *m as u64 / side > 0 && *m as u64 % side > 0)
                    .map(|(_, e)| e + 1)
                    .collect();
                assert_eq!(run.edges, want, "{name}: edges");
                assert_eq!(run.clocks, tess.clocks + 1, "{name}: clocks");
            }
        }
    }
}
