//! The concrete pipelines, one per supported coordinate width, and run-time
//! selection among them.
//!
//! Stable Rust cannot compute `Bits<{W + 1}>` from a generic `W`, so each
//! width is instantiated with its derived widths spelled out as constant
//! expressions of `tritri_geom::widths` (the one place that derives them);
//! [`TrianglePipeline::new`] checks them again.
//!
//! ```
//! use tritri_rtl::pipeline::pipeline_for_width::{pipeline_for_width, SUPPORTED_WIDTHS};
//! assert!(SUPPORTED_WIDTHS.contains(&24));
//! let p = pipeline_for_width(24).unwrap();
//! assert_eq!(p.width(), 24);
//! assert_eq!(p.latency(), tritri_rtl::pipeline::triangle_pipeline::latency());
//! ```

use crate::arith::convert::from_i128;
use crate::broad_phase::binning_unit::on_unit_stack;
use crate::pipeline::shared_rare_pipeline::SharedRarePipeline;
use crate::pipeline::triangle_pipeline::{latency, TrianglePipeline};
use crate::pipeline::RareCasePath;
use crate::sim_drive;
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::scene::TaggedTriangle;
use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};

/// One clock's worth of the pipeline's input bus (thesis, chapter 3: a
/// `bset` cycle loads the base triangle, every following valid cycle tests
/// one streamed triangle against it). Every engine, rust-hdl, Icarus and
/// Verilator, is driven with these.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PipelineInput {
    pub valid: bool,
    pub bset: bool,
    pub id: u32,
    /// `x0 y0 z0 x1 y1 z1 x2 y2 z2`, each within the W-bit signed range.
    pub vertices: [i64; 9],
}

impl PipelineInput {
    /// The cycle that loads `t` into the base registers.
    pub fn load_base(t: &TaggedTriangle) -> Self {
        PipelineInput {
            valid: true,
            bset: true,
            id: t.id,
            vertices: flatten(&t.triangle),
        }
    }
    /// The cycle that tests `t` against the loaded base.
    pub fn test(t: &TaggedTriangle) -> Self {
        PipelineInput {
            valid: true,
            bset: false,
            id: t.id,
            vertices: flatten(&t.triangle),
        }
    }
    /// A bubble: nothing on the bus.
    pub fn idle() -> Self {
        PipelineInput::default()
    }
}

/// `x0 y0 z0 x1 y1 z1 x2 y2 z2`, the order of the coordinate ports.
pub fn flatten(t: &FixedTriangle) -> [i64; 9] {
    [
        t[0][0], t[0][1], t[0][2], t[1][0], t[1][1], t[1][2], t[2][0], t[2][1], t[2][2],
    ]
}

/// The output ports after a clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PipelineOutput {
    pub valid: bool,
    pub hit: bool,
    /// The verdict is provably the verdict before quantization.
    pub certain: bool,
    pub base_id: u32,
    pub stream_id: u32,
}

/// A simulated pipeline of some width, driven directly (see
/// [`crate::sim_drive`]). Object safe, so the width can be chosen at run time.
pub trait PipelineSimulation: Send {
    /// Coordinate width W.
    fn width(&self) -> usize;
    /// Latency `L` in clocks.
    fn latency(&self) -> usize;
    /// Drives the input ports (they take effect at the next clock).
    fn set_input(&mut self, input: &PipelineInput);
    /// The pipeline holds this clock (a rare pair waits for the shared
    /// unit): the input on the bus is not taken and must stay there.
    /// Depends on registers only, so it can be read before the edge.
    fn hold(&self) -> bool;
    /// Drives the clock enable.
    fn set_advance(&mut self, advance: bool);
    /// Drives the synchronous reset.
    fn set_reset(&mut self, rst: bool);
    /// One clock period, then settle.
    fn clock_cycle(&mut self);
    /// Drives the clock to `level` and settles (half a period).
    fn half_cycle(&mut self, level: bool);
    /// The output ports.
    fn output(&self) -> PipelineOutput;
    /// The circuit, for probes (VCD).
    fn block(&self) -> &dyn Block;
    /// rust-hdl's Verilog for this pipeline (top module `top`) and its units.
    fn raw_design(&self) -> crate::unit::RawDesign;
}

/// The simulation interface of a pipeline top; `$hold` reads its `hold`
/// port, if it has one, and `$connect_more` marks its other inputs driven
/// (a pipeline on its own leaves them 0).
macro_rules! pipeline_simulation {
    ($top:ident, $hold:expr, $connect_more:expr) => {
        impl<const W: usize, const D: usize, const C: usize, const O: usize> $top<W, D, C, O> {
            /// The nine coordinate inputs `in_x0 … in_z2`, in bus order.
            pub fn coordinate_inputs(&mut self) -> [&mut Signal<In, Bits<W>>; 9] {
                [
                    &mut self.in_x0,
                    &mut self.in_y0,
                    &mut self.in_z0,
                    &mut self.in_x1,
                    &mut self.in_y1,
                    &mut self.in_z1,
                    &mut self.in_x2,
                    &mut self.in_y2,
                    &mut self.in_z2,
                ]
            }

            /// A pipeline ready to simulate: every top-level input marked driven,
            /// internal connections made, `advance` high, `reset` low.
            pub fn new_connected() -> Self {
                let mut p = Self::new();
                p.clock.connect();
                p.reset.connect();
                p.advance.connect();
                p.in_valid.connect();
                p.in_bset.connect();
                p.in_id.connect();
                for v in p.coordinate_inputs() {
                    v.connect();
                }
                $connect_more(&mut p);
                p.connect_all();
                p.advance.next = true;
                sim_drive::settle(&mut p);
                p
            }
        }

        impl<const W: usize, const D: usize, const C: usize, const O: usize> PipelineSimulation
            for $top<W, D, C, O>
        {
            fn width(&self) -> usize {
                W
            }
            fn latency(&self) -> usize {
                latency()
            }
            fn set_input(&mut self, input: &PipelineInput) {
                self.in_valid.next = input.valid;
                self.in_bset.next = input.bset;
                self.in_id.next = Bits::from(input.id as u64);
                for (signal, &v) in self.coordinate_inputs().into_iter().zip(&input.vertices) {
                    let lo = -(1i64 << (W - 1));
                    let hi = (1i64 << (W - 1)) - 1;
                    assert!(
                        (lo..=hi).contains(&v),
                        "coordinate {v} does not fit in {W} bits"
                    );
                    signal.next = from_i128::<W>(v as i128);
                }
            }
            fn hold(&self) -> bool {
                $hold(self)
            }
            fn set_advance(&mut self, advance: bool) {
                self.advance.next = advance;
            }
            fn set_reset(&mut self, rst: bool) {
                self.reset.next = rst;
            }
            fn clock_cycle(&mut self) {
                sim_drive::clock_cycle(self, |p| &mut p.clock);
            }
            fn half_cycle(&mut self, level: bool) {
                self.clock.next = Clock { clk: level };
                sim_drive::settle(self);
            }
            fn output(&self) -> PipelineOutput {
                PipelineOutput {
                    valid: self.out_valid.val(),
                    hit: self.out_hit.val(),
                    certain: self.out_certain.val(),
                    base_id: self.out_base_id.val().to_u32(),
                    stream_id: self.out_stream_id.val().to_u32(),
                }
            }
            fn block(&self) -> &dyn Block {
                self
            }
            fn raw_design(&self) -> crate::unit::RawDesign {
                crate::unit::RawDesign::of(self)
            }
        }
    };
}

pipeline_simulation!(
    TrianglePipeline,
    |_: &TrianglePipeline<W, D, C, O>| false,
    |_: &mut TrianglePipeline<W, D, C, O>| ()
);
pipeline_simulation!(
    SharedRarePipeline,
    |p: &SharedRarePipeline<W, D, C, O>| p.hold.val(),
    |p: &mut SharedRarePipeline<W, D, C, O>| {
        p.hold_others.connect();
    }
);

/// Calls `$then!` with the one list of coordinate widths that have
/// hardware. The pipelines here, the systems
/// (`system::system_for_width`), [`SUPPORTED_WIDTHS`] and through it the
/// command line's checks and help all come from this list.
macro_rules! for_supported_widths {
    ($then:ident) => {
        $then!(8, 12, 16, 18, 20, 24, 28, 32);
    };
}
pub(crate) use for_supported_widths;

macro_rules! pipeline_widths {
    ($($w:literal),*) => {
        /// Coordinate widths with a concrete pipeline and system.
        pub const SUPPORTED_WIDTHS: &[usize] = &[$($w),*];

        /// A new, connected pipeline for `width`-bit coordinates, its rare
        /// cases on the path `rare_cases` names.
        pub fn pipeline_with(
            width: usize,
            rare_cases: RareCasePath,
        ) -> Result<Box<dyn PipelineSimulation>, UnsupportedWidth> {
            match (width, rare_cases) {
                // Built where they fit: at W = 32 (and with the shared unit
                // at every width) they outgrow a test thread's stack.
                $(($w, RareCasePath::Parallel) => Ok(on_unit_stack(|| -> Box<dyn PipelineSimulation> { Box::new(
                    TrianglePipeline::<$w, { difference_bits($w) }, { cross_bits($w) }, { orient3d_bits($w) }>::new_connected(),
                ) })),
                ($w, RareCasePath::Shared) => Ok(on_unit_stack(|| -> Box<dyn PipelineSimulation> { Box::new(
                    SharedRarePipeline::<$w, { difference_bits($w) }, { cross_bits($w) }, { orient3d_bits($w) }>::new_connected(),
                ) })),)*
                _ => Err(UnsupportedWidth(width)),
            }
        }
    };
}

for_supported_widths!(pipeline_widths);

/// A new, connected pipeline for `width`-bit coordinates, with the rare
/// cases' tests in parallel (the default).
pub fn pipeline_for_width(width: usize) -> Result<Box<dyn PipelineSimulation>, UnsupportedWidth> {
    pipeline_with(width, RareCasePath::Parallel)
}

/// `Ok` when `width` has hardware, else the error that lists the widths
/// that do.
pub fn check_width(width: usize) -> Result<(), UnsupportedWidth> {
    if SUPPORTED_WIDTHS.contains(&width) {
        Ok(())
    } else {
        Err(UnsupportedWidth(width))
    }
}

/// A width without a concrete pipeline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnsupportedWidth(pub usize);

impl std::fmt::Display for UnsupportedWidth {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "no hardware is generated for {}-bit coordinates; the supported widths are {:?}",
            self.0, SUPPORTED_WIDTHS
        )
    }
}

impl std::error::Error for UnsupportedWidth {}

/// rust-hdl's generated Verilog for the pipeline top at `width` (top module
/// `top`, submodules `top$child`): raw, before the emitter's clean-up.
pub fn raw_design(width: usize) -> Result<crate::unit::RawDesign, UnsupportedWidth> {
    Ok(pipeline_for_width(width)?.raw_design())
}
