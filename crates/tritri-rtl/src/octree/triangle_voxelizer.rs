//! Surface voxelization in hardware (`octree_engine.txt`, function 3, the
//! boundary representation to voxels): triangles streamed in, each one's
//! voxels streamed out, exactly as `tritri_geom::octree::voxelize::surface`
//! marks them on its fine grid.
//!
//! ```text
//!  triangles ─► setup (the multiplications, exact intervals) ─► loaded
//!  (valid/ready)   stalls while its output waits for the traversal  │
//!                                                                   ▼
//!  start ─► root ─┐                                    13 test functions
//!  stack top ─────┴─► issue (one child of the top per clock, moved
//!        ▲               into by interpolation: adds and shifts)
//!        │                 │  cell classifier: thirteen axis steps
//!        │                 ▼
//!        └── push ◄─── result (5 clocks later): the children the
//!            (children     triangle meets; for a level-1 cell they are
//!             met)         voxels ─► record out: cell, voxel mask
//! ```
//!
//! One triangle is traversed at a time: its thirteen functions are loaded
//! from the setup's output when the previous traversal is over, and the
//! setup works on the next triangles meanwhile. The traversal is the plane
//! traversal's ([`super::plane_traversal`]) with the triangle's classifier
//! ([`super::cell_classifier`]) in place of the plane's two axis steps; the
//! stack ([`super::traversal_stack`]) is the same unit, and the thirteen
//! values at each stacked cell's low corner sit beside it, the top's in
//! registers and the rest in block RAMs driven by its ports. Cells are in
//! voxels; the classifier works on the fine grid, `SUB_BITS` levels below a
//! voxel, where the vertices are.
//!
//! The cycle model is [`super::voxelizer_machine::voxelizer_schedule`].
//! The whole traversal stalls while a record waits for `out_ready`.

use super::cell_classifier::{CellClassifier, AXES, CELL_CLASSIFIER_LATENCY};
use super::traversal_stack::{StackCell, TraversalStack};
use super::triangle_setup::TriangleSetup;
use crate::arith::delay_line::DelayLine;
use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;
use tritri_geom::octree::voxelize::SUB_BITS;

/// Bits of a voxel coordinate (0 to 1024).
pub const VOXEL_BITS: usize = 11;
/// Address bits of the stack's block RAM in the emitted unit (the unit's
/// `S`; tests build smaller stacks to see the overflow flag rise).
pub const VOXELIZER_STACK_BITS: usize = 6;
/// Largest grid level (1024 voxels a side).
pub const VOXELIZER_MAX_LEVEL: u32 = 10;
/// The grid width the unit is built for: fine coordinates up to
/// `2^(10 + SUB_BITS)` need `10 + SUB_BITS + 2` signed bits.
pub const VOXELIZER_GRID_BITS: usize = 32;

const _: () = assert!(
    VOXELIZER_MAX_LEVEL as usize + SUB_BITS as usize + 2 <= VOXELIZER_GRID_BITS && VOXEL_BITS == 11
);

#[derive(LogicBlock)]
pub struct TriangleVoxelizer<
    const G: usize,
    const V: usize,
    const N: usize,
    const T: usize,
    const S: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: idle, stack empty, setup empty.
    pub reset: Signal<In, Bit>,
    /// The grid is `2^level` voxels a side (1 to 10); held.
    pub level: Signal<In, Bits<4>>,
    // Triangles in (valid/ready): `x0 y0 z0 x1 … z2` from bit 0 up, G bits
    // each, fine-grid coordinates in [0, 2^(level + SUB_BITS)].
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_vertices: Signal<In, Bits<T>>,
    /// A triangle is in the unit or a record waits.
    pub busy: Signal<Out, Bit>,
    /// Sticky: a push found the stack's RAM full (the records are then
    /// incomplete).
    pub overflow: Signal<Out, Bit>,
    // Records out (valid/ready): a level-1 cell and the voxels met.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_x: Signal<Out, Bits<11>>,
    pub out_y: Signal<Out, Bits<11>>,
    pub out_z: Signal<Out, Bits<11>>,
    pub out_mask: Signal<Out, Bits<8>>,
    setup: TriangleSetup<G, V, N>,
    /// Triangles in the setup, not yet loaded.
    in_setup: DFF<Bits<3>>,
    loaded_gradient_x: DFF<Bits<N>>,
    loaded_gradient_y: DFF<Bits<N>>,
    loaded_gradient_z: DFF<Bits<N>>,
    loaded_low: DFF<Bits<N>>,
    loaded_high: DFF<Bits<N>>,
    classifier: CellClassifier<V>,
    cell_x: DelayLine<Bits<11>, CELL_CLASSIFIER_LATENCY>,
    cell_y: DelayLine<Bits<11>, CELL_CLASSIFIER_LATENCY>,
    cell_z: DelayLine<Bits<11>, CELL_CLASSIFIER_LATENCY>,
    cell_level: DelayLine<Bits<4>, CELL_CLASSIFIER_LATENCY>,
    /// Which cell to issue, and the cells with children left.
    stack: TraversalStack<S>,
    /// The thirteen values of the stack's cells: the top's, the rest's.
    top_value: [DFF<Bits<V>>; AXES],
    stack_value: [SimpleDualPortRam<Bits<V>, S>; AXES],
    out_valid_q: DFF<Bit>,
    out_x_q: DFF<Bits<11>>,
    out_y_q: DFF<Bits<11>>,
    out_z_q: DFF<Bits<11>>,
    out_mask_q: DFF<Bits<8>>,
    // Where each vertex coordinate sits in `in_vertices`, each test
    // function in the setup's packed outputs.
    vertex_offset: [Constant<Bits<16>>; 9],
    field_offset: [Constant<Bits<16>>; AXES],
    /// The classifier's level is the cell's in fine-grid steps.
    sub_bits: Constant<Bits<6>>,
    // Combinational.
    advance: Signal<Local, Bit>,
    load: Signal<Local, Bit>,
    setup_advance: Signal<Local, Bit>,
    push: Signal<Local, Bit>,
    pushed: Signal<Local, StackCell>,
    /// The setup's and classifier's tags, unused, folded into one bit whose
    /// name tells Verilator's lint so.
    unused_outputs: Signal<Local, Bit>,
}

impl<const G: usize, const V: usize, const N: usize, const T: usize, const S: usize>
    crate::unit::Unit for TriangleVoxelizer<G, V, N, T, S>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            setup,
            in_setup,
            loaded_gradient_x,
            loaded_gradient_y,
            loaded_gradient_z,
            loaded_low,
            loaded_high,
            classifier,
            cell_x,
            cell_y,
            cell_z,
            cell_level,
            stack,
            top_value,
            stack_value,
            out_valid_q,
            out_x_q,
            out_y_q,
            out_z_q,
            out_mask_q
        );
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize, const S: usize> Default
    for TriangleVoxelizer<G, V, N, T, S>
{
    fn default() -> Self {
        assert!(
            V == super::value_bits(G) && N == AXES * V && T == 9 * G,
            "triangle voxelizer for G = {G}"
        );
        let words = 1 << S;
        TriangleVoxelizer {
            clock: Default::default(),
            reset: Default::default(),
            level: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_vertices: Default::default(),
            busy: Default::default(),
            overflow: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_x: Default::default(),
            out_y: Default::default(),
            out_z: Default::default(),
            out_mask: Default::default(),
            setup: Default::default(),
            in_setup: Default::default(),
            loaded_gradient_x: Default::default(),
            loaded_gradient_y: Default::default(),
            loaded_gradient_z: Default::default(),
            loaded_low: Default::default(),
            loaded_high: Default::default(),
            classifier: Default::default(),
            cell_x: Default::default(),
            cell_y: Default::default(),
            cell_z: Default::default(),
            cell_level: Default::default(),
            stack: Default::default(),
            top_value: Default::default(),
            stack_value: std::array::from_fn(|_| SimpleDualPortRam::new(words)),
            out_valid_q: Default::default(),
            out_x_q: Default::default(),
            out_y_q: Default::default(),
            out_z_q: Default::default(),
            out_mask_q: Default::default(),
            vertex_offset: std::array::from_fn(|k| Constant::new(Bits::<16>::from((k * G) as u64))),
            field_offset: std::array::from_fn(|i| Constant::new(Bits::<16>::from((i * V) as u64))),
            sub_bits: Constant::new(Bits::<6>::from(SUB_BITS as u64)),
            advance: Default::default(),
            load: Default::default(),
            setup_advance: Default::default(),
            push: Default::default(),
            pushed: Default::default(),
            unused_outputs: Default::default(),
        }
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize, const S: usize> Logic
    for TriangleVoxelizer<G, V, N, T, S>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            in_setup,
            loaded_gradient_x,
            loaded_gradient_y,
            loaded_gradient_z,
            loaded_low,
            loaded_high,
            out_valid_q,
            out_x_q,
            out_y_q,
            out_z_q,
            out_mask_q
        );
        clock!(self, clock, setup, classifier, cell_x, cell_y, cell_z, cell_level, stack);
        // The traversal moves unless a record waits at the output.
        self.advance.next = !self.out_valid_q.q.val() | self.out_ready.val();
        self.out_valid.next = self.out_valid_q.q.val();
        self.out_x.next = self.out_x_q.q.val();
        self.out_y.next = self.out_y_q.q.val();
        self.out_z.next = self.out_z_q.q.val();
        self.out_mask.next = self.out_mask_q.q.val();
        self.overflow.next = self.stack.overflow.val();
        self.busy.next =
            self.stack.busy.val() | (self.in_setup.q.val() != 0) | self.out_valid_q.q.val();

        // The setup: the next triangle's functions wait at its output until
        // the traversal is over, then are loaded.
        self.load.next = self.setup.out_valid.val() & !self.stack.busy.val();
        self.setup_advance.next = !self.setup.out_valid.val() | self.load.val();
        self.in_ready.next = self.setup_advance.val();
        self.setup.reset.next = self.reset.val();
        self.setup.advance.next = self.setup_advance.val();
        self.setup.in_valid.next = self.in_valid.val();
        self.setup.in_tag.next = 0.into();
        self.setup.grow.next = false;
        self.setup.in_x0.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[0].val().index());
        self.setup.in_y0.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[1].val().index());
        self.setup.in_z0.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[2].val().index());
        self.setup.in_x1.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[3].val().index());
        self.setup.in_y1.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[4].val().index());
        self.setup.in_z1.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[5].val().index());
        self.setup.in_x2.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[6].val().index());
        self.setup.in_y2.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[7].val().index());
        self.setup.in_z2.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[8].val().index());
        // Relative to the grid's origin, every function is zero there.
        self.setup.in_root_x.next = 0.into();
        self.setup.in_root_y.next = 0.into();
        self.setup.in_root_z.next = 0.into();
        if (self.in_valid.val() & self.setup_advance.val()) & !self.load.val() {
            self.in_setup.d.next = self.in_setup.q.val() + 1;
        }
        if !(self.in_valid.val() & self.setup_advance.val()) & self.load.val() {
            self.in_setup.d.next = self.in_setup.q.val() - 1;
        }
        if self.load.val() {
            self.loaded_gradient_x.d.next = self.setup.out_gradient_x.val();
            self.loaded_gradient_y.d.next = self.setup.out_gradient_y.val();
            self.loaded_gradient_z.d.next = self.setup.out_gradient_z.val();
            self.loaded_low.d.next = self.setup.out_low.val();
            self.loaded_high.d.next = self.setup.out_high.val();
        }

        // The stack issues the root after a load, then the children met.
        self.stack.reset.next = self.reset.val();
        self.stack.advance.next = self.advance.val();
        self.stack.start.next = self.load.val();
        self.stack.root_level.next = self.level.val();
        self.stack.result_valid.next = self.classifier.out_valid.val();
        self.classifier.reset.next = self.reset.val();
        self.classifier.advance.next = self.advance.val();
        self.classifier.in_valid.next = self.stack.issue.val();
        self.classifier.in_tag.next = 0.into();
        self.classifier.in_octant.next = self.stack.issue_octant.val();
        // The classifier's levels are the fine grid's, SUB_BITS below a voxel.
        self.classifier.in_level.next =
            bit_cast::<6, 4>(self.stack.issue_level.val()) + self.sub_bits.val();
        self.classifier.in_descend.next = !self.stack.issue_root.val();
        self.cell_x.advance.next = self.advance.val();
        self.cell_y.advance.next = self.advance.val();
        self.cell_z.advance.next = self.advance.val();
        self.cell_level.advance.next = self.advance.val();
        self.cell_x.d.next = self.stack.issue_x.val();
        self.cell_y.d.next = self.stack.issue_y.val();
        self.cell_z.d.next = self.stack.issue_z.val();
        self.cell_level.d.next = self.stack.issue_level.val();
        for i in 0..13 {
            self.classifier.in_gradient_x[i].next = self
                .loaded_gradient_x
                .q
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_gradient_y[i].next = self
                .loaded_gradient_y
                .q
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_gradient_z[i].next = self
                .loaded_gradient_z
                .q
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_low[i].next = self
                .loaded_low
                .q
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_high[i].next = self
                .loaded_high
                .q
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            // Relative to the grid's origin, every function is zero at the root.
            self.classifier.in_at_lo[i].next = self.top_value[i].q.val();
            if self.stack.issue_root.val() {
                self.classifier.in_at_lo[i].next = 0.into();
            }
        }

        // The result: a level-1 cell's voxels are a record; a larger cell
        // with children met goes onto the stack.
        self.push.next = self.classifier.out_valid.val()
            & (self.cell_level.q.val() != 1)
            & (self.classifier.out_mask.val() != 0);
        self.pushed.next.x = self.cell_x.q.val();
        self.pushed.next.y = self.cell_y.q.val();
        self.pushed.next.z = self.cell_z.q.val();
        self.pushed.next.level = self.cell_level.q.val();
        self.pushed.next.mask = self.classifier.out_mask.val();
        self.stack.push.next = self.push.val();
        self.stack.pushed.next = self.pushed.val();
        if self.advance.val() {
            self.out_valid_q.d.next = self.classifier.out_valid.val()
                & (self.cell_level.q.val() == 1)
                & (self.classifier.out_mask.val() != 0);
            self.out_x_q.d.next = self.cell_x.q.val();
            self.out_y_q.d.next = self.cell_y.q.val();
            self.out_z_q.d.next = self.cell_z.q.val();
            self.out_mask_q.d.next = self.classifier.out_mask.val();
        }
        // The values move with their cell: written beside it, read back with
        // it, and the pushed cell's from the classifier.
        for i in 0..13 {
            self.stack_value[i].clock.next = self.clock.val();
            self.stack_value[i].write_enable.next = self.stack.write_enable.val();
            self.stack_value[i].write_address.next = self.stack.write_address.val();
            self.stack_value[i].write_data.next = self.top_value[i].q.val();
            self.stack_value[i].read_enable.next = self.stack.read_enable.val();
            self.stack_value[i].read_address.next = self.stack.read_address.val();
            self.top_value[i].clock.next = self.clock.val();
            self.top_value[i].d.next = self.top_value[i].q.val();
            if self.stack.take_pushed.val() {
                self.top_value[i].d.next = self.classifier.out_at_lo[i].val();
            } else if self.stack.take_read.val() {
                self.top_value[i].d.next = self.stack_value[i].read_data.val();
            }
        }
        if self.reset.val() {
            self.in_setup.d.next = 0.into();
            self.out_valid_q.d.next = false;
        }
        self.unused_outputs.next =
            self.setup.out_tag.val().any() ^ self.classifier.out_tag.val().any();
    }
}

// The loops over the test functions are written with a literal.
const _: () = assert!(AXES == 13);
