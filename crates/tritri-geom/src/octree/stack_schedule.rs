//! The cycle model of the octree engine's depth-first traversals in
//! hardware (the plane traversal, `tritri_rtl::octree::plane_traversal`,
//! and the triangle voxelizer, `tritri_rtl::octree::triangle_voxelizer`):
//! one cell issued per clock edge into a classifier of fixed latency, and a
//! stack whose top sits in registers and the rest in a block RAM.
//!
//! Each edge issues one cell: the root after [`StackSchedule::start`], else
//! the lowest remaining child of the stack's top. The result of the cell
//! issued at edge `e` is taken at edge `e + latency`; a result with
//! children to descend into becomes the new top (the old top, if it has
//! children left, goes to the RAM). A top whose last child is issued is
//! dropped; the next comes back from the RAM at the edge after (no issue at
//! that edge) unless a push takes its place. The classification itself is
//! the caller's: a closure from a cell to its result and the mask of the
//! children to descend into.

use super::cell::Cell;
use std::collections::VecDeque;

#[derive(Clone, Copy, Debug)]
struct Entry {
    cell: Cell,
    mask: u8,
}

/// The traversal's state between clock edges.
#[derive(Clone, Debug)]
pub struct StackSchedule<R> {
    latency: u64,
    /// The root to issue at the next edge.
    start: Option<Cell>,
    top: Option<Entry>,
    /// The entry read from the RAM, the top after this edge.
    refill: Option<Entry>,
    stack: Vec<Entry>,
    /// Results with the edge they are taken at, and their descend masks.
    in_flight: VecDeque<(u64, R, Cell, u8)>,
    /// The most entries the RAM held (the top register apart).
    pub stack_depth: usize,
    /// Cells issued.
    pub cells: u64,
}

impl<R> StackSchedule<R> {
    pub fn new(latency: u64) -> StackSchedule<R> {
        StackSchedule {
            latency,
            start: None,
            top: None,
            refill: None,
            stack: Vec::new(),
            in_flight: VecDeque::new(),
            stack_depth: 0,
            cells: 0,
        }
    }

    /// Issue `root` at the next edge (the traversal must be idle).
    pub fn start(&mut self, root: Cell) {
        debug_assert!(!self.busy());
        self.start = Some(root);
    }

    /// Cells wait to be issued or classified.
    pub fn busy(&self) -> bool {
        self.start.is_some()
            || self.top.is_some()
            || self.refill.is_some()
            || !self.stack.is_empty()
            || !self.in_flight.is_empty()
    }

    /// One clock edge, `edge` counted as the caller counts: issues a cell
    /// (classified by `classify` into its result and the children to
    /// descend into) and returns the result taken at this edge.
    pub fn edge(&mut self, edge: u64, classify: impl FnOnce(Cell) -> (R, u8)) -> Option<R> {
        let result = match self.in_flight.front() {
            Some(&(ready, ..)) if ready == edge => self
                .in_flight
                .pop_front()
                .map(|(_, r, cell, mask)| (r, cell, mask)),
            _ => None,
        };
        let from_top = if self.start.is_some() { None } else { self.top };
        let remaining = from_top.map_or(0, |t| t.mask & t.mask.wrapping_sub(1));
        let issued = match (self.start.take(), from_top) {
            (Some(root), _) => Some(root),
            (None, Some(t)) => Some(t.cell.child(t.mask.trailing_zeros() as usize)),
            (None, None) => None,
        };
        if let Some(cell) = issued {
            let (r, mask) = classify(cell);
            self.in_flight
                .push_back((edge + self.latency, r, cell, mask));
            self.cells += 1;
        }
        if let Some(t) = from_top {
            self.top = (remaining != 0).then_some(Entry {
                cell: t.cell,
                mask: remaining,
            });
        }
        match &result {
            Some((_, cell, mask)) if *mask != 0 => {
                if let (Some(t), true) = (from_top, remaining != 0) {
                    self.stack.push(Entry {
                        cell: t.cell,
                        mask: remaining,
                    });
                }
                // An entry being read back stays on the stack.
                if let Some(e) = self.refill.take() {
                    self.stack.push(e);
                }
                self.top = Some(Entry {
                    cell: *cell,
                    mask: *mask,
                });
            }
            _ => {
                if let Some(e) = self.refill.take() {
                    self.top = Some(e);
                } else if from_top.is_some() && remaining == 0 {
                    self.refill = self.stack.pop();
                }
            }
        }
        self.stack_depth = self
            .stack_depth
            .max(self.stack.len() + usize::from(self.refill.is_some()));
        result.map(|(r, ..)| r)
    }
}
