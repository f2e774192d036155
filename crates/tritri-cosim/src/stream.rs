//! The stream schedule and the result type shared by every co-simulation
//! engine (rust-hdl direct drive, Icarus, Verilator).
//!
//! Schedule (thesis, chapter 3): for each base triangle, one cycle with
//! `bset = 1` loads it into the base registers, then every streamed triangle
//! follows, one per cycle, with `bset = 0`. Each streamed cycle yields one
//! verdict `L` cycles later, so a run of `N1` bases against `N2` streamed
//! triangles takes `N1 + N1 * N2 + L` cycles, counted from the first input
//! cycle to the cycle in which the last verdict is visible, inclusive.
//!
//! Every engine takes a [`TriangleStream`] and returns a [`StreamResult`];
//! two engines agree when their results are equal.

use tritri_geom::fixed_point::FixedTriangle;

/// A triangle with the id it carries through the pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IdTriangle {
    pub id: u32,
    pub triangle: FixedTriangle,
}

/// The work of one run: every base triangle against every streamed triangle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TriangleStream {
    /// The outer loop (`N1` triangles), each loaded once with `bset = 1`.
    pub bases: Vec<IdTriangle>,
    /// The inner loop (`N2` triangles), streamed past every base.
    pub streamed: Vec<IdTriangle>,
}

/// One cycle on the pipeline's input bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputCycle {
    pub valid: bool,
    pub bset: bool,
    pub id: u32,
    /// `x0 y0 z0 x1 y1 z1 x2 y2 z2`, each a signed W-bit value.
    pub coordinates: [i64; 9],
}

impl InputCycle {
    pub fn load_base(t: &IdTriangle) -> Self {
        InputCycle { valid: true, bset: true, id: t.id, coordinates: flatten(&t.triangle) }
    }
    pub fn test(t: &IdTriangle) -> Self {
        InputCycle { valid: true, bset: false, id: t.id, coordinates: flatten(&t.triangle) }
    }
    /// A bubble: nothing on the bus.
    pub fn idle() -> Self {
        InputCycle { valid: false, bset: false, id: 0, coordinates: [0; 9] }
    }
}

/// `x0 y0 z0 x1 y1 z1 x2 y2 z2`.
pub fn flatten(t: &FixedTriangle) -> [i64; 9] {
    [t[0][0], t[0][1], t[0][2], t[1][0], t[1][1], t[1][2], t[2][0], t[2][1], t[2][2]]
}

impl TriangleStream {
    /// Pairs the lists up with ids `0..` in their order.
    pub fn from_triangles(bases: &[FixedTriangle], streamed: &[FixedTriangle]) -> Self {
        let tag = |ts: &[FixedTriangle]| {
            ts.iter().enumerate().map(|(i, t)| IdTriangle { id: i as u32, triangle: *t }).collect()
        };
        TriangleStream { bases: tag(bases), streamed: tag(streamed) }
    }

    /// The input cycles, in order: per base one `bset` cycle, then the stream.
    pub fn schedule(&self) -> impl Iterator<Item = InputCycle> + '_ {
        self.bases.iter().flat_map(move |b| {
            std::iter::once(InputCycle::load_base(b)).chain(self.streamed.iter().map(InputCycle::test))
        })
    }

    /// `N1 + N1 * N2`.
    pub fn input_cycles(&self) -> u64 {
        let (n1, n2) = (self.bases.len() as u64, self.streamed.len() as u64);
        n1 + n1 * n2
    }

    /// `N1 + N1 * N2 + L` for a pipeline of latency `L` (0 when there is no pair).
    pub fn expected_cycles(&self, latency: u64) -> u64 {
        if self.bases.is_empty() || self.streamed.is_empty() {
            self.input_cycles()
        } else {
            self.input_cycles() + latency
        }
    }

    /// The expected verdicts, in output order, from a software model.
    pub fn expected(&self, intersects: impl Fn(&FixedTriangle, &FixedTriangle) -> bool) -> Vec<PairVerdict> {
        self.bases
            .iter()
            .flat_map(|b| {
                self.streamed.iter().map(|s| PairVerdict {
                    base_id: b.id,
                    stream_id: s.id,
                    hit: intersects(&b.triangle, &s.triangle),
                })
            })
            .collect::<Vec<_>>()
    }
}

/// One output of the pipeline: the verdict for (base, streamed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct PairVerdict {
    pub base_id: u32,
    pub stream_id: u32,
    pub hit: bool,
}

/// What a run returns: every verdict in output order, and the cycle count.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct StreamResult {
    pub verdicts: Vec<PairVerdict>,
    /// Cycles from the first input cycle to the last verdict, inclusive
    /// (`N1 + N1 * N2 + L`).
    pub cycles: u64,
}

impl StreamResult {
    /// The intersecting pairs `(base_id, stream_id)`.
    pub fn hits(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.verdicts.iter().filter(|v| v.hit).map(|v| (v.base_id, v.stream_id))
    }

    /// Verdicts that differ from `expected`, position by position (a length
    /// difference counts every missing or extra verdict).
    pub fn mismatches(&self, expected: &[PairVerdict]) -> usize {
        let common = self.verdicts.iter().zip(expected).filter(|(a, b)| a != b).count();
        common + self.verdicts.len().abs_diff(expected.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The schedule is one bset cycle per base followed by the whole stream.
    #[test]
    fn schedule_is_bset_then_stream_per_base() {
        let t = [[0, 0, 0], [1, 0, 0], [0, 1, 0]];
        let s = TriangleStream::from_triangles(&[t, t], &[t, t, t]);
        let cycles: Vec<_> = s.schedule().map(|c| (c.bset, c.id)).collect();
        assert_eq!(
            cycles,
            vec![(true, 0), (false, 0), (false, 1), (false, 2), (true, 1), (false, 0), (false, 1), (false, 2)]
        );
        assert_eq!(s.input_cycles(), 8);
        assert_eq!(s.expected_cycles(30), 38);
    }
}
