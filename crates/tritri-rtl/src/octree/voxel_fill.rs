//! The memory side of the octree engine: the plane traversal's records
//! (and, in general, any cell with a mask of children to fill) written into
//! the voxel memory a word at a time (`octree_engine.txt`: the engine keeps
//! voxel models in its memory).
//!
//! The memory holds the `2^level` grid x fastest, 64 voxels a word, voxel
//! `i` in bit `i % 64` of word `i / 64`
//! (`tritri_geom::octree::voxels::VoxelGrid`). A full child of side `s` is
//! `s^2` rows; a row is `s / 64` whole words when `s >= 64`, else `s` bits
//! of one word (a child's corner is a multiple of `s`, so a short row never
//! straddles two words). Each clock the unit offers one write: the word's
//! address and the mask of its bits to set (`word |= mask`). Rows go x
//! fastest, then y, then z, children in octant order, records in arrival
//! order; the next record is taken as the last write of the previous one
//! leaves, so a run of records costs its writes
//! (`tritri_geom::octree::plane::TraversalRun::fill_words`) and one clock
//! for each record without a child to fill.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of a word address: 1024^3 voxels are 2^24 words.
pub const ADDRESS_BITS: usize = 24;

#[derive(LogicBlock, Default)]
pub struct VoxelFill {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// The grid is `2^level` voxels a side (1 to 10), held.
    pub level: Signal<In, Bits<4>>,
    // Records in (valid/ready): a cell and the children to fill.
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_x: Signal<In, Bits<11>>,
    pub in_y: Signal<In, Bits<11>>,
    pub in_z: Signal<In, Bits<11>>,
    /// The cell's level (>= 1); its children's side is `2^(in_level - 1)`.
    pub in_level: Signal<In, Bits<4>>,
    pub in_full: Signal<In, Bits<8>>,
    // Word writes out (valid/ready).
    pub write_valid: Signal<Out, Bit>,
    pub write_ready: Signal<In, Bit>,
    pub write_address: Signal<Out, Bits<24>>,
    pub write_mask: Signal<Out, Bits<64>>,
    /// A record is being written.
    active: DFF<Bit>,
    cell_x: DFF<Bits<11>>,
    cell_y: DFF<Bits<11>>,
    cell_z: DFF<Bits<11>>,
    /// The children's level.
    child_level: DFF<Bits<4>>,
    remaining: DFF<Bits<8>>,
    /// Position inside the current child: row (dy, dz) and word along x.
    dy: DFF<Bits<11>>,
    dz: DFF<Bits<11>>,
    word: DFF<Bits<5>>,
    /// Words per row less one, set with the record (a register, so that
    /// `in_ready` depends on registers only).
    last_word: DFF<Bits<5>>,
    // Combinational.
    octant: Signal<Local, Bits<3>>,
    side: Signal<Local, Bits<11>>,
    x: Signal<Local, Bits<11>>,
    y: Signal<Local, Bits<11>>,
    z: Signal<Local, Bits<11>>,
    index: Signal<Local, Bits<30>>,
    short_row: Signal<Local, Bits<64>>,
    last_of_child: Signal<Local, Bit>,
    last_of_record: Signal<Local, Bit>,
    next_remaining: Signal<Local, Bits<8>>,
    take: Signal<Local, Bit>,
    sent: Signal<Local, Bit>,
}

impl crate::unit::Unit for VoxelFill {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            active,
            cell_x,
            cell_y,
            cell_z,
            child_level,
            remaining,
            dy,
            dz,
            word,
            last_word
        );
    }
}

impl Logic for VoxelFill {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            active,
            cell_x,
            cell_y,
            cell_z,
            child_level,
            remaining,
            dy,
            dz,
            word,
            last_word
        );
        // The current child: the lowest remaining octant.
        self.octant.next = 7.into();
        if self.remaining.q.val().get_bit(0) {
            self.octant.next = 0.into();
        } else if self.remaining.q.val().get_bit(1) {
            self.octant.next = 1.into();
        } else if self.remaining.q.val().get_bit(2) {
            self.octant.next = 2.into();
        } else if self.remaining.q.val().get_bit(3) {
            self.octant.next = 3.into();
        } else if self.remaining.q.val().get_bit(4) {
            self.octant.next = 4.into();
        } else if self.remaining.q.val().get_bit(5) {
            self.octant.next = 5.into();
        } else if self.remaining.q.val().get_bit(6) {
            self.octant.next = 6.into();
        }
        self.next_remaining.next = self.remaining.q.val() & (self.remaining.q.val() - 1);
        self.side.next = bits::<11>(1) << self.child_level.q.val();
        self.x.next = self.cell_x.q.val();
        self.y.next = self.cell_y.q.val() + self.dy.q.val();
        self.z.next = self.cell_z.q.val() + self.dz.q.val();
        if self.octant.val().get_bit(0) {
            self.x.next = self.cell_x.q.val() + self.side.val();
        }
        if self.octant.val().get_bit(1) {
            self.y.next = self.cell_y.q.val() + self.side.val() + self.dy.q.val();
        }
        if self.octant.val().get_bit(2) {
            self.z.next = self.cell_z.q.val() + self.side.val() + self.dz.q.val();
        }
        // The row's first voxel, then the word: (z n + y) n + x + 64 word.
        self.index.next = (bit_cast::<30, 11>(self.z.val())
            << (bit_cast::<5, 4>(self.level.val()) + bit_cast::<5, 4>(self.level.val())))
            + (bit_cast::<30, 11>(self.y.val()) << self.level.val())
            + bit_cast::<30, 11>(self.x.val())
            + (bit_cast::<30, 5>(self.word.q.val()) << 6);
        self.write_address.next = self.index.val().get_bits::<24>(6);
        // s ones (s < 64; the shift's six bits are 0 for longer rows).
        self.short_row.next = (bits::<64>(1) << bit_cast::<6, 11>(self.side.val())) - 1;
        self.write_mask.next = !bits::<64>(0);
        if self.child_level.q.val() < 6 {
            self.write_mask.next = self.short_row.val() << bit_cast::<6, 30>(self.index.val());
        }
        self.write_valid.next = self.active.q.val();
        self.last_of_child.next = (self.word.q.val() == self.last_word.q.val())
            & (self.dy.q.val() == self.side.val() - 1)
            & (self.dz.q.val() == self.side.val() - 1);
        self.last_of_record.next = self.last_of_child.val() & (self.next_remaining.val() == 0);
        self.sent.next = self.active.q.val() & self.write_ready.val();
        self.in_ready.next = !self.active.q.val() | (self.sent.val() & self.last_of_record.val());
        self.take.next = self.in_valid.val() & self.in_ready.val();
        // Step through words, rows, children.
        if self.sent.val() {
            if self.word.q.val() != self.last_word.q.val() {
                self.word.d.next = self.word.q.val() + 1;
            } else {
                self.word.d.next = 0.into();
                if self.dy.q.val() != self.side.val() - 1 {
                    self.dy.d.next = self.dy.q.val() + 1;
                } else {
                    self.dy.d.next = 0.into();
                    if self.dz.q.val() != self.side.val() - 1 {
                        self.dz.d.next = self.dz.q.val() + 1;
                    } else {
                        self.dz.d.next = 0.into();
                        self.remaining.d.next = self.next_remaining.val();
                        if self.next_remaining.val() == 0 {
                            self.active.d.next = false;
                        }
                    }
                }
            }
        }
        if self.take.val() {
            self.cell_x.d.next = self.in_x.val();
            self.cell_y.d.next = self.in_y.val();
            self.cell_z.d.next = self.in_z.val();
            self.child_level.d.next = self.in_level.val() - 1;
            self.remaining.d.next = self.in_full.val();
            self.word.d.next = 0.into();
            self.dy.d.next = 0.into();
            self.dz.d.next = 0.into();
            self.active.d.next = self.in_full.val() != 0;
            // Words per row less one: s / 64 - 1 for children of side s >= 64.
            self.last_word.d.next = 0.into();
            if self.in_level.val() == 8 {
                self.last_word.d.next = 1.into();
            } else if self.in_level.val() == 9 {
                self.last_word.d.next = 3.into();
            } else if self.in_level.val() == 10 {
                self.last_word.d.next = 7.into();
            }
        }
        if self.reset.val() {
            self.active.d.next = false;
        }
    }
}
