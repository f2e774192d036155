//! The orient3d unit alone: its sign equals the sign of
//! `tritri_geom::fixed_point::orient3d_value`, and its Verilog is valid.

use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::orient3d_value;
use tritri_rtl::arith::convert::from_i128;
use tritri_rtl::pipeline::orient3d::{Orient3d, ORIENT3D_LATENCY};
use tritri_rtl::sim_drive::clock_cycle;

type Unit = Orient3d<24, 25, 49, 74>;

fn set_point(sig: &mut [Signal<In, Bits<24>>; 3], p: [i64; 3]) {
    for k in 0..3 {
        sig[k].next = from_i128::<24>(p[k] as i128);
    }
}

#[test]
fn orient3d_sign_matches_software_at_w24() {
    let mut uut = Unit::default();
    uut.clock.connect();
    uut.advance.connect();
    for i in 0..3 {
        uut.a[i].connect();
        uut.b[i].connect();
        uut.c[i].connect();
        uut.d[i].connect();
    }
    uut.connect_all();
    uut.advance.next = true;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let lim = 1i64 << 23;
    let mut points = Vec::new();
    for n in 0..300 {
        let mut p = [[0i64; 3]; 4];
        for q in p.iter_mut() {
            for c in q.iter_mut() {
                *c = match n % 3 {
                    0 => rng.gen_range(-lim..lim),
                    1 => {
                        if rng.gen_bool(0.5) {
                            -lim
                        } else {
                            lim - 1
                        }
                    }
                    _ => rng.gen_range(-2..2),
                };
            }
        }
        points.push(p);
    }
    let mut got = Vec::new();
    for cycle in 0..points.len() + ORIENT3D_LATENCY {
        if let Some(p) = points.get(cycle) {
            set_point(&mut uut.a, p[0]);
            set_point(&mut uut.b, p[1]);
            set_point(&mut uut.c, p[2]);
            set_point(&mut uut.d, p[3]);
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        if cycle + 1 >= ORIENT3D_LATENCY {
            got.push((uut.negative.val(), uut.zero.val()));
        }
    }
    for (p, g) in points.iter().zip(&got) {
        let v = orient3d_value(p[0], p[1], p[2], p[3]);
        assert_eq!(*g, (v < 0, v == 0), "points {p:?} value {v}");
    }
    // rust-hdl's checks (connectivity, logic loops) pass and it emits Verilog.
    assert!(generate_verilog(&uut).contains("module top("));
}
