//! What says a run is wrong. Every fault is a bug in the hardware or in one
//! of its models, never a limit of the configuration (that is
//! [`crate::scene_query::QueryError::Unsupported`]): the command line
//! reports each by name and exits with status 1.

use crate::engine::Engine;

/// One disagreement, named by what differed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Fault {
    /// The engine's pairs are not the exact model's on the same quantized
    /// coordinates (both decide the same integer triangles).
    DiffersFromGrid {
        engine: Engine,
        missing: Vec<(u32, u32)>,
        extra: Vec<(u32, u32)>,
    },
    /// A hardware overflow flag was raised.
    Overflow { what: &'static str },
    /// Simulated cycles outside what the cycle model allows (`low == high`
    /// where it gives the count exactly).
    Cycles { simulated: u64, low: u64, high: u64 },
    /// The owner filter let a pair through more than once.
    OwnerDuplicates { through: u64, distinct: u64 },
    /// The broad-phase top's pairs differ from its model's.
    TopPairs { top: usize, model: usize },
    /// The binning unit's clock-exact model and the broad phase's planner
    /// give other leaves.
    BinningLeaves { unit: usize, planner: usize },
    /// The emitted DRAM top walked the octree otherwise than its
    /// clock-exact model: `what` differs.
    TopWalk {
        what: &'static str,
        top: u64,
        model: u64,
    },
}

impl std::fmt::Display for Fault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Fault::DiffersFromGrid {
                engine,
                missing,
                extra,
            } => write!(
                f,
                "the {} engine differs from the exact model on the quantized coordinates: {} pairs missing, {} extra, e.g. {:?} {:?} (a bug)",
                engine.name(),
                missing.len(),
                extra.len(),
                &missing[..missing.len().min(5)],
                &extra[..extra.len().min(5)]
            ),
            Fault::Overflow { what } => write!(f, "OVERFLOW flag set: {what} (a bug)"),
            Fault::Cycles {
                simulated,
                low,
                high,
            } if low == high => write!(
                f,
                "{simulated} cycles simulated, the cycle model says {low} (a bug)"
            ),
            Fault::Cycles {
                simulated,
                low,
                high,
            } => write!(
                f,
                "done after {simulated} clocks, outside the models' {low} to {high} (a bug)"
            ),
            Fault::OwnerDuplicates { through, distinct } => write!(
                f,
                "the owner filter let {through} pairs through for {distinct} distinct pairs (a bug)"
            ),
            Fault::TopPairs { top, model } => write!(
                f,
                "the broad-phase top's {top} pairs differ from its model's {model} (a bug)"
            ),
            Fault::BinningLeaves { unit, planner } => write!(
                f,
                "the binning unit's model streams other leaves than the broad phase's planner ({unit} against {planner}; a bug)"
            ),
            Fault::TopWalk { what, top, model } => write!(
                f,
                "the DRAM top's {what}: {top}, its clock-exact model's {model} (a bug)"
            ),
        }
    }
}
