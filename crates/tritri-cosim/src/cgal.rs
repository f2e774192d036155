//! The best software as the baseline: CGAL's query on the same f64
//! triangles, in the same run. `cgal/cgal_pairs.cpp` is CGAL's
//! `box_intersection_d` over the triangles' boxes with `do_intersect` on
//! its exact-predicates kernel, one thread, timed from triangles in memory;
//! it is compiled here, once per source, with g++ against Debian's
//! `libcgal-dev` (scripts/setup.sh installs it), like the simulators'
//! testbenches.

use crate::simulator::{cache_root, fingerprint, WorkDir};
use anyhow::{bail, Context as _};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;
use tritri_geom::scene::reference::PairSet;
use tritri_geom::triangle::Triangle;

/// The program's source.
const SOURCE: &str = include_str!("../cgal/cgal_pairs.cpp");
/// The header whose absence means CGAL is not installed.
const CGAL_HEADER: &str = "/usr/include/CGAL/box_intersection_d.h";

/// CGAL's answer and what it took.
#[derive(Clone, Debug)]
pub struct CgalRun {
    /// The intersecting pairs `(index in A, index in B)`.
    pub pairs: PairSet,
    /// Pairs whose boxes overlap (each decided by `do_intersect`).
    pub box_pairs: u64,
    /// Each repetition's time, boxes to the last pair, triangles in memory.
    pub times: Vec<Duration>,
}

impl CgalRun {
    /// The median repetition.
    pub fn median(&self) -> Duration {
        let mut times = self.times.clone();
        times.sort();
        times[times.len() / 2]
    }
}

/// The compiled program, built once per source into the cache
/// ([`cache_root`], as the simulators' images are); concurrent callers each
/// build into a file of their own and rename it into place.
fn program() -> anyhow::Result<PathBuf> {
    let dir = cache_root().join(format!("cgal-{:016x}", fingerprint([SOURCE])));
    let image = dir.join("cgal_pairs");
    if image.exists() {
        return Ok(image);
    }
    if !Path::new(CGAL_HEADER).exists() {
        bail!("CGAL is not installed ({CGAL_HEADER} is missing): install Debian's libcgal-dev (bash scripts/setup.sh does)");
    }
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let source = dir.join("cgal_pairs.cpp");
    std::fs::write(&source, SOURCE).with_context(|| format!("writing {}", source.display()))?;
    let building = dir.join(format!("cgal_pairs.{}", std::process::id()));
    let output = Command::new("g++")
        .args(["-O2", "-DNDEBUG", "-std=c++17", "-o"])
        .arg(&building)
        .arg(&source)
        .args(["-lgmp", "-lmpfr"])
        .output()
        .context("running g++ to build CGAL's baseline (is g++ installed?)")?;
    if !output.status.success() {
        bail!(
            "g++ could not build {}:\n{}",
            source.display(),
            String::from_utf8_lossy(&output.stderr)
        );
    }
    std::fs::rename(&building, &image)
        .with_context(|| format!("moving {} into place", building.display()))?;
    Ok(image)
}

/// CGAL's pairs of `a` × `b`, its query run `repeats` times (at least once).
pub fn cgal_pairs(a: &[Triangle], b: &[Triangle], repeats: usize) -> anyhow::Result<CgalRun> {
    let image = program()?;
    let work = WorkDir::new("cgal").context("a directory for CGAL's input")?;
    let input = work.join("triangles.bin");
    let mut bytes = Vec::with_capacity(16 + 72 * (a.len() + b.len()));
    bytes.extend((a.len() as u64).to_le_bytes());
    bytes.extend((b.len() as u64).to_le_bytes());
    for t in a.iter().chain(b) {
        for p in t {
            for c in p {
                bytes.extend(c.to_le_bytes());
            }
        }
    }
    std::fs::File::create(&input)
        .and_then(|mut f| f.write_all(&bytes))
        .with_context(|| format!("writing {}", input.display()))?;
    let pairs_path = work.join("pairs.txt");
    let output = Command::new(&image)
        .arg(&input)
        .arg(repeats.max(1).to_string())
        .arg(&pairs_path)
        .output()
        .with_context(|| format!("running {}", image.display()))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        bail!(
            "{} failed ({}):\n{}{}",
            image.display(),
            output.status,
            stdout,
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let mut times = Vec::new();
    let mut box_pairs = None;
    for line in stdout.lines() {
        let bad = || format!("CGAL's baseline printed `{line}`");
        match line.split_once(' ') {
            Some(("seconds", s)) => {
                times.push(Duration::from_secs_f64(s.parse().with_context(bad)?))
            }
            Some(("boxes", n)) => box_pairs = Some(n.parse().with_context(bad)?),
            Some(("pairs", _)) => {}
            _ => bail!(bad()),
        }
    }
    let text = std::fs::read_to_string(&pairs_path)
        .with_context(|| format!("reading {}", pairs_path.display()))?;
    let mut pairs = PairSet::new();
    for line in text.lines() {
        let pair = line
            .split_once(' ')
            .and_then(|(i, j)| Some((i.parse().ok()?, j.parse().ok()?)))
            .with_context(|| format!("CGAL's pair line `{line}`"))?;
        pairs.insert(pair);
    }
    if times.len() != repeats.max(1) {
        bail!(
            "CGAL's baseline printed {} times for {} runs",
            times.len(),
            repeats.max(1)
        );
    }
    Ok(CgalRun {
        pairs,
        box_pairs: box_pairs.context("CGAL's baseline printed no `boxes` line")?,
        times,
    })
}
