//! What the Icarus and Verilator runners share: the design under test as
//! emitted Verilog, the testbench, work directories and the run record.

use crate::stream::StreamResult;
use crate::vectors::TimedVerdict;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use tritri_rtl::emit::EmittedDesign;

/// The testbench, compiled into the library so runs need no checkout.
pub const TESTBENCH: &str = include_str!("../../../testbenches/tb_triangle_pipeline.sv");
/// Its top module.
pub const TESTBENCH_TOP: &str = "tb_triangle_pipeline";

/// An emitted pipeline and the facts the testbench needs about it.
#[derive(Clone, Debug)]
pub struct RtlDut {
    pub design: EmittedDesign,
    /// Coordinate width W.
    pub width: u32,
    /// Width of the ids on the bus.
    pub id_bits: u32,
    /// Pipeline latency L.
    pub latency: u64,
}

impl RtlDut {
    /// The Verilog files (name, contents), top first.
    pub fn verilog(&self) -> impl Iterator<Item = (&str, &str)> {
        self.design.verilog_files().map(|f| (f.path.as_str(), f.contents.as_str()))
    }

    /// A stable 64-bit fingerprint of everything a build depends on.
    pub fn fingerprint(&self, extra: &str) -> u64 {
        let mut h = Fnv1a::default();
        for (name, text) in self.verilog() {
            h.write(name.as_bytes());
            h.write(text.as_bytes());
        }
        h.write(TESTBENCH.as_bytes());
        h.write(format!("{} {} {}", self.width, self.id_bits, extra).as_bytes());
        h.0
    }
}

/// FNV-1a: a hash that is the same in every build (the cache key must be).
struct Fnv1a(u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv1a {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// One simulation run of emitted Verilog.
#[derive(Clone, Debug)]
pub struct RtlRun {
    pub result: StreamResult,
    /// Every verdict with the cycle it appeared in.
    pub timed: Vec<TimedVerdict>,
    /// Seconds spent compiling (0 for a cached Verilator build).
    pub build_seconds: f64,
    /// Seconds spent simulating (including reading and writing the files).
    pub simulate_seconds: f64,
}

/// A directory removed on drop (unless `TRITRI_KEEP_WORK` is set, for debugging).
pub struct WorkDir {
    pub path: PathBuf,
}

impl WorkDir {
    pub fn new(label: &str) -> std::io::Result<Self> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let path = std::env::temp_dir().join(format!(
            "tritri-{label}-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path)?;
        tritri_rtl::tools::interrupt::register_temporary(&path);
        Ok(WorkDir { path })
    }
    pub fn join(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        tritri_rtl::tools::interrupt::unregister_temporary(&self.path);
        if std::env::var_os("TRITRI_KEEP_WORK").is_none() {
            let _ = std::fs::remove_dir_all(&self.path);
        } else {
            eprintln!("tritri: kept work directory {}", self.path.display());
        }
    }
}

/// Writes the DUT's Verilog and the testbench into `dir`; returns the
/// paths, testbench first.
pub fn write_sources(dut: &RtlDut, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut paths = vec![dir.join("tb_triangle_pipeline.sv")];
    std::fs::write(&paths[0], TESTBENCH)?;
    for (name, text) in dut.verilog() {
        let p = dir.join(name);
        std::fs::write(&p, text)?;
        paths.push(p);
    }
    Ok(paths)
}

/// The emitted `width`-bit pipeline as a DUT, emitted once per process.
pub fn pipeline_dut(width: usize) -> anyhow::Result<std::sync::Arc<RtlDut>> {
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex, OnceLock};
    static CACHE: OnceLock<Mutex<HashMap<usize, Arc<RtlDut>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(d) = cache.lock().unwrap().get(&width) {
        return Ok(d.clone());
    }
    let design = tritri_rtl::emit::emit_pipeline(width)?;
    let dut = Arc::new(RtlDut {
        design,
        width: width as u32,
        id_bits: tritri_rtl::pipeline::ID_BITS as u32,
        latency: tritri_rtl::pipeline::triangle_pipeline::latency() as u64,
    });
    cache.lock().unwrap().insert(width, dut.clone());
    Ok(dut)
}

/// `(id, triangle)` lists as a stream.
pub fn stream_of(
    bases: &[(u32, tritri_geom::fixed_point::FixedTriangle)],
    streamed: &[(u32, tritri_geom::fixed_point::FixedTriangle)],
) -> crate::stream::TriangleStream {
    use crate::stream::IdTriangle;
    crate::stream::TriangleStream {
        bases: bases.iter().map(|&(id, triangle)| IdTriangle { id, triangle }).collect(),
        streamed: streamed.iter().map(|&(id, triangle)| IdTriangle { id, triangle }).collect(),
    }
}
