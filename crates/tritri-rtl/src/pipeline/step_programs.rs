//! The shared rare-case unit's programs: for each of stage 1's 24
//! destination coordinates (`u0`, `u1`, `w0`'s three lanes, `w1`'s: 8
//! destinations of 3 coordinates, `3 d + k`), the point it takes at each
//! step of a job, one-hot (bit `p` for point `p`: T1's vertices or
//! segment ends 0, 1, 2, T2's 3, 4, 5). A coplanar pair's six steps give
//! the eighteen orient2d values of `hulls_intersect_2d`, two segments'
//! four steps the components of `[a, b, c]`, `[a, b, d]`, `[c, d, a]`,
//! `[c, d, b]` (the numbering of [`super::rare_decisions`]: value
//! `3 step + lane` is `u × w` of lane `lane`, `u = u1 - u0`, `w = w1 - w0`).
//!
//! The pick is registered a clock ahead: from each copy's step and kind
//! (the parent's copies of the job's counters, one per destination
//! coordinate, so that no register drives all 24), decoded at the step
//! after the copy's current one from registers alone (a LUT a bit); the
//! copy's load and its count then only choose among that, the first
//! step's constant and the pick held. Decoded from the copy's next value,
//! the pick was five levels behind the copy's steps left (W = 16, ECP5,
//! 134.8 MHz).

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Stage 1's destination coordinates.
pub const DESTINATIONS: usize = 24;

#[derive(LogicBlock, Default)]
pub struct StepPrograms {
    pub clock: Signal<In, Clock>,
    /// Copy `c` takes a new job at this clock's edge.
    pub load: [Signal<In, Bit>; DESTINATIONS],
    /// That job is two segments (else a coplanar pair).
    pub load_segments: Signal<In, Bit>,
    /// Copy `c`'s step and its job's kind (two segments), held in the
    /// parent's registers.
    pub step: [Signal<In, Bits<3>>; DESTINATIONS],
    pub segments: [Signal<In, Bit>; DESTINATIONS],
    /// Copy `c` has steps left: it moves on to its next step at this edge.
    pub moving: [Signal<In, Bit>; DESTINATIONS],
    /// The point each destination coordinate takes at the next clock edge,
    /// one-hot: copy `c`'s program at the step and kind it holds then.
    pub pick: [Signal<Out, Bits<6>>; DESTINATIONS],
    pick_q: [DFF<Bits<6>>; DESTINATIONS],
    /// Copy `c`'s program at the step after its current one, and that step.
    next_pick: [Signal<Local, Bits<6>>; DESTINATIONS],
    step_ahead: [Signal<Local, Bits<3>>; DESTINATIONS],
}

impl crate::unit::Unit for StepPrograms {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, pick_q);
    }
}

impl Logic for StepPrograms {
    #[hdl_gen]
    fn update(&mut self) {
        for c in 0..24 {
            self.pick_q[c].clock.next = self.clock.val();
            self.pick[c].next = self.pick_q[c].q.val();
        }
        // The programs: point `p` (bit `p` of the pick) at each step, read
        // at the step after the copy's current one.
        for c in 0..24 {
            self.step_ahead[c].next = self.step[c].val() + 1;
        }
        // u0
        for k in 0..3 {
            if self.segments[k].val() {
                if self.step_ahead[k].val() == 0 || self.step_ahead[k].val() == 1 {
                    self.next_pick[k].next = 1.into();
                } else {
                    self.next_pick[k].next = 8.into();
                }
            } else {
                if self.step_ahead[k].val() == 0 {
                    self.next_pick[k].next = 1.into();
                } else if self.step_ahead[k].val() == 1 {
                    self.next_pick[k].next = 2.into();
                } else if self.step_ahead[k].val() == 2 {
                    self.next_pick[k].next = 4.into();
                } else if self.step_ahead[k].val() == 3 {
                    self.next_pick[k].next = 8.into();
                } else if self.step_ahead[k].val() == 4 {
                    self.next_pick[k].next = 16.into();
                } else {
                    self.next_pick[k].next = 32.into();
                }
            }
        }
        // u1
        for k in 0..3 {
            if self.segments[3 + k].val() {
                if self.step_ahead[3 + k].val() == 0 || self.step_ahead[3 + k].val() == 1 {
                    self.next_pick[3 + k].next = 2.into();
                } else {
                    self.next_pick[3 + k].next = 16.into();
                }
            } else {
                if self.step_ahead[3 + k].val() == 0 {
                    self.next_pick[3 + k].next = 2.into();
                } else if self.step_ahead[3 + k].val() == 1 {
                    self.next_pick[3 + k].next = 4.into();
                } else if self.step_ahead[3 + k].val() == 2 {
                    self.next_pick[3 + k].next = 1.into();
                } else if self.step_ahead[3 + k].val() == 3 {
                    self.next_pick[3 + k].next = 16.into();
                } else if self.step_ahead[3 + k].val() == 4 {
                    self.next_pick[3 + k].next = 32.into();
                } else {
                    self.next_pick[3 + k].next = 8.into();
                }
            }
        }
        // w0 lane 0
        for k in 0..3 {
            if self.segments[6 + k].val() {
                if self.step_ahead[6 + k].val() == 0 || self.step_ahead[6 + k].val() == 1 {
                    self.next_pick[6 + k].next = 1.into();
                } else {
                    self.next_pick[6 + k].next = 8.into();
                }
            } else {
                if self.step_ahead[6 + k].val() == 0
                    || self.step_ahead[6 + k].val() == 3
                    || self.step_ahead[6 + k].val() == 4
                    || self.step_ahead[6 + k].val() == 5
                {
                    self.next_pick[6 + k].next = 1.into();
                } else if self.step_ahead[6 + k].val() == 1 {
                    self.next_pick[6 + k].next = 2.into();
                } else {
                    self.next_pick[6 + k].next = 4.into();
                }
            }
        }
        // w0 lane 1
        for k in 0..3 {
            if self.segments[9 + k].val() {
                if self.step_ahead[9 + k].val() == 0 || self.step_ahead[9 + k].val() == 1 {
                    self.next_pick[9 + k].next = 1.into();
                } else {
                    self.next_pick[9 + k].next = 8.into();
                }
            } else {
                if self.step_ahead[9 + k].val() == 0 {
                    self.next_pick[9 + k].next = 1.into();
                } else if self.step_ahead[9 + k].val() == 1
                    || self.step_ahead[9 + k].val() == 3
                    || self.step_ahead[9 + k].val() == 4
                    || self.step_ahead[9 + k].val() == 5
                {
                    self.next_pick[9 + k].next = 2.into();
                } else {
                    self.next_pick[9 + k].next = 4.into();
                }
            }
        }
        // w0 lane 2
        for k in 0..3 {
            if self.segments[12 + k].val() {
                if self.step_ahead[12 + k].val() == 0 || self.step_ahead[12 + k].val() == 1 {
                    self.next_pick[12 + k].next = 1.into();
                } else {
                    self.next_pick[12 + k].next = 8.into();
                }
            } else {
                if self.step_ahead[12 + k].val() == 0 {
                    self.next_pick[12 + k].next = 1.into();
                } else if self.step_ahead[12 + k].val() == 1 {
                    self.next_pick[12 + k].next = 2.into();
                } else {
                    self.next_pick[12 + k].next = 4.into();
                }
            }
        }
        // w1 lane 0
        for k in 0..3 {
            if self.segments[15 + k].val() {
                if self.step_ahead[15 + k].val() == 0 {
                    self.next_pick[15 + k].next = 8.into();
                } else if self.step_ahead[15 + k].val() == 1 {
                    self.next_pick[15 + k].next = 16.into();
                } else if self.step_ahead[15 + k].val() == 2 {
                    self.next_pick[15 + k].next = 1.into();
                } else {
                    self.next_pick[15 + k].next = 2.into();
                }
            } else {
                if self.step_ahead[15 + k].val() == 0
                    || self.step_ahead[15 + k].val() == 1
                    || self.step_ahead[15 + k].val() == 2
                    || self.step_ahead[15 + k].val() == 3
                {
                    self.next_pick[15 + k].next = 8.into();
                } else if self.step_ahead[15 + k].val() == 4 {
                    self.next_pick[15 + k].next = 16.into();
                } else {
                    self.next_pick[15 + k].next = 32.into();
                }
            }
        }
        // w1 lane 1
        for k in 0..3 {
            if self.segments[18 + k].val() {
                if self.step_ahead[18 + k].val() == 0 {
                    self.next_pick[18 + k].next = 8.into();
                } else if self.step_ahead[18 + k].val() == 1 {
                    self.next_pick[18 + k].next = 16.into();
                } else if self.step_ahead[18 + k].val() == 2 {
                    self.next_pick[18 + k].next = 1.into();
                } else {
                    self.next_pick[18 + k].next = 2.into();
                }
            } else {
                if self.step_ahead[18 + k].val() == 0
                    || self.step_ahead[18 + k].val() == 1
                    || self.step_ahead[18 + k].val() == 2
                    || self.step_ahead[18 + k].val() == 4
                {
                    self.next_pick[18 + k].next = 16.into();
                } else if self.step_ahead[18 + k].val() == 3 {
                    self.next_pick[18 + k].next = 8.into();
                } else {
                    self.next_pick[18 + k].next = 32.into();
                }
            }
        }
        // w1 lane 2
        for k in 0..3 {
            if self.segments[21 + k].val() {
                if self.step_ahead[21 + k].val() == 0 {
                    self.next_pick[21 + k].next = 8.into();
                } else if self.step_ahead[21 + k].val() == 1 {
                    self.next_pick[21 + k].next = 16.into();
                } else if self.step_ahead[21 + k].val() == 2 {
                    self.next_pick[21 + k].next = 1.into();
                } else {
                    self.next_pick[21 + k].next = 2.into();
                }
            } else {
                if self.step_ahead[21 + k].val() == 0
                    || self.step_ahead[21 + k].val() == 1
                    || self.step_ahead[21 + k].val() == 2
                    || self.step_ahead[21 + k].val() == 5
                {
                    self.next_pick[21 + k].next = 32.into();
                } else if self.step_ahead[21 + k].val() == 3 {
                    self.next_pick[21 + k].next = 8.into();
                } else {
                    self.next_pick[21 + k].next = 16.into();
                }
            }
        }
        // The next pick: the program's where the copy moves on, its first
        // step's where it takes a job (as the programs above give it at
        // step 0), else the pick held.
        for c in 0..24 {
            self.pick_q[c].d.next = self.pick_q[c].q.val();
            if self.moving[c].val() {
                self.pick_q[c].d.next = self.next_pick[c].val();
            }
        }
        for k in 0..3 {
            if self.load[k].val() {
                self.pick_q[k].d.next = 1.into();
            }
            if self.load[3 + k].val() {
                self.pick_q[3 + k].d.next = 2.into();
            }
            if self.load[6 + k].val() {
                self.pick_q[6 + k].d.next = 1.into();
            }
            if self.load[9 + k].val() {
                self.pick_q[9 + k].d.next = 1.into();
            }
            if self.load[12 + k].val() {
                self.pick_q[12 + k].d.next = 1.into();
            }
            if self.load[15 + k].val() {
                self.pick_q[15 + k].d.next = 8.into();
            }
            if self.load[18 + k].val() {
                if self.load_segments.val() {
                    self.pick_q[18 + k].d.next = 8.into();
                } else {
                    self.pick_q[18 + k].d.next = 16.into();
                }
            }
            if self.load[21 + k].val() {
                if self.load_segments.val() {
                    self.pick_q[21 + k].d.next = 8.into();
                } else {
                    self.pick_q[21 + k].d.next = 32.into();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::{clock_cycle, settle};

    /// The programs as a table, destination by destination (`u0`, `u1`,
    /// `w0` lanes 0 to 2, `w1` lanes 0 to 2): the point of each step.
    /// Coplanar: lane `l` of step `s` is orient2d value `3 s + l` of
    /// `hulls_intersect_2d`; segments: lane `l` of step `s` is component
    /// `l` of the cross product of step `s` (`ab × ac`, `ab × ad`,
    /// `cd × ca`, `cd × cb` with a, b, c, d at points 0, 1, 3, 4).
    const COPLANAR: [[usize; 6]; 8] = [
        [0, 1, 2, 3, 4, 5],
        [1, 2, 0, 4, 5, 3],
        [0, 1, 2, 0, 0, 0],
        [0, 1, 2, 1, 1, 1],
        [0, 1, 2, 2, 2, 2],
        [3, 3, 3, 3, 4, 5],
        [4, 4, 4, 3, 4, 5],
        [5, 5, 5, 3, 4, 5],
    ];
    const SEGMENTS: [[usize; 4]; 8] = [
        [0, 0, 3, 3],
        [1, 1, 4, 4],
        [0, 0, 3, 3],
        [0, 0, 3, 3],
        [0, 0, 3, 3],
        [3, 4, 0, 1],
        [3, 4, 0, 1],
        [3, 4, 0, 1],
    ];

    fn program(segments: bool, d: usize, s: usize) -> u64 {
        let point = if segments {
            SEGMENTS[d][s]
        } else {
            COPLANAR[d][s]
        };
        1 << point
    }

    /// One clock with every copy driven alike: `load`, else moving on from
    /// `step` of a job of kind `segments`.
    fn clock(uut: &mut StepPrograms, load: Option<bool>, step: usize, segments: bool) {
        for c in 0..DESTINATIONS {
            uut.load[c].next = load.is_some();
            uut.step[c].next = (step as u64).into();
            uut.segments[c].next = segments;
            uut.moving[c].next = true;
        }
        uut.load_segments.next = load.unwrap_or(false);
        settle(uut);
        clock_cycle(uut, |u| &mut u.clock);
    }

    fn assert_picks(uut: &StepPrograms, segments: bool, s: usize) {
        for d in 0..8 {
            for k in 0..3 {
                assert_eq!(
                    uut.pick[3 * d + k].val().index() as u64,
                    program(segments, d, s),
                    "destination {d} coordinate {k}, step {s}, segments {segments}"
                );
            }
        }
    }

    /// Jobs back to back, each kind after each: every step's pick is the
    /// table's, and a load at a job's last step starts the next job's
    /// program at its first step.
    #[test]
    fn every_step_picks_the_programs_point() {
        let mut uut = StepPrograms::default();
        uut.connect_all();
        for kinds in [[false, true], [true, false], [false, false], [true, true]] {
            for (j, &kind) in kinds.iter().enumerate() {
                // The load: at the previous job's last step (j = 1), or idle.
                clock(&mut uut, Some(kind), if j == 0 { 0 } else { 3 }, !kind);
                assert_picks(&uut, kind, 0);
                let steps = if kind { 4 } else { 6 };
                for s in 0..steps - 1 {
                    clock(&mut uut, None, s, kind);
                    assert_picks(&uut, kind, s + 1);
                }
            }
        }
    }
}
