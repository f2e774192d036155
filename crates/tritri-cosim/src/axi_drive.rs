//! The rust-hdl side of an AXI4 manager port against the Rust memory model
//! ([`tritri_rtl::axi::memory_model`]), for every unit whose port has the
//! `m_axi_` names: the memory's outputs onto the unit's inputs, and the
//! unit's outputs as the memory's [`ManagerSignals`], and the clock loop to
//! `done` (macros, because the units are different types with the same
//! field names); and the simulator side both AXI testbenches share: the
//! memory model's parameters, its hex file, the status line and the dump.
//!
//! [`ManagerSignals`]: tritri_rtl::axi::memory_model::ManagerSignals

/// Drives `$uut`'s subordinate-side inputs from `$out`
/// (`AxiMemory::outputs()`): OKAY responses, ID 0.
macro_rules! drive_from_memory {
    ($uut:expr, $out:expr, $dw:expr) => {{
        let out = $out;
        $uut.m_axi_arready.next = out.arready;
        $uut.m_axi_rvalid.next = out.rvalid;
        $uut.m_axi_rdata.next = $crate::axi_copy::bits_of::<$dw>(&out.rdata);
        $uut.m_axi_rlast.next = out.rlast;
        $uut.m_axi_rresp.next = 0.into();
        $uut.m_axi_rid.next = false;
        $uut.m_axi_bid.next = false;
        $uut.m_axi_awready.next = out.awready;
        $uut.m_axi_wready.next = out.wready;
        $uut.m_axi_bvalid.next = out.bvalid;
        $uut.m_axi_bresp.next = 0.into();
    }};
}

/// `$uut`'s manager-side outputs, settled, as the memory model reads them.
macro_rules! manager_signals {
    ($uut:expr, $dw:expr) => {
        tritri_rtl::axi::memory_model::ManagerSignals {
            arvalid: $uut.m_axi_arvalid.val(),
            araddr: $uut.m_axi_araddr.val().to_u64(),
            arlen: $uut.m_axi_arlen.val().to_u64(),
            arsize: $uut.m_axi_arsize.val().to_u64(),
            arburst: $uut.m_axi_arburst.val().to_u64(),
            rready: $uut.m_axi_rready.val(),
            awvalid: $uut.m_axi_awvalid.val(),
            awaddr: $uut.m_axi_awaddr.val().to_u64(),
            awlen: $uut.m_axi_awlen.val().to_u64(),
            awsize: $uut.m_axi_awsize.val().to_u64(),
            awburst: $uut.m_axi_awburst.val().to_u64(),
            wvalid: $uut.m_axi_wvalid.val(),
            wdata: $crate::axi_copy::bytes_of::<$dw>($uut.m_axi_wdata.val()),
            wlast: $uut.m_axi_wlast.val(),
            bready: $uut.m_axi_bready.val(),
        }
    };
}

pub(crate) use {drive_from_memory, manager_signals};

/// Clocks `$uut` against `$memory` from `start` in clock 0 until `done`,
/// at most `$limit` clocks (an error naming `$what` past it); the clocks.
macro_rules! clock_until_done {
    ($uut:expr, $memory:expr, $dw:expr, $limit:expr, $what:expr) => {{
        let mut cycles = 0u64;
        loop {
            let out = $memory.outputs();
            $uut.start.next = cycles == 0;
            drive_from_memory!($uut, &out, $dw);
            tritri_rtl::sim_drive::settle(&mut $uut);
            let manager = manager_signals!($uut, $dw);
            $memory.edge(&manager);
            tritri_rtl::sim_drive::clock_cycle(&mut $uut, |u| &mut u.clock);
            cycles += 1;
            if $uut.done.val() {
                break;
            }
            if cycles >= $limit {
                anyhow::bail!(
                    "the rust-hdl {} did not end within {} clocks",
                    $what,
                    $limit
                );
            }
        }
        cycles
    }};
}

pub(crate) use clock_until_done;

/// The memory model's testbench parameters (`testbenches/axi_memory.sv`)
/// for `params` and a memory of `bytes` bytes.
pub(crate) fn memory_parameters(
    params: &tritri_rtl::axi::memory_model::MemoryParams,
    bytes: u64,
) -> Vec<(String, String)> {
    [
        ("BYTES", bytes),
        ("READ_LATENCY", params.read_latency),
        ("WRITE_LATENCY", params.write_latency),
        ("OUTSTANDING", params.outstanding as u64),
        ("BPC_NUM", params.bytes_per_clock.0),
        ("BPC_DEN", params.bytes_per_clock.1),
        ("STALL_PERCENT", u64::from(params.stall_percent)),
        ("SEED", u64::from(params.seed)),
    ]
    .iter()
    .map(|(n, v)| (n.to_string(), v.to_string()))
    .collect()
}

/// Writes `bytes` as the testbenches' `+memory=` file: hex, a byte a line.
pub(crate) fn write_memory_hex(path: &std::path::Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut hex = String::with_capacity(3 * bytes.len());
    for b in bytes {
        let _ = writeln!(hex, "{b:02x}");
    }
    std::fs::write(path, hex)
}

/// The status line both AXI testbenches print:
/// `# cycles N stalled S faults F error E done D`.
pub(crate) struct RunStatus {
    pub cycles: u64,
    pub stalled: u64,
    pub faults: usize,
    pub error: bool,
    pub done: bool,
}

/// [`RunStatus`] from a testbench's standard output.
pub(crate) fn parse_status(text: &str) -> anyhow::Result<RunStatus> {
    use anyhow::Context as _;
    let line = text
        .lines()
        .find(|l| l.starts_with("# cycles "))
        .with_context(|| format!("the testbench printed no cycles:\n{text}"))?;
    let field = |name: &str| -> anyhow::Result<u64> {
        let mut words = line.split_whitespace();
        while let Some(w) = words.next() {
            if w == name {
                return words
                    .next()
                    .and_then(|v| v.parse().ok())
                    .with_context(|| format!("no number after {name} in {line:?}"));
            }
        }
        anyhow::bail!("no {name} in {line:?}")
    };
    Ok(RunStatus {
        cycles: field("cycles")?,
        stalled: field("stalled")?,
        faults: field("faults")? as usize,
        error: field("error")? != 0,
        done: field("done")? == 1,
    })
}

/// The first `bytes` bytes of a memory written by `$writememh`, a byte a
/// line (the rest, which the testbench never loaded, may be unknown).
pub(crate) fn read_memory_dump(path: &std::path::Path, bytes: usize) -> anyhow::Result<Vec<u8>> {
    use anyhow::Context as _;
    std::fs::read_to_string(path)
        .with_context(|| format!("the memory dump {}", path.display()))?
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("//") && !l.starts_with('@'))
        .take(bytes)
        .map(|l| u8::from_str_radix(l, 16).with_context(|| format!("memory dump line {l:?}")))
        .collect()
}
