//! The concrete system tops, one per supported coordinate width, and
//! run-time selection among them (as [`crate::pipeline::pipeline_for_width`] does for the
//! pipeline alone).
//!
//! ```
//! use tritri_rtl::system::system_for_width::{system_for_config, PipelineKind};
//! use tritri_rtl::system::SystemConfig;
//! let config = SystemConfig::new(24, 2).with_pipeline_latency(5).with_depth(16);
//! let system = system_for_config(config, PipelineKind::Stub).unwrap();
//! assert_eq!(system.system_config().pipelines, 2);
//! ```

use super::collision_system::{CollisionSystem, SharedCollisionSystem, StubCollisionSystem};
use super::host_ports::HostPorts;
use super::SystemConfig;
pub use crate::pipeline::pipeline_for_width::UnsupportedWidth;
use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};

/// Which pipelines the system holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PipelineKind {
    /// The Devillers–Guigue pipeline with its rare pairs on parallel units
    /// of its own ([`crate::pipeline::RareCasePath::Parallel`];
    /// `config.pipeline_latency` must be its latency).
    Parallel,
    /// [`super::stub_pipeline::StubPipeline`] of latency `config.pipeline_latency`.
    Stub,
    /// The Devillers–Guigue pipeline with its rare pairs on a shared unit
    /// ([`crate::pipeline::RareCasePath::Shared`],
    /// [`crate::pipeline::shared_rare_pipeline`]).
    Shared,
}

impl From<crate::pipeline::RareCasePath> for PipelineKind {
    /// The Devillers–Guigue pipelines with their rare cases on that path.
    fn from(rare_cases: crate::pipeline::RareCasePath) -> Self {
        match rare_cases {
            crate::pipeline::RareCasePath::Parallel => PipelineKind::Parallel,
            crate::pipeline::RareCasePath::Shared => PipelineKind::Shared,
        }
    }
}

macro_rules! system_widths {
    ($($w:literal),*) => {
        /// A new system for `config` (unconnected: the harness connects it).
        pub fn system_for_config(config: SystemConfig, kind: PipelineKind) -> Result<Box<dyn HostPorts>, UnsupportedWidth> {
            match (config.coordinate_bits, kind) {
                $(
                    ($w, PipelineKind::Parallel) => Ok(Box::new(
                        CollisionSystem::<$w, { difference_bits($w) }, { cross_bits($w) }, { orient3d_bits($w) }>::with_pipelines(config),
                    )),
                    ($w, PipelineKind::Stub) => Ok(Box::new(StubCollisionSystem::<$w>::with_stub_pipelines(config))),
                    ($w, PipelineKind::Shared) => Ok(Box::new(
                        SharedCollisionSystem::<$w, { difference_bits($w) }, { cross_bits($w) }, { orient3d_bits($w) }>::with_pipelines(config),
                    )),
                )*
                (w, _) => Err(UnsupportedWidth(w)),
            }
        }
    };
}

crate::pipeline::pipeline_for_width::for_supported_widths!(system_widths);
