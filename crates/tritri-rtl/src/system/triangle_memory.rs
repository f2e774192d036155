//! The triangle memory of one object (thesis, chapter 4: "memories holding
//! the arrays, two banks used alternately"): `2 · depth` triangles, each
//! its nine `W`-bit coordinates and its original id. Bank `k` is the address
//! range `[k · depth, (k + 1) · depth)`; the address generator writes the
//! next batch into one bank while it reads the other, so one simple
//! dual-port memory per object does both at once.
//!
//! Ten columns (nine coordinates, one id) share the addresses; each is a
//! [`SimpleDualPortRam`]. The coordinates are `x0 y0 z0 x1 y1 z1 x2 y2 z2`,
//! signed `W`-bit two's complement, as on the pipeline's input bus.
//!
//! A read takes [`MEMORY_READ_LATENCY`](super::MEMORY_READ_LATENCY) = 2
//! clocks: the block RAM's registered read, then its output register
//! (each column [`SimpleDualPortRam::with_output_register`]). Without the
//! second register an ECP5 block RAM (`REGMODE NOREG`) takes 5.8 ns from
//! clock to data; driving the bus choice and the pipelines' input
//! registers from it limited the system to 86.5 MHz. Yosys puts the
//! second register in fabric, which still leaves those 5.8 ns and a wire
//! before it (113.8 MHz, W = 16, P = 1); `--dsp ecp5` puts it in the
//! DP16KD ([`crate::emit::block_ram_mapping`]). Both stages hold while
//! `read_enable` is low.
//!
//! A write lands a clock after its transfer: enable, address, id and
//! coordinates pass through one register each before the columns. The
//! enable and address come from the address generator's handshake
//! (`bank_full` → `in_ready` → the transfer), and the enable fans out to
//! every block RAM of the memory; unregistered, that was the critical path
//! of the two-pipeline system at W = 8 (7.50 ns, 4.5 ns of it the one
//! route to the id column's `WEA`). The extra clock costs nothing: the
//! end-of-batch word follows a bank's last triangle by a clock at least,
//! and the read side first reads a bank two clocks after that word (it
//! sees the bank full a clock after it, and reads from the next), so the
//! last write is in place a clock before the first read.

use super::dual_port_ram::SimpleDualPortRam;
use super::{ADDRESS_BITS, ID_BITS};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock)]
pub struct TriangleMemory<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Signal<In, Bit>,
    pub write_address: Signal<In, Bits<ADDRESS_BITS>>,
    pub write_id: Signal<In, Bits<ID_BITS>>,
    pub write_coordinates: [Signal<In, Bits<W>>; 9],
    pub read_enable: Signal<In, Bit>,
    pub read_address: Signal<In, Bits<ADDRESS_BITS>>,
    pub read_id: Signal<Out, Bits<ID_BITS>>,
    pub read_coordinates: [Signal<Out, Bits<W>>; 9],
    /// The write port, a clock later.
    write_enable_q: DFF<Bit>,
    write_address_q: DFF<Bits<ADDRESS_BITS>>,
    write_id_q: DFF<Bits<ID_BITS>>,
    write_coordinates_q: [DFF<Bits<W>>; 9],
    id_column: SimpleDualPortRam<Bits<ID_BITS>, ADDRESS_BITS>,
    coordinate_columns: [SimpleDualPortRam<Bits<W>, ADDRESS_BITS>; 9],
}

impl<const W: usize> crate::unit::Unit for TriangleMemory<W> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            write_enable_q,
            write_address_q,
            write_id_q,
            write_coordinates_q,
            id_column,
            coordinate_columns
        );
    }
}

impl<const W: usize> TriangleMemory<W> {
    /// A memory of two banks of `triangles_per_bank` triangles each.
    pub fn new(triangles_per_bank: usize) -> Self {
        let words = 2 * triangles_per_bank;
        TriangleMemory {
            clock: Default::default(),
            write_enable: Default::default(),
            write_address: Default::default(),
            write_id: Default::default(),
            write_coordinates: Default::default(),
            read_enable: Default::default(),
            read_address: Default::default(),
            read_id: Default::default(),
            read_coordinates: Default::default(),
            write_enable_q: Default::default(),
            write_address_q: Default::default(),
            write_id_q: Default::default(),
            write_coordinates_q: Default::default(),
            id_column: SimpleDualPortRam::with_output_register(words),
            coordinate_columns: std::array::from_fn(|_| {
                SimpleDualPortRam::with_output_register(words)
            }),
        }
    }
}

impl<const W: usize> Logic for TriangleMemory<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, write_enable_q, write_address_q, write_id_q);
        self.write_enable_q.d.next = self.write_enable.val();
        self.write_address_q.d.next = self.write_address.val();
        self.write_id_q.d.next = self.write_id.val();
        self.id_column.clock.next = self.clock.val();
        self.id_column.write_enable.next = self.write_enable_q.q.val();
        self.id_column.write_address.next = self.write_address_q.q.val();
        self.id_column.write_data.next = self.write_id_q.q.val();
        self.id_column.read_enable.next = self.read_enable.val();
        self.id_column.read_address.next = self.read_address.val();
        self.read_id.next = self.id_column.read_data.val();
        for i in 0..9 {
            self.write_coordinates_q[i].clock.next = self.clock.val();
            self.write_coordinates_q[i].d.next = self.write_coordinates[i].val();
            self.coordinate_columns[i].clock.next = self.clock.val();
            self.coordinate_columns[i].write_enable.next = self.write_enable_q.q.val();
            self.coordinate_columns[i].write_address.next = self.write_address_q.q.val();
            self.coordinate_columns[i].write_data.next = self.write_coordinates_q[i].q.val();
            self.coordinate_columns[i].read_enable.next = self.read_enable.val();
            self.coordinate_columns[i].read_address.next = self.read_address.val();
            self.read_coordinates[i].next = self.coordinate_columns[i].read_data.val();
        }
    }
}
