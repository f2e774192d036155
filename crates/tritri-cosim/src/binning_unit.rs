//! Co-simulation of the binning unit ([`tritri_rtl::octree::binning_unit`]):
//! a scene's two arrays streamed in, the leaves streamed out, against the
//! cycle-exact model ([`tritri_rtl::octree::binning_machine`]), whose
//! leaves are the broad phase planner's.

use anyhow::bail;
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_rtl::octree::binning_machine::BinningParams;
use tritri_rtl::octree::binning_unit::BinningUnit;
use tritri_rtl::octree::cell_classifier::AXES;
use tritri_rtl::octree::value_bits;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// One leaf as the unit streams it: its cell and its arrays (indices into
/// the host's arrays).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamedLeaf {
    pub cell: Cell,
    pub a: Vec<u32>,
    pub b: Vec<u32>,
}

/// What a run gives: the leaves, and the clocks from the first triangle in
/// to the end of binning (the first clock the leaves stream).
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct BinningOutput {
    pub leaves: Vec<StreamedLeaf>,
    pub cycles: u64,
}

/// Memory sizes for a scene: every triangle, and list words for what the
/// model's run wrote.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitSizes {
    pub triangles: usize,
    pub list_words: usize,
    pub leaves: usize,
}

/// The unit's grids: the widths its setup and classifier are built for.
pub const BINNING_GRID_WIDTHS: [usize; 3] = [16, 24, 32];

/// The scene through the rust-hdl model of the unit for `grid_bits`-bit
/// coordinates; `reader_ready(clock)` drives `out_ready`.
pub fn run_rusthdl(
    grid_bits: usize,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    params: BinningParams,
    sizes: UnitSizes,
    reader_ready: &dyn Fn(u64) -> bool,
) -> anyhow::Result<BinningOutput> {
    fn run<const G: usize, const V: usize, const N: usize, const T: usize>(
        a: &[FixedTriangle],
        b: &[FixedTriangle],
        root: Cell,
        params: BinningParams,
        sizes: UnitSizes,
        reader_ready: &dyn Fn(u64) -> bool,
    ) -> anyhow::Result<BinningOutput> {
        let mut uut = BinningUnit::<G, V, N, T>::new(sizes.triangles, sizes.list_words, sizes.leaves).with_system(params.log_depth, params.log_pipelines);
        uut.connect_all();
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let g = |v: i64| -> Bits<G> { Bits::from((v as u64) & ((1u64 << G) - 1)) };
        uut.root_x.next = g(root.lo[0]);
        uut.root_y.next = g(root.lo[1]);
        uut.root_z.next = g(root.lo[2]);
        uut.root_level.next = (root.level as u64).into();
        uut.max_leaf_enable.next = params.max_leaf_level.is_some();
        uut.max_leaf_level.next = (params.max_leaf_level.unwrap_or(0) as u64).into();
        uut.start.next = true;
        clock_cycle(&mut uut, |u| &mut u.clock);
        uut.start.next = false;
        let stream: Vec<(bool, &FixedTriangle)> = a.iter().map(|t| (false, t)).chain(b.iter().map(|t| (true, t))).collect();
        let mut clock = 0u64;
        let mut next = 0;
        let mut out = BinningOutput::default();
        let mut binned_at = None;
        let mut current: Option<StreamedLeaf> = None;
        let limit = 1_000_000_000u64;
        loop {
            uut.in_valid.next = next < stream.len();
            if let Some(&(object, t)) = stream.get(next) {
                uut.in_object.next = object;
                uut.in_last.next = next + 1 == stream.len();
                let mut word = Bits::<T>::default();
                for (k, v) in t.iter().flatten().enumerate() {
                    word.set_bits::<G>(k * G, g(*v));
                }
                uut.in_vertices.next = word;
            }
            uut.out_ready.next = reader_ready(clock);
            settle(&mut uut);
            if uut.binned.val() && binned_at.is_none() {
                binned_at = Some(clock);
            }
            if uut.done.val() {
                break;
            }
            let taken = uut.in_valid.val() && uut.in_ready.val();
            if uut.out_valid.val() && uut.out_ready.val() {
                if uut.out_header.val() {
                    out.leaves.extend(current.take());
                    let coordinate = |v: Bits<G>| -> i64 { ((v.index() as i64) << (64 - G)) >> (64 - G) };
                    let lo = [coordinate(uut.out_x.val()), coordinate(uut.out_y.val()), coordinate(uut.out_z.val())];
                    current = Some(StreamedLeaf { cell: Cell { lo, level: uut.out_level.val().index() as u32 }, a: Vec::new(), b: Vec::new() });
                } else {
                    let Some(leaf) = current.as_mut() else { bail!("an entry before the first header at clock {clock}") };
                    let index = uut.out_index.val().index() as u32;
                    if uut.out_object.val() { leaf.b.push(index) } else { leaf.a.push(index) }
                }
            }
            clock_cycle(&mut uut, |u| &mut u.clock);
            if taken {
                next += 1;
            }
            clock += 1;
            if clock > limit {
                bail!("the binning unit did not finish in {limit} clocks");
            }
        }
        out.leaves.extend(current.take());
        // Clocks are counted from the first triangle taken (clock 0).
        out.cycles = binned_at.unwrap_or(clock);
        Ok(out)
    }
    match grid_bits {
        16 => run::<16, { value_bits(16) }, { AXES * value_bits(16) }, { 9 * 16 }>(a, b, root, params, sizes, reader_ready),
        24 => run::<24, { value_bits(24) }, { AXES * value_bits(24) }, { 9 * 24 }>(a, b, root, params, sizes, reader_ready),
        32 => run::<32, { value_bits(32) }, { AXES * value_bits(32) }, { 9 * 32 }>(a, b, root, params, sizes, reader_ready),
        g => bail!("the binning unit is built for {BINNING_GRID_WIDTHS:?}-bit grids, not {g}"),
    }
}
