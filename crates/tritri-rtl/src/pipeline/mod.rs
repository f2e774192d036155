//! The Devillers–Guigue pipeline, one unit per step of the algorithm; the
//! top is [`triangle_pipeline::TrianglePipeline`].

pub mod align_t1;
pub mod align_t2;
pub mod base_polygon;
pub mod certified_orient3d;
pub mod coplanar_test;
pub mod decision;
pub mod degenerate_pair;
pub mod dominant_axis;
pub mod general_path;
pub mod hold_forecast;
pub mod hold_next;
pub mod hold_register;
pub mod interval_overlap;
pub mod load_enable;
pub mod normal;
pub mod orient3d_operands;
pub mod pipeline_for_width;
pub mod pipeline_unit;
pub mod plane_side;
pub mod ports;
pub mod rare_decisions;
pub mod segment_ends;
pub mod shared_rare_cases;
pub mod shared_rare_pipeline;
pub mod step_programs;
pub mod third_determinant;
pub mod triangle_front_end;
pub mod triangle_pipeline;
#[cfg(test)]
pub(crate) mod unit_vectors;
pub mod verdict_queue;

/// Width of the triangle ids carried with each triangle (the one place).
pub const ID_BITS: usize = 32;

/// Where a pipeline tests its rare pairs (coplanar, and two degenerate
/// triangles).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RareCasePath {
    /// Their own units beside the general path: 60 multipliers, no stall
    /// ([`triangle_pipeline::TrianglePipeline`]).
    #[default]
    Parallel,
    /// One shared unit that takes a pair every few clocks: 6 multipliers,
    /// the pipeline holding while a rare pair waits for it
    /// ([`shared_rare_pipeline::SharedRarePipeline`]).
    Shared,
}

impl RareCasePath {
    /// The command line's names (`tritri gen --rare-cases`, `tritri sim
    /// --rare-cases`), in the order of the variants.
    pub const NAMES: [&'static str; 2] = ["parallel", "shared"];

    /// The variants, the default first.
    pub const ALL: [RareCasePath; 2] = [RareCasePath::Parallel, RareCasePath::Shared];

    /// The command line's name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "parallel" => Some(RareCasePath::Parallel),
            "shared" => Some(RareCasePath::Shared),
            _ => None,
        }
    }
}
