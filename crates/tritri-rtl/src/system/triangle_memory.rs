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
//! clocks: the block RAM's registered read, then a register in fabric.
//! Yosys maps ECP5 block RAM without its output register (`REGMODE
//! NOREG`), whose clock-to-output is 5.8 ns; driving the bus choice and
//! the pipelines' input registers from it limited the system to 86.5 MHz.
//! Both stages hold while `read_enable` is low.

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
    id_column: SimpleDualPortRam<Bits<ID_BITS>, ADDRESS_BITS>,
    coordinate_columns: [SimpleDualPortRam<Bits<W>, ADDRESS_BITS>; 9],
    /// The output registers, after the block RAMs' read data.
    id_q: DFF<Bits<ID_BITS>>,
    coordinates_q: [DFF<Bits<W>>; 9],
}

impl<const W: usize> crate::unit::Unit for TriangleMemory<W> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            id_column,
            coordinate_columns,
            id_q,
            coordinates_q
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
            id_column: SimpleDualPortRam::new(words),
            coordinate_columns: std::array::from_fn(|_| SimpleDualPortRam::new(words)),
            id_q: Default::default(),
            coordinates_q: Default::default(),
        }
    }
}

impl<const W: usize> Logic for TriangleMemory<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, id_q);
        self.id_column.clock.next = self.clock.val();
        self.id_column.write_enable.next = self.write_enable.val();
        self.id_column.write_address.next = self.write_address.val();
        self.id_column.write_data.next = self.write_id.val();
        self.id_column.read_enable.next = self.read_enable.val();
        self.id_column.read_address.next = self.read_address.val();
        if self.read_enable.val() {
            self.id_q.d.next = self.id_column.read_data.val();
        }
        self.read_id.next = self.id_q.q.val();
        for i in 0..9 {
            self.coordinate_columns[i].clock.next = self.clock.val();
            self.coordinate_columns[i].write_enable.next = self.write_enable.val();
            self.coordinate_columns[i].write_address.next = self.write_address.val();
            self.coordinate_columns[i].write_data.next = self.write_coordinates[i].val();
            self.coordinate_columns[i].read_enable.next = self.read_enable.val();
            self.coordinate_columns[i].read_address.next = self.read_address.val();
            self.coordinates_q[i].clock.next = self.clock.val();
            self.coordinates_q[i].d.next = self.coordinates_q[i].q.val();
            if self.read_enable.val() {
                self.coordinates_q[i].d.next = self.coordinate_columns[i].read_data.val();
            }
            self.read_coordinates[i].next = self.coordinates_q[i].q.val();
        }
    }
}
