//! The stack of the octree engine's depth-first traversals (the plane
//! traversal, [`super::plane_traversal`], and the triangle voxelizer,
//! [`super::triangle_voxelizer`]): which cell to issue each clock, and the
//! cells with children still to classify. Its cycle model is
//! `tritri_geom::octree::stack_schedule::StackSchedule`.
//!
//! Each clock it issues the root after `start`, else the lowest remaining
//! child of the top (its corner and level worked out here). A result with
//! children to descend into is pushed: it becomes the top, and the old top,
//! if it has children left, goes to the block RAM. A top whose last child is
//! issued is dropped, and the next comes back from the RAM the clock after
//! (no issue that clock) unless a push takes its place.
//!
//! The cells' values (the affine functions at a cell's low corner, which the
//! classifier interpolates) are the caller's: it keeps the top's in
//! registers and the rest in RAMs of its own, driven by this unit's write
//! and read ports, and loads its top values from the pushed result when
//! `take_pushed` is high and from its RAMs' read data when `take_read` is.
//! A push into a full RAM raises the sticky `overflow`.

use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// A cell on the stack: its low corner in voxels, its level and the
/// children still to classify.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct StackCell {
    pub x: Bits<11>,
    pub y: Bits<11>,
    pub z: Bits<11>,
    pub level: Bits<4>,
    pub mask: Bits<8>,
}

#[derive(LogicBlock)]
pub struct TraversalStack<const S: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: idle, empty, overflow cleared.
    pub reset: Signal<In, Bit>,
    /// Everything moves (low while the caller's output waits).
    pub advance: Signal<In, Bit>,
    /// High while idle: issue the root next.
    pub start: Signal<In, Bit>,
    /// The root's level, while the root is issued.
    pub root_level: Signal<In, Bits<4>>,
    /// A result comes back this clock.
    pub result_valid: Signal<In, Bit>,
    /// ... and it has children to descend into: push it.
    pub push: Signal<In, Bit>,
    pub pushed: Signal<In, StackCell>,
    /// A cell is issued this clock: the root, or child `issue_octant` of
    /// the top, at `issue_x`, `issue_y`, `issue_z` (voxels) and level
    /// `issue_level`.
    pub issue: Signal<Out, Bit>,
    pub issue_root: Signal<Out, Bit>,
    pub issue_octant: Signal<Out, Bits<3>>,
    pub issue_x: Signal<Out, Bits<11>>,
    pub issue_y: Signal<Out, Bits<11>>,
    pub issue_z: Signal<Out, Bits<11>>,
    pub issue_level: Signal<Out, Bits<4>>,
    /// Cells wait to be issued or classified.
    pub busy: Signal<Out, Bit>,
    pub overflow: Signal<Out, Bit>,
    // The caller's value RAMs follow these ports.
    pub write_enable: Signal<Out, Bit>,
    pub write_address: Signal<Out, Bits<S>>,
    pub read_enable: Signal<Out, Bit>,
    pub read_address: Signal<Out, Bits<S>>,
    /// At this edge the top becomes the pushed result, or the RAM's data.
    pub take_pushed: Signal<Out, Bit>,
    pub take_read: Signal<Out, Bit>,
    stack: SimpleDualPortRam<StackCell, S>,
    top: DFF<StackCell>,
    top_valid: DFF<Bit>,
    /// The RAM's read data is the next top (read the clock before).
    refill: DFF<Bit>,
    /// Entries in the RAM.
    depth: DFF<Bits<16>>,
    in_flight: DFF<Bits<4>>,
    start_pending: DFF<Bit>,
    overflow_q: DFF<Bit>,
    /// Entries the RAM holds.
    stack_words: Constant<Bits<16>>,
    // Combinational.
    /// The top's mask (a struct field cannot be indexed in Verilog).
    top_mask: Signal<Local, Bits<8>>,
    octant: Signal<Local, Bits<3>>,
    remaining: Signal<Local, Bits<8>>,
    half: Signal<Local, Bits<11>>,
}

impl<const S: usize> crate::unit::Unit for TraversalStack<S> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            stack,
            top,
            top_valid,
            refill,
            depth,
            in_flight,
            start_pending,
            overflow_q
        );
    }
}

impl<const S: usize> Default for TraversalStack<S> {
    fn default() -> Self {
        TraversalStack {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            start: Default::default(),
            root_level: Default::default(),
            result_valid: Default::default(),
            push: Default::default(),
            pushed: Default::default(),
            issue: Default::default(),
            issue_root: Default::default(),
            issue_octant: Default::default(),
            issue_x: Default::default(),
            issue_y: Default::default(),
            issue_z: Default::default(),
            issue_level: Default::default(),
            busy: Default::default(),
            overflow: Default::default(),
            write_enable: Default::default(),
            write_address: Default::default(),
            read_enable: Default::default(),
            read_address: Default::default(),
            take_pushed: Default::default(),
            take_read: Default::default(),
            stack: SimpleDualPortRam::new(1 << S),
            top: Default::default(),
            top_valid: Default::default(),
            refill: Default::default(),
            depth: Default::default(),
            in_flight: Default::default(),
            start_pending: Default::default(),
            overflow_q: Default::default(),
            stack_words: Constant::new(Bits::<16>::from(1u64 << S)),
            top_mask: Default::default(),
            octant: Default::default(),
            remaining: Default::default(),
            half: Default::default(),
        }
    }
}

impl<const S: usize> Logic for TraversalStack<S> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            top,
            top_valid,
            refill,
            depth,
            in_flight,
            start_pending,
            overflow_q
        );
        clock!(self, clock, stack);
        self.busy.next = self.start_pending.q.val()
            | self.top_valid.q.val()
            | self.refill.q.val()
            | (self.depth.q.val() != 0)
            | (self.in_flight.q.val() != 0);
        self.overflow.next = self.overflow_q.q.val();

        // Issue: the root after start, else the top's lowest remaining child.
        self.top_mask.next = self.top.q.val().mask;
        self.octant.next = 0.into();
        if self.top_mask.val().get_bit(0) {
            self.octant.next = 0.into();
        } else if self.top_mask.val().get_bit(1) {
            self.octant.next = 1.into();
        } else if self.top_mask.val().get_bit(2) {
            self.octant.next = 2.into();
        } else if self.top_mask.val().get_bit(3) {
            self.octant.next = 3.into();
        } else if self.top_mask.val().get_bit(4) {
            self.octant.next = 4.into();
        } else if self.top_mask.val().get_bit(5) {
            self.octant.next = 5.into();
        } else if self.top_mask.val().get_bit(6) {
            self.octant.next = 6.into();
        } else {
            self.octant.next = 7.into();
        }
        self.remaining.next = self.top_mask.val() & (self.top_mask.val() - 1);
        self.half.next = bits::<11>(1) << (self.top.q.val().level - 1);
        self.issue.next = self.start_pending.q.val() | self.top_valid.q.val();
        self.issue_root.next = self.start_pending.q.val();
        self.issue_octant.next = self.octant.val();
        if self.start_pending.q.val() {
            self.issue_level.next = self.root_level.val();
            self.issue_x.next = 0.into();
            self.issue_y.next = 0.into();
            self.issue_z.next = 0.into();
        } else {
            self.issue_level.next = self.top.q.val().level - 1;
            self.issue_x.next = self.top.q.val().x;
            self.issue_y.next = self.top.q.val().y;
            self.issue_z.next = self.top.q.val().z;
            if self.octant.val().get_bit(0) {
                self.issue_x.next = self.top.q.val().x + self.half.val();
            }
            if self.octant.val().get_bit(1) {
                self.issue_y.next = self.top.q.val().y + self.half.val();
            }
            if self.octant.val().get_bit(2) {
                self.issue_z.next = self.top.q.val().z + self.half.val();
            }
        }

        // The stack.
        self.stack.write_enable.next = false;
        self.stack.write_address.next = bit_cast::<S, 16>(self.depth.q.val());
        self.stack.write_data.next = self.top.q.val();
        self.stack.write_data.next.mask = self.remaining.val();
        self.stack.read_enable.next = false;
        self.stack.read_address.next = bit_cast::<S, 16>(self.depth.q.val() - 1);
        self.take_pushed.next = false;
        self.take_read.next = false;
        if self.advance.val() {
            if self.start_pending.q.val() {
                self.start_pending.d.next = false;
            } else if self.top_valid.q.val() {
                self.top.d.next.mask = self.remaining.val();
                if self.remaining.val() == 0 {
                    self.top_valid.d.next = false;
                }
            }
            if self.push.val() {
                if self.top_valid.q.val()
                    & !self.start_pending.q.val()
                    & (self.remaining.val() != 0)
                {
                    self.stack.write_enable.next = true;
                    self.depth.d.next = self.depth.q.val() + 1;
                    if self.depth.q.val() == self.stack_words.val() {
                        self.overflow_q.d.next = true;
                    }
                }
                if self.refill.q.val() {
                    // The entry just read stays where it was.
                    self.depth.d.next = self.depth.q.val() + 1;
                }
                self.top.d.next = self.pushed.val();
                self.top_valid.d.next = true;
                self.refill.d.next = false;
                self.take_pushed.next = true;
            } else if self.refill.q.val() {
                self.top.d.next = self.stack.read_data.val();
                self.top_valid.d.next = true;
                self.refill.d.next = false;
                self.take_read.next = true;
            } else if self.top_valid.q.val()
                & !self.start_pending.q.val()
                & (self.remaining.val() == 0)
                & (self.depth.q.val() != 0)
            {
                self.stack.read_enable.next = true;
                self.depth.d.next = self.depth.q.val() - 1;
                self.refill.d.next = true;
            }
            if self.issue.val() & !self.result_valid.val() {
                self.in_flight.d.next = self.in_flight.q.val() + 1;
            }
            if !self.issue.val() & self.result_valid.val() {
                self.in_flight.d.next = self.in_flight.q.val() - 1;
            }
        }
        self.write_enable.next = self.stack.write_enable.val();
        self.write_address.next = self.stack.write_address.val();
        self.read_enable.next = self.stack.read_enable.val();
        self.read_address.next = self.stack.read_address.val();
        if self.start.val() & !self.busy.val() {
            self.start_pending.d.next = true;
        }
        if self.reset.val() {
            self.start_pending.d.next = false;
            self.top_valid.d.next = false;
            self.refill.d.next = false;
            self.depth.d.next = 0.into();
            self.in_flight.d.next = 0.into();
            self.overflow_q.d.next = false;
        }
    }
}
