//! The accelerator's port to external memory: an AXI4 memory-mapped
//! manager, the interface of Xilinx MIG and the Zynq HP ports, of
//! LiteDRAM's AXI front end and of Intel's EMIF.
//!
//! * [`burst_reader`]: a region of memory read in INCR bursts, several
//!   outstanding, streamed out a data word (a *beat*) at a time;
//! * [`burst_writer`]: a stream of beats written in INCR bursts, each
//!   burst's write response awaited;
//! * [`beat_fifo`]: the first-word-fall-through queue in block RAM that
//!   both keep their beats in;
//! * [`axi_copy`]: a reader and a writer on one port, a region copied to
//!   another: the smallest unit that exercises every channel;
//! * [`transfer_machine`]: the cycle-exact model of the reader and the
//!   writer, and the memory model ([`memory_model`]) the co-simulations
//!   run them against.
//!
//! # The port
//!
//! One manager port, five channels, the signal names of the AXI4
//! specification (ARM IHI 0022) with an `m_axi_` prefix: `araddr`,
//! `arlen`, `arsize`, `arburst`, `arcache`, `arprot`, `arvalid`,
//! `arready`; `rdata`, `rresp`, `rlast`, `rvalid`, `rready`; `awaddr`,
//! `awlen`, `awsize`, `awburst`, `awcache`, `awprot`, `awvalid`,
//! `awready`; `wdata`, `wstrb`, `wlast`, `wvalid`, `wready`; `bresp`,
//! `bvalid`, `bready`, and one-bit IDs `arid`, `rid`, `awid`, `bid`: every
//! request has ID 0, so responses come in order, which the units rely on;
//! a response for another ID sets `error`.
//!
//! * The data width `DW` is a parameter: 64, 128, 256 or 512 bits.
//! * Addresses are 32 bits of bytes; every address the units issue is
//!   aligned to the beat (`DW / 8` bytes), so the region's base must be.
//! * Every burst is INCR of full-width beats (`arsize = log2(DW / 8)`), at
//!   most `max_burst` beats (at most 256, AXI4's limit), and never crosses
//!   a 4 KB boundary (AXI4's rule: a burst is cut at the boundary).
//! * `arcache`/`awcache` = `0011` (normal, non-cacheable, bufferable: what
//!   Xilinx's memory controllers ask of a DMA engine), `*prot` = `000`.
//! * The reader keeps at most `outstanding` bursts in flight and issues a
//!   burst only when its queue has room for every beat of it, so `rready`
//!   is always high; the writer issues a burst only when its queue holds
//!   every beat of it, so a burst's `wvalid` never falls inside the burst
//!   for want of data.
//! * A response other than OKAY (`rresp`, `bresp`) sets the unit's sticky
//!   `error`; the transfer still runs to its end, so nothing hangs.

pub mod axi_copy;
pub mod beat_fifo;
pub mod burst_reader;
pub mod burst_rule;
pub mod burst_writer;
pub mod memory_model;
pub mod transfer_machine;

/// Bits of a byte address on the port.
pub const ADDRESS_BITS: usize = 32;
/// The data widths the units are built for.
pub const DATA_WIDTHS: [usize; 4] = [64, 128, 256, 512];
/// AXI4's longest INCR burst.
pub const MAX_BURST_BEATS: usize = 256;
/// Bytes between the boundaries no burst may cross.
pub const PAGE_BYTES: u64 = 4096;
/// The most bursts a unit keeps in flight (its counter's width).
pub const MAX_OUTSTANDING: usize = 15;
/// `arburst`/`awburst` of an INCR burst.
pub const BURST_INCR: u64 = 1;
/// `arcache`/`awcache`: normal, non-cacheable, bufferable.
pub const CACHE_NORMAL_BUFFERABLE: u64 = 0b0011;

/// Beats of the longest burst at `address` that is at most `limit` beats
/// of `beat_bytes` and does not cross a 4 KB boundary: the rule both units
/// apply, and the models with them.
pub fn burst_beats(address: u64, beat_bytes: u64, limit: u64) -> u64 {
    let to_boundary = (PAGE_BYTES - address % PAGE_BYTES) / beat_bytes;
    limit.min(to_boundary)
}

/// How a reader or writer is built: its queue and how far ahead it goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TransferConfig {
    /// Data bits of the port (one of [`DATA_WIDTHS`]).
    pub data_bits: usize,
    /// The longest burst the unit issues, 1 to [`MAX_BURST_BEATS`].
    pub max_burst: usize,
    /// Bursts in flight, 1 to [`MAX_OUTSTANDING`].
    pub outstanding: usize,
    /// Beats the unit's queue holds (its block RAM and its two
    /// registers, [`beat_fifo`]).
    pub queue_beats: usize,
}

impl TransferConfig {
    /// Bytes of a beat.
    pub fn beat_bytes(&self) -> u64 {
        self.data_bits as u64 / 8
    }

    /// An error naming the parameter out of the units' range, if any.
    pub fn check(&self) -> Result<(), String> {
        if !DATA_WIDTHS.contains(&self.data_bits) {
            return Err(format!(
                "the AXI port is {DATA_WIDTHS:?} bits wide, not {}",
                self.data_bits
            ));
        }
        if self.max_burst == 0 || self.max_burst > MAX_BURST_BEATS {
            return Err(format!(
                "a burst is 1 to {MAX_BURST_BEATS} beats, not {}",
                self.max_burst
            ));
        }
        if self.outstanding == 0 || self.outstanding > MAX_OUTSTANDING {
            return Err(format!(
                "1 to {MAX_OUTSTANDING} bursts in flight, not {}",
                self.outstanding
            ));
        }
        if self.queue_beats < self.max_burst {
            return Err(format!(
                "a queue of {} beats cannot hold a burst of {}",
                self.queue_beats, self.max_burst
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bursts_stop_at_4_kb_boundaries() {
        assert_eq!(burst_beats(0, 8, 16), 16);
        assert_eq!(burst_beats(4096 - 8, 8, 16), 1);
        assert_eq!(burst_beats(4096 - 64, 64, 256), 1);
        assert_eq!(burst_beats(4096 * 3 + 1024, 64, 256), 48);
        assert_eq!(burst_beats(0, 8, 256), 256);
        assert_eq!(burst_beats(0, 64, 256), 64);
    }
}
