//! The octree engine's core circuit (`octree_engine.txt`, section 5): the
//! grid classified against the plane `f(p) = n · p = d`, one octant per
//! clock, children's values interpolated from the parent's.
//!
//! The software model is `tritri_geom::octree::plane`; the cycle model,
//! record for record and edge for edge, is
//! `tritri_geom::octree::plane::traversal_schedule`.
//!
//! ```text
//!  start ─► root ─┐
//!  stack top ─────┴─► issue (one child of the top per clock: its lowest
//!        ▲               remaining octant, moved into by interpolation)
//!        │                 │  two axis steps, f against [d, d] (crossing)
//!        │                 │  and against [root_min, d] (some point below)
//!        │                 ▼  + the centre test of a level-1 cell's voxels
//!        └── push ◄─── result (5 clocks later): children inside the
//!            (crossing     half-space, crossing it, or outside
//!             children)    └─► record out: cell, level, full children mask,
//!                              crossed voxels mask (valid/ready)
//! ```
//!
//! A *record* says which children of a classified cell belong to the
//! half-space `f <= d` as wholes: a child entirely below the plane, or a
//! voxel (child of a level-1 cell) whose centre is; a memory-side unit
//! writes each such child into the voxel memory a word at a time. For a
//! level-1 cell the record also has the voxels the closed plane crosses.
//! Crossing children of a cell of level >= 2 are classified in turn: the
//! cell goes onto the stack with the mask of those children, and the issue
//! logic takes them one per clock from the top.
//!
//! The stack ([`super::traversal_stack`], shared with the triangle
//! voxelizer) keeps its top in registers and the rest in a block RAM; the
//! cells' values `f(lo)` sit beside it in a RAM of this unit's. Pushing a
//! result while the top has children left writes the top to the RAM; a top
//! whose last child is issued is dropped, and the next comes back from the
//! RAM (one clock without an issue). The order records leave in is not
//! preorder (writes into a voxel memory need none); the set of records is
//! the software traversal's, and the cycle model gives the order.
//!
//! The whole unit stalls while a record waits for `out_ready`.

use super::axis_step::{AxisStep, AXIS_STEP_LATENCY};
use super::centre_test::CentreTest;
use super::traversal_stack::{StackCell, TraversalStack};
use crate::arith::delay_line::DelayLine;
use crate::arith::valid_line::ValidLine;
use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of the plane's values: a grid of up to 1024 voxels a side and
/// normal components up to 2^20 give `|n · p| < 2^32`.
pub const PLANE_VALUE_BITS: usize = 40;
/// Bits of a cell corner coordinate (0 to 1024).
pub const CORNER_BITS: usize = 11;
/// Address bits of the stack's block RAM in the emitted unit (the unit's
/// `S`; tests build smaller stacks to see the overflow flag rise).
pub const STACK_ADDRESS_BITS: usize = 8;
/// Clock edges from an issue to its result: the axis steps, then one
/// register stage (masks, value and the centre test).
pub const CLASSIFY_LATENCY: usize = AXIS_STEP_LATENCY + 1;
/// Largest grid level (1024 voxels a side).
pub const MAX_LEVEL: u32 = 10;

const _: () = assert!(PLANE_VALUE_BITS == 40 && CORNER_BITS == 11);

#[derive(LogicBlock)]
pub struct PlaneTraversal<const S: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: idle, stack empty.
    pub reset: Signal<In, Bit>,
    // The plane, held from `start` until `busy` falls.
    pub gradient_x: Signal<In, Bits<40>>,
    pub gradient_y: Signal<In, Bits<40>>,
    pub gradient_z: Signal<In, Bits<40>>,
    pub d: Signal<In, Bits<40>>,
    /// The least value of `f` over the grid (the low end of "some point
    /// at or below the plane").
    pub root_min: Signal<In, Bits<40>>,
    /// `2d - Σn`, for the voxel centres.
    pub centre_offset: Signal<In, Bits<40>>,
    /// The grid is `2^level` voxels a side (1 to 10).
    pub level: Signal<In, Bits<4>>,
    /// One clock high while idle: classify the grid.
    pub start: Signal<In, Bit>,
    pub busy: Signal<Out, Bit>,
    /// Sticky: a push found the stack's RAM full (the records are then
    /// incomplete).
    pub overflow: Signal<Out, Bit>,
    // Records out (valid/ready).
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_x: Signal<Out, Bits<11>>,
    pub out_y: Signal<Out, Bits<11>>,
    pub out_z: Signal<Out, Bits<11>>,
    /// The classified cell's level (its children's is one less).
    pub out_level: Signal<Out, Bits<4>>,
    /// Children wholly in the half-space (for a level-1 cell: voxels whose
    /// centre is).
    pub out_full: Signal<Out, Bits<8>>,
    /// For a level-1 cell, the voxels the closed plane crosses.
    pub out_crossed: Signal<Out, Bits<8>>,
    crossing: AxisStep<40>,
    below: AxisStep<40>,
    centre: CentreTest<40>,
    cell_x: DelayLine<Bits<11>, CLASSIFY_LATENCY>,
    cell_y: DelayLine<Bits<11>, CLASSIFY_LATENCY>,
    cell_z: DelayLine<Bits<11>, CLASSIFY_LATENCY>,
    cell_level: DelayLine<Bits<4>, CLASSIFY_LATENCY>,
    cell_valid: ValidLine<CLASSIFY_LATENCY>,
    crossing_q: DFF<Bits<8>>,
    below_q: DFF<Bits<8>>,
    value_q: DFF<Bits<40>>,
    /// Which cell to issue, and the cells with children left.
    stack: TraversalStack<S>,
    /// The stack's cells' values `f(lo)`: the top's, the rest's.
    top_value: DFF<Bits<40>>,
    stack_value: SimpleDualPortRam<Bits<40>, S>,
    out_valid_q: DFF<Bit>,
    out_x_q: DFF<Bits<11>>,
    out_y_q: DFF<Bits<11>>,
    out_z_q: DFF<Bits<11>>,
    out_level_q: DFF<Bits<4>>,
    out_full_q: DFF<Bits<8>>,
    out_crossed_q: DFF<Bits<8>>,
    // Combinational.
    advance: Signal<Local, Bit>,
    inside: Signal<Local, Bits<8>>,
    full: Signal<Local, Bits<8>>,
    crossed: Signal<Local, Bits<8>>,
    push: Signal<Local, Bit>,
    pushed: Signal<Local, StackCell>,
}

impl<const S: usize> crate::unit::Unit for PlaneTraversal<S> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            crossing,
            below,
            centre,
            cell_x,
            cell_y,
            cell_z,
            cell_level,
            cell_valid,
            crossing_q,
            below_q,
            value_q,
            stack,
            top_value,
            stack_value,
            out_valid_q,
            out_x_q,
            out_y_q,
            out_z_q,
            out_level_q,
            out_full_q,
            out_crossed_q
        );
    }
}

impl<const S: usize> Default for PlaneTraversal<S> {
    fn default() -> Self {
        PlaneTraversal {
            clock: Default::default(),
            reset: Default::default(),
            gradient_x: Default::default(),
            gradient_y: Default::default(),
            gradient_z: Default::default(),
            d: Default::default(),
            root_min: Default::default(),
            centre_offset: Default::default(),
            level: Default::default(),
            start: Default::default(),
            busy: Default::default(),
            overflow: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_x: Default::default(),
            out_y: Default::default(),
            out_z: Default::default(),
            out_level: Default::default(),
            out_full: Default::default(),
            out_crossed: Default::default(),
            crossing: Default::default(),
            below: Default::default(),
            centre: Default::default(),
            cell_x: Default::default(),
            cell_y: Default::default(),
            cell_z: Default::default(),
            cell_level: Default::default(),
            cell_valid: Default::default(),
            crossing_q: Default::default(),
            below_q: Default::default(),
            value_q: Default::default(),
            stack: Default::default(),
            top_value: Default::default(),
            stack_value: SimpleDualPortRam::new(1 << S),
            out_valid_q: Default::default(),
            out_x_q: Default::default(),
            out_y_q: Default::default(),
            out_z_q: Default::default(),
            out_level_q: Default::default(),
            out_full_q: Default::default(),
            out_crossed_q: Default::default(),
            advance: Default::default(),
            inside: Default::default(),
            full: Default::default(),
            crossed: Default::default(),
            push: Default::default(),
            pushed: Default::default(),
        }
    }
}

impl<const S: usize> Logic for PlaneTraversal<S> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            crossing_q,
            below_q,
            value_q,
            top_value,
            out_valid_q,
            out_x_q,
            out_y_q,
            out_z_q,
            out_level_q,
            out_full_q,
            out_crossed_q
        );
        // Everything moves unless a record waits at the output.
        self.advance.next = !self.out_valid_q.q.val() | self.out_ready.val();
        self.out_valid.next = self.out_valid_q.q.val();
        self.out_x.next = self.out_x_q.q.val();
        self.out_y.next = self.out_y_q.q.val();
        self.out_z.next = self.out_z_q.q.val();
        self.out_level.next = self.out_level_q.q.val();
        self.out_full.next = self.out_full_q.q.val();
        self.out_crossed.next = self.out_crossed_q.q.val();
        self.overflow.next = self.stack.overflow.val();
        self.busy.next = self.stack.busy.val() | self.out_valid_q.q.val();

        // The stack issues the root after start, then the crossing children.
        self.stack.reset.next = self.reset.val();
        self.stack.advance.next = self.advance.val();
        self.stack.start.next = self.start.val() & !self.busy.val();
        self.stack.root_level.next = self.level.val();
        self.stack.result_valid.next = self.cell_valid.q.val();

        clock!(
            self,
            clock,
            crossing,
            below,
            centre,
            cell_x,
            cell_y,
            cell_z,
            cell_level,
            cell_valid,
            stack,
            stack_value
        );
        self.crossing.advance.next = self.advance.val();
        self.below.advance.next = self.advance.val();
        self.centre.advance.next = self.advance.val();
        self.crossing.gradient_x.next = self.gradient_x.val();
        self.crossing.gradient_y.next = self.gradient_y.val();
        self.crossing.gradient_z.next = self.gradient_z.val();
        self.below.gradient_x.next = self.gradient_x.val();
        self.below.gradient_y.next = self.gradient_y.val();
        self.below.gradient_z.next = self.gradient_z.val();
        self.crossing.low.next = self.d.val();
        self.crossing.high.next = self.d.val();
        self.below.low.next = self.root_min.val();
        self.below.high.next = self.d.val();
        self.centre.gradient_x.next = self.gradient_x.val();
        self.centre.gradient_y.next = self.gradient_y.val();
        self.centre.gradient_z.next = self.gradient_z.val();
        self.centre.offset.next = self.centre_offset.val();
        self.centre.value.next = self.crossing.value.val();
        self.cell_x.advance.next = self.advance.val();
        self.cell_y.advance.next = self.advance.val();
        self.cell_z.advance.next = self.advance.val();
        self.cell_level.advance.next = self.advance.val();
        self.cell_valid.advance.next = self.advance.val();
        self.cell_valid.reset.next = self.reset.val();
        self.cell_valid.d.next = self.stack.issue.val();
        self.cell_level.d.next = self.stack.issue_level.val();
        self.cell_x.d.next = self.stack.issue_x.val();
        self.cell_y.d.next = self.stack.issue_y.val();
        self.cell_z.d.next = self.stack.issue_z.val();
        self.crossing.level.next = bit_cast::<6, 4>(self.stack.issue_level.val());
        self.crossing.descend.next = !self.stack.issue_root.val();
        self.crossing.at_lo.next = self.top_value.q.val();
        if self.stack.issue_root.val() {
            self.crossing.at_lo.next = 0.into();
        }
        self.crossing.octant.next = self.stack.issue_octant.val();
        self.below.level.next = self.crossing.level.val();
        self.below.descend.next = self.crossing.descend.val();
        self.below.at_lo.next = self.crossing.at_lo.val();
        self.below.octant.next = self.stack.issue_octant.val();

        // One register after the axis steps, beside the centre test.
        if self.advance.val() {
            self.crossing_q.d.next = self.crossing.mask.val();
            self.below_q.d.next = self.below.mask.val();
            // Both steps carry the cell's value; the centre test takes one,
            // the stack the other.
            self.value_q.d.next = self.below.value.val();
        }

        // The result: children inside (below and not crossing), crossing,
        // or outside; a level-1 cell's voxels by their centres.
        self.inside.next = self.below_q.q.val() & !self.crossing_q.q.val();
        self.full.next = self.inside.val();
        self.crossed.next = 0.into();
        if self.cell_level.q.val() == 1 {
            self.full.next = self.inside.val() | (self.crossing_q.q.val() & self.centre.mask.val());
            self.crossed.next = self.crossing_q.q.val();
        }
        self.push.next = self.cell_valid.q.val()
            & (self.cell_level.q.val() != 1)
            & (self.crossing_q.q.val() != 0);
        self.pushed.next.x = self.cell_x.q.val();
        self.pushed.next.y = self.cell_y.q.val();
        self.pushed.next.z = self.cell_z.q.val();
        self.pushed.next.level = self.cell_level.q.val();
        self.pushed.next.mask = self.crossing_q.q.val();

        self.stack.push.next = self.push.val();
        self.stack.pushed.next = self.pushed.val();
        // The values move with their cell: written beside it, read back
        // with it, and the pushed cell's from the axis steps.
        self.stack_value.write_enable.next = self.stack.write_enable.val();
        self.stack_value.write_address.next = self.stack.write_address.val();
        self.stack_value.write_data.next = self.top_value.q.val();
        self.stack_value.read_enable.next = self.stack.read_enable.val();
        self.stack_value.read_address.next = self.stack.read_address.val();
        if self.stack.take_pushed.val() {
            self.top_value.d.next = self.value_q.q.val();
        } else if self.stack.take_read.val() {
            self.top_value.d.next = self.stack_value.read_data.val();
        }
        if self.advance.val() {
            self.out_valid_q.d.next =
                self.cell_valid.q.val() & ((self.full.val() != 0) | (self.crossed.val() != 0));
            self.out_x_q.d.next = self.cell_x.q.val();
            self.out_y_q.d.next = self.cell_y.q.val();
            self.out_z_q.d.next = self.cell_z.q.val();
            self.out_level_q.d.next = self.cell_level.q.val();
            self.out_full_q.d.next = self.full.val();
            self.out_crossed_q.d.next = self.crossed.val();
        }
        if self.reset.val() {
            self.out_valid_q.d.next = false;
        }
    }
}
