//! The octree engine's set-operation unit and clipper in hardware: random
//! voxel models through the unit in rust-hdl, Icarus and Verilator equal
//! the software model word for word, one word per clock; the laws of the
//! operations hold on the hardware's results (commutativity, A ∩ B ⊆ A ⊆
//! A ∪ B, De Morgan with complements formed as differences from the full
//! model, and the octree round trip of every result); octants of every
//! level against boxes across, inside and around the grid get the software
//! model's classes.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::simulator::Simulator;
use tritri_cosim::voxel_units::{
    clip_emitted, clip_rusthdl, set_operation_rusthdl, set_operations_emitted,
};
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::clip::classify;
use tritri_geom::octree::tree::{Octree, SetOperation};
use tritri_geom::octree::voxels::VoxelGrid;

const LEVEL: u32 = 4;

fn random_grid(rng: &mut ChaCha8Rng) -> VoxelGrid {
    let mut g = VoxelGrid::empty(LEVEL);
    for _ in 0..rng.gen_range(1..10) {
        let l = rng.gen_range(0..LEVEL);
        let side = 1usize << l;
        let lo = [0; 3].map(|_: usize| rng.gen_range(0..16 / side) * side);
        g.fill_cube(lo, l);
    }
    g
}

fn grid(words: Vec<u64>) -> VoxelGrid {
    VoxelGrid::from_words(LEVEL, words).expect("the unit's words form a grid")
}

#[test]
fn set_operations_in_hardware_equal_the_model_and_obey_the_laws() {
    let mut rng = ChaCha8Rng::seed_from_u64(1995);
    let full = {
        let mut g = VoxelGrid::empty(LEVEL);
        g.fill_cube([0; 3], LEVEL);
        g
    };
    let ops = [
        SetOperation::Union,
        SetOperation::Intersection,
        SetOperation::Difference,
    ];
    for round in 0..6 {
        let (a, b) = (random_grid(&mut rng), random_grid(&mut rng));
        let mut jobs: Vec<(SetOperation, &[u64], &[u64])> = Vec::new();
        for op in ops {
            jobs.push((op, a.words(), b.words()));
            jobs.push((op, b.words(), a.words()));
        }
        jobs.push((SetOperation::Difference, full.words(), a.words()));
        jobs.push((SetOperation::Difference, full.words(), b.words()));
        let rusthdl: Vec<Vec<u64>> = jobs
            .iter()
            .map(|&(op, x, y)| {
                let (words, edges) = set_operation_rusthdl(op, x, y);
                assert_eq!(
                    edges,
                    x.len() as u64 + 1,
                    "one word per clock, one clock of latency"
                );
                words
            })
            .collect();
        for (k, &(op, x, y)) in jobs.iter().enumerate() {
            let expected = grid(x.to_vec()).combine(op, &grid(y.to_vec()));
            assert_eq!(grid(rusthdl[k].clone()), expected, "round {round} job {k}");
        }
        for simulator in [Simulator::Icarus, Simulator::Verilator] {
            assert_eq!(
                set_operations_emitted(&jobs, simulator).unwrap(),
                rusthdl,
                "{simulator:?} round {round}"
            );
        }
        // The laws, on the hardware's results.
        let [union, union_ba, inter, inter_ba, diff, _, not_a, not_b] =
            [0, 1, 2, 3, 4, 5, 6, 7].map(|k| grid(rusthdl[k].clone()));
        assert_eq!(union, union_ba);
        assert_eq!(inter, inter_ba);
        let within =
            |x: &VoxelGrid, y: &VoxelGrid| x.combine(SetOperation::Difference, y).count() == 0;
        assert!(within(&inter, &a) && within(&a, &union) && within(&diff, &a));
        let (not_union, _) =
            set_operation_rusthdl(SetOperation::Difference, full.words(), union.words());
        let (both_not, _) =
            set_operation_rusthdl(SetOperation::Intersection, not_a.words(), not_b.words());
        assert_eq!(not_union, both_not, "De Morgan, round {round}");
        for g in [&union, &inter, &diff] {
            assert_eq!(&Octree::from_voxels(g).to_voxels(), g, "octree round trip");
        }
    }
}

#[test]
fn the_clipper_classifies_octants_as_the_model() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let n = 1i64 << 9;
    let boxes = [
        ([100, 100, 100], [400, 300, 350]),
        ([0, 0, 0], [512, 512, 512]),
        ([3, 0, 500], [4, 512, 512]),
        ([256, 256, 256], [257, 257, 257]),
    ];
    let mut jobs = Vec::new();
    for (lo, hi) in boxes {
        let octants: Vec<Cell> = (0..400)
            .map(|_| {
                let level = rng.gen_range(0..=9u32);
                let side = 1i64 << level;
                Cell {
                    lo: [0; 3].map(|_: i64| rng.gen_range(0..n / side) * side),
                    level,
                }
            })
            .collect();
        jobs.push((lo, hi, octants));
    }
    let emitted_jobs: Vec<([i64; 3], [i64; 3], &[Cell])> = jobs
        .iter()
        .map(|(lo, hi, o)| (*lo, *hi, o.as_slice()))
        .collect();
    let verilator = clip_emitted(&emitted_jobs, Simulator::Verilator).unwrap();
    for ((lo, hi, octants), from_verilator) in jobs.iter().zip(verilator) {
        let expected: Vec<_> = octants.iter().map(|o| classify(o, *lo, *hi)).collect();
        assert_eq!(
            clip_rusthdl(*lo, *hi, octants).unwrap(),
            expected,
            "{lo:?} {hi:?}"
        );
        assert_eq!(from_verilator, expected, "Verilator {lo:?} {hi:?}");
    }
}
