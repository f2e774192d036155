//! The emitted AXI copy unit ([`crate::axi::axi_copy`]): its name, ports
//! and the widths it is built for.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::axi::axi_copy::{AxiCopy, COPY_QUEUE_ADDRESS_BITS};
use crate::axi::TransferConfig;
use rust_hdl::prelude::*;

/// How a copy unit is built: the port's width and the units' bursts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxiCopyConfig {
    pub data_bits: usize,
    pub max_burst: usize,
    pub outstanding: usize,
}

impl AxiCopyConfig {
    /// `tritri_axi_copy_d<DW>_b<max burst>_o<outstanding>`.
    pub fn unit_name(&self) -> String {
        format!(
            "tritri_axi_copy_d{}_b{}_o{}",
            self.data_bits, self.max_burst, self.outstanding
        )
    }

    /// The reader's and the writer's configuration.
    pub fn transfer(&self) -> TransferConfig {
        TransferConfig {
            data_bits: self.data_bits,
            max_burst: self.max_burst,
            outstanding: self.outstanding,
            queue_beats: (1 << COPY_QUEUE_ADDRESS_BITS) + 2,
        }
    }
}

/// rust-hdl's Verilog of the unit.
pub fn raw_axi_copy_verilog(config: &AxiCopyConfig) -> Result<crate::unit::RawDesign, String> {
    config.transfer().check()?;
    fn raw<const DW: usize, const S: usize>(c: &AxiCopyConfig) -> crate::unit::RawDesign {
        let mut uut = AxiCopy::<DW, S, COPY_QUEUE_ADDRESS_BITS>::new(c.max_burst, c.outstanding);
        uut.connect_all();
        crate::unit::RawDesign::of(&uut)
    }
    Ok(match config.data_bits {
        64 => raw::<64, 8>(config),
        128 => raw::<128, 16>(config),
        256 => raw::<256, 32>(config),
        _ => raw::<512, 64>(config),
    })
}

/// The description of the unit for the emitter.
pub fn axi_copy_unit(config: &AxiCopyConfig) -> UnitDescription {
    let dw = config.data_bits;
    let mut unit = UnitDescription::new(
        &config.unit_name(),
        "A region of external memory copied to another through one AXI4 manager port: \
         a burst reader streams the source into a burst writer.",
    )
    .detail(&format!(
        "Bursts are INCR of {dw}-bit beats, at most {} beats, never across a 4 KB boundary; at most {} \
         in flight per direction. Reads are issued only when the queue has room for the whole burst \
         (rready is always high); writes only when the queue holds the whole burst.",
        config.max_burst, config.outstanding
    ))
    .detail(
        "Cycles: tritri_rtl::axi::transfer_machine::CopyModel, clock-exact against the memory model \
         tritri_rtl::axi::memory_model.",
    )
    .parameter("DATA_BITS", &format!("{dw}: bits of a beat"))
    .parameter("MAX_BURST", &format!("{}: beats of the longest burst", config.max_burst))
    .parameter("OUTSTANDING", &format!("{}: bursts in flight per direction", config.outstanding))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high.")
    .port("start", "One clock high while not busy: copy `beats` beats from `source` to `destination`.")
    .port("source", "Byte address of the first beat to read, aligned to the beat.")
    .port("destination", "Byte address of the first beat to write, aligned to the beat.")
    .port("beats", "Beats to copy.")
    .port("busy", "From the clock after `start` to the end of the copy.")
    .port("done", "High from the end of a copy (every write response in) until the next `start`.")
    .port("error", "A read or write response of the last copy was not OKAY.");
    for (name, meaning) in axi_manager_ports() {
        unit = unit.port(name, meaning);
    }
    unit.throughput("a beat per clock each way once the memory's latency is covered")
}

/// The AXI4 manager port's signals and what they carry (module docs of
/// [`crate::axi`]).
pub fn axi_manager_ports() -> Vec<(&'static str, &'static str)> {
    vec![
        ("m_axi_arid", "AXI4 AR: 0 (one ID: responses in order)."),
        ("m_axi_araddr", "AXI4 AR: byte address of a read burst."),
        ("m_axi_arlen", "AXI4 AR: beats of the burst, minus one."),
        (
            "m_axi_arsize",
            "AXI4 AR: log2 of the bytes of a beat (full width).",
        ),
        ("m_axi_arburst", "AXI4 AR: 01, INCR."),
        (
            "m_axi_arcache",
            "AXI4 AR: 0011, normal non-cacheable bufferable.",
        ),
        ("m_axi_arprot", "AXI4 AR: 000."),
        ("m_axi_arvalid", "AXI4 AR: a read burst is requested."),
        ("m_axi_arready", "AXI4 AR: the memory takes the request."),
        ("m_axi_rid", "AXI4 R: the beat's ID; not 0 sets `error`."),
        (
            "m_axi_rdata",
            "AXI4 R: a beat, lowest address in the lowest byte.",
        ),
        (
            "m_axi_rresp",
            "AXI4 R: the beat's response; not OKAY sets `error`.",
        ),
        ("m_axi_rlast", "AXI4 R: the burst's last beat."),
        ("m_axi_rvalid", "AXI4 R: a beat is offered."),
        (
            "m_axi_rready",
            "AXI4 R: always high (the reader's queue has room for every beat it asked for).",
        ),
        ("m_axi_awid", "AXI4 AW: 0 (one ID: responses in order)."),
        ("m_axi_awaddr", "AXI4 AW: byte address of a write burst."),
        ("m_axi_awlen", "AXI4 AW: beats of the burst, minus one."),
        (
            "m_axi_awsize",
            "AXI4 AW: log2 of the bytes of a beat (full width).",
        ),
        ("m_axi_awburst", "AXI4 AW: 01, INCR."),
        (
            "m_axi_awcache",
            "AXI4 AW: 0011, normal non-cacheable bufferable.",
        ),
        ("m_axi_awprot", "AXI4 AW: 000."),
        ("m_axi_awvalid", "AXI4 AW: a write burst is requested."),
        ("m_axi_awready", "AXI4 AW: the memory takes the request."),
        (
            "m_axi_wdata",
            "AXI4 W: a beat, lowest address in the lowest byte.",
        ),
        ("m_axi_wstrb", "AXI4 W: all ones (whole beats are written)."),
        ("m_axi_wlast", "AXI4 W: the burst's last beat."),
        (
            "m_axi_wvalid",
            "AXI4 W: a beat is offered (only beats of requested bursts).",
        ),
        ("m_axi_wready", "AXI4 W: the memory takes the beat."),
        (
            "m_axi_bid",
            "AXI4 B: the response's ID; not 0 sets `error`.",
        ),
        (
            "m_axi_bresp",
            "AXI4 B: the burst's response; not OKAY sets `error`.",
        ),
        ("m_axi_bvalid", "AXI4 B: a write response is offered."),
        ("m_axi_bready", "AXI4 B: always high."),
    ]
}

/// A copy unit that cannot be built, or could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum AxiEmitError {
    #[error("AXI copy unit: {0}")]
    Config(String),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// The emitted copy unit.
pub fn emit_axi_copy(config: &AxiCopyConfig) -> Result<EmittedDesign, AxiEmitError> {
    let raw = raw_axi_copy_verilog(config).map_err(AxiEmitError::Config)?;
    Ok(emit(&raw, &axi_copy_unit(config))?)
}
