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

use tritri_geom::certificate::CertifiedVerdict;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::scene::{Batch, TaggedTriangle};
use tritri_geom::triangle::{permute, VERTEX_PERMUTATIONS};
use tritri_rtl::pipeline::pipeline_for_width::PipelineInput;
use tritri_rtl::system::rare_case_model::{rare_case_cost, RareCaseCost};

/// The work of one run: every base triangle against every streamed triangle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TriangleStream {
    /// The outer loop (`N1` triangles), each loaded once with `bset = 1`.
    pub bases: Vec<TaggedTriangle>,
    /// The inner loop (`N2` triangles), streamed past every base.
    pub streamed: Vec<TaggedTriangle>,
}

impl TriangleStream {
    /// Pairs the lists up with ids `0..` in their order.
    pub fn from_triangles(bases: &[FixedTriangle], streamed: &[FixedTriangle]) -> Self {
        let tag = |ts: &[FixedTriangle]| {
            ts.iter()
                .enumerate()
                .map(|(i, t)| TaggedTriangle {
                    id: i as u32,
                    triangle: *t,
                })
                .collect()
        };
        TriangleStream {
            bases: tag(bases),
            streamed: tag(streamed),
        }
    }

    /// `(id, triangle)` lists as a stream.
    pub fn from_tagged(bases: &[(u32, FixedTriangle)], streamed: &[(u32, FixedTriangle)]) -> Self {
        let tag = |ts: &[(u32, FixedTriangle)]| {
            ts.iter()
                .map(|&(id, triangle)| TaggedTriangle { id, triangle })
                .collect()
        };
        TriangleStream {
            bases: tag(bases),
            streamed: tag(streamed),
        }
    }

    /// The input cycles, in order: per base one `bset` cycle, then the stream.
    pub fn schedule(&self) -> impl Iterator<Item = PipelineInput> + '_ {
        self.bases.iter().flat_map(move |b| {
            std::iter::once(PipelineInput::load_base(b))
                .chain(self.streamed.iter().map(PipelineInput::test))
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

    /// The expected verdicts, in output order, from a software model
    /// (`tritri_geom::certificate::certified_intersects`: the verdict and
    /// its certificate).
    pub fn expected(
        &self,
        model: impl Fn(&FixedTriangle, &FixedTriangle) -> CertifiedVerdict,
    ) -> Vec<PairVerdict> {
        self.bases
            .iter()
            .flat_map(|b| {
                self.streamed
                    .iter()
                    .map(|s| PairVerdict::new(b.id, s.id, model(&b.triangle, &s.triangle)))
            })
            .collect::<Vec<_>>()
    }
}

/// A base triangle and the triangles streamed past it. A list of groups is
/// the general form of a test run: unlike a [`TriangleStream`], every base
/// has a stream of its own.
pub type PairGroup = (FixedTriangle, Vec<FixedTriangle>);

/// The 72 orderings of a pair (6 vertex orders of each triangle, and the two
/// roles swapped) as 12 groups: each ordering of one triangle as the base,
/// against the 6 orderings of the other. The algorithm's alignment steps
/// take a different branch for each, so a verdict that depends on the
/// ordering shows up here.
pub fn all_orderings(t1: FixedTriangle, t2: FixedTriangle) -> Vec<PairGroup> {
    let mut groups = Vec::with_capacity(12);
    for (a, b) in [(t1, t2), (t2, t1)] {
        for p in VERTEX_PERMUTATIONS {
            groups.push((
                permute(a, p),
                VERTEX_PERMUTATIONS.iter().map(|&q| permute(b, q)).collect(),
            ));
        }
    }
    groups
}

/// The input cycles of `groups` (per group one `bset` cycle, then its
/// streamed triangles) and the verdicts `model` expects, in output order.
/// A base's id is its group's index, a streamed triangle's id its position
/// in the group, so a verdict names the pair it belongs to.
pub fn group_schedule(
    groups: &[PairGroup],
    model: impl Fn(&FixedTriangle, &FixedTriangle) -> CertifiedVerdict,
) -> (Vec<PipelineInput>, Vec<PairVerdict>) {
    let mut cycles = Vec::with_capacity(groups.iter().map(|(_, s)| 1 + s.len()).sum());
    let mut expected = Vec::with_capacity(cycles.capacity() - groups.len());
    for (g, (base, streamed)) in groups.iter().enumerate() {
        let base_id = g as u32;
        cycles.push(PipelineInput::load_base(&TaggedTriangle {
            id: base_id,
            triangle: *base,
        }));
        for (s, t) in streamed.iter().enumerate() {
            let stream_id = s as u32;
            cycles.push(PipelineInput::test(&TaggedTriangle {
                id: stream_id,
                triangle: *t,
            }));
            expected.push(PairVerdict::new(base_id, stream_id, model(base, t)));
        }
    }
    (cycles, expected)
}

/// What the rare pairs of `groups`, sent as [`group_schedule`] sends them
/// (no gap between groups), cost one pipeline with the shared rare-case
/// unit: `system::rare_case_model`'s count, which the pipeline's `hold`
/// must equal clock for clock.
pub fn shared_path_cost(groups: &[PairGroup]) -> RareCaseCost {
    let tag = |id: usize, triangle: &FixedTriangle| TaggedTriangle {
        id: id as u32,
        triangle: *triangle,
    };
    let owned: Vec<([TaggedTriangle; 1], Vec<TaggedTriangle>)> = groups
        .iter()
        .enumerate()
        .map(|(g, (base, streamed))| {
            (
                [tag(g, base)],
                streamed
                    .iter()
                    .enumerate()
                    .map(|(s, t)| tag(s, t))
                    .collect(),
            )
        })
        .collect();
    let batches: Vec<Batch> = owned.iter().map(|(a, b)| Batch { a, b }).collect();
    rare_case_cost(1, &batches)
}

/// One output of the pipeline: the verdict for (base, streamed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct PairVerdict {
    pub base_id: u32,
    pub stream_id: u32,
    pub hit: bool,
    /// `out_certain`: the verdict is provably the verdict before quantization.
    pub certain: bool,
}

impl PairVerdict {
    /// The verdict of a model on (base, streamed).
    pub fn new(base_id: u32, stream_id: u32, verdict: CertifiedVerdict) -> Self {
        PairVerdict {
            base_id,
            stream_id,
            hit: verdict.hit,
            certain: verdict.certain,
        }
    }
}

/// What a run returns: every verdict in output order, and the cycle count.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct StreamResult {
    pub verdicts: Vec<PairVerdict>,
    /// Cycles from the first input cycle to the last verdict, inclusive
    /// (`N1 + N1 * N2 + L`, plus `held`).
    pub cycles: u64,
    /// Cycles in which the pipeline held its input (`hold` high: a rare
    /// pair waited for the shared unit); 0 with the parallel rare tests.
    pub held: u64,
}

impl StreamResult {
    /// The intersecting pairs `(base_id, stream_id)`.
    pub fn hits(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.verdicts
            .iter()
            .filter(|v| v.hit)
            .map(|v| (v.base_id, v.stream_id))
    }

    /// Verdicts that differ from `expected`, position by position (a length
    /// difference counts every missing or extra verdict).
    pub fn mismatches(&self, expected: &[PairVerdict]) -> usize {
        let common = self
            .verdicts
            .iter()
            .zip(expected)
            .filter(|(a, b)| a != b)
            .count();
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
            vec![
                (true, 0),
                (false, 0),
                (false, 1),
                (false, 2),
                (true, 1),
                (false, 0),
                (false, 1),
                (false, 2)
            ]
        );
        assert_eq!(s.input_cycles(), 8);
        assert_eq!(s.expected_cycles(30), 38);
    }

    /// The 72 orderings are 72 distinct pairs, and the group schedule names
    /// each verdict by (group, position).
    #[test]
    fn all_orderings_are_72_distinct_pairs() {
        let t1 = [[0, 0, 0], [1, 0, 0], [0, 1, 0]];
        let t2 = [[5, 5, 5], [6, 5, 5], [5, 7, 5]];
        let groups = all_orderings(t1, t2);
        let pairs: std::collections::BTreeSet<_> = groups
            .iter()
            .flat_map(|(b, s)| s.iter().map(move |t| (*b, *t)))
            .collect();
        assert_eq!(pairs.len(), 72);
        let (cycles, expected) = group_schedule(&groups, |a, _| CertifiedVerdict {
            hit: a == &t1,
            certain: true,
        });
        assert_eq!(cycles.len(), 12 + 72);
        assert_eq!(cycles.iter().filter(|c| c.bset).count(), 12);
        assert_eq!(
            expected.iter().filter(|v| v.hit).count(),
            6,
            "t1 in its own order is the base of one group"
        );
        assert_eq!((expected[7].base_id, expected[7].stream_id), (1, 1));
    }
}
