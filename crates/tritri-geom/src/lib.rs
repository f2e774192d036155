//! Software models of the Devillers–Guigue triangle–triangle overlap test.
//!
//! * [`exact_f64`]: exact predicates on the f64 coordinates — the ground truth;
//! * [`fixed_point`]: exact integer predicates on W-bit coordinates — the
//!   bit-exact model of the hardware, with [`quantize`] and [`widths`];
//! * [`published_float`]: the published double / single precision code, fast
//!   and not robust;
//! * [`moller`]: Möller's 1997 test with its epsilon, the classic baseline.
//!
//! All are reached through [`arithmetic::Arithmetic`].
//!
//! ```
//! use tritri_geom::exact_f64;
//! let t1 = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let t2 = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]; // shares a vertex
//! assert!(exact_f64::intersects(&t1, &t2)); // touching counts
//! ```

pub mod arithmetic;
pub mod bezier;
pub mod bounding_volume;
pub mod builtin_scene;
pub mod certificate;
pub mod devillers_guigue;
pub mod exact_big_integer;
pub mod exact_f64;
pub mod fixed_point;
pub mod hard_cases;
pub mod kernel;
pub mod mesh;
pub mod moller;
pub mod octree;
pub mod pairs_io;
pub mod published_float;
pub mod quantize;
pub mod raster;
pub mod scene;
pub mod sign;
mod text;
pub mod triangle;
pub mod two_objects;
pub mod widths;

#[cfg(test)]
mod reader_fuzz;

pub use triangle::{Point, Triangle, TrianglePair};
