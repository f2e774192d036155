//! The software baseline, measured: the project's exact software path (box
//! sweep, exact predicates on the f64 coordinates, triangles in memory) on
//! one and two threads beside CGAL's `box_intersection_d` with
//! `do_intersect` on its exact-predicates kernel, one thread, in the same
//! run on the same triangles. The pairs must be the same set; the times are
//! medians of repeated runs, and the ratios are what every speed line of
//! the project is measured against (issue 66).
//!
//!   cargo run --release --example software_baseline -- [A B [SCALE_B TX TY TZ]] [--repeats N]
//!
//! Without a scene: the built-in torus and sphere.

use anyhow::{ensure, Context as _};
use std::time::Duration;
use tritri_cosim::cgal::cgal_pairs;
use tritri_examples::{median_time, scene_objects, take_option};
use tritri_geom::scene::reference::{exact_f64_pairs, exact_f64_pairs_threads};

fn main() -> anyhow::Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let repeats: usize = match take_option(&mut args, "--repeats", "a count of runs")? {
        None => 5,
        Some(n) => n
            .parse()
            .ok()
            .filter(|&n| n >= 1)
            .with_context(|| format!("--repeats {n:?}: a count of runs, 1 or more"))?,
    };
    let (a, b) = scene_objects(&args, "software_baseline")?;
    println!(
        "scene: A = {} ({} triangles), B = {} ({} triangles)",
        a.name,
        a.triangles.len(),
        b.name,
        b.triangles.len()
    );
    let one = exact_f64_pairs(&a.triangles, &b.triangles);
    let ours_one = median_time(repeats, || {
        std::hint::black_box(exact_f64_pairs(&a.triangles, &b.triangles));
    });
    let two = exact_f64_pairs_threads(&a.triangles, &b.triangles, 2);
    let ours_two = median_time(repeats, || {
        std::hint::black_box(exact_f64_pairs_threads(&a.triangles, &b.triangles, 2));
    });
    let cgal = cgal_pairs(&a.triangles, &b.triangles, repeats)?;
    ensure!(
        two.pairs == one.pairs,
        "two threads found other pairs than one"
    );
    ensure!(
        cgal.pairs == one.pairs,
        "CGAL: {} pairs, ours {} ({} only CGAL's, {} only ours)",
        cgal.pairs.len(),
        one.pairs.len(),
        cgal.pairs.difference(&one.pairs).count(),
        one.pairs.difference(&cgal.pairs).count()
    );
    let cgal_time = cgal.median();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!(
        "pairs: {} intersecting, the same set from CGAL and from ours; boxes overlapping: CGAL {}, ours {}",
        one.pairs.len(),
        cgal.box_pairs,
        one.pairs_decided
    );
    println!("time (median of {repeats}):");
    println!(
        "  CGAL box_intersection_d + do_intersect (Epick), 1 thread: {:.3} ms",
        ms(cgal_time)
    );
    println!(
        "  ours, box sweep + exact predicates, 1 thread: {:.3} ms ({:.2} x CGAL's speed)",
        ms(ours_one),
        cgal_time.as_secs_f64() / ours_one.as_secs_f64()
    );
    println!(
        "  ours, 2 threads: {:.3} ms ({:.2} x CGAL's speed)",
        ms(ours_two),
        cgal_time.as_secs_f64() / ours_two.as_secs_f64()
    );
    Ok(())
}
