//! From two objects to the batches the hardware processes (thesis,
//! chapter 4; docs/ARCHITECTURE.md, conventions):
//!
//! 1. the AABB of each object and their overlap, the common BV (none: the
//!    objects cannot touch, zero pairs);
//! 2. per object the triangles whose f64 box meets the common BV (the
//!    conservative filter of [`triangle_box_overlap_conservative`]);
//! 3. the kept triangles of *both* objects quantized into one W-bit frame
//!    ([`Frame::fit`] over them);
//! 4. the integer triangle–box test against the integer common box, both
//!    grown by one grid step ([`BROAD_PHASE_MARGIN`]), see [`prepare`] for
//!    why it loses no pair that touches before or after quantization;
//! 5. the arrays split into tiles of at most `D` triangles (the memory depth
//!    of the generated hardware): one [`Batch`] per A-tile × B-tile, so every
//!    pair of kept triangles is in exactly one batch.
//!
//! Triangles carry their index in the object's triangle list as id
//! ([`load`] documents the indices).
//!
//! ```
//! use tritri_geom::scene::{load::load_object, prepare, SceneOptions};
//! let a = load_object("@torus", 8).unwrap();
//! let b = load_object("@sphere", 8).unwrap();
//! let scene = prepare(&a, &b, &SceneOptions { grid_bits: 24, depth: 4096, split: true }).unwrap();
//! assert!(scene.common.is_some());
//! assert!(scene.pairs_tested() < (a.triangles.len() * b.triangles.len()) as u64);
//! ```

pub mod load;
pub mod octree;
pub mod owner_slots;
pub mod reference;
pub mod render;

use crate::bounding_volume::{grown_triangle_touches_box, triangle_box_overlap_conservative, Aabb};
use crate::fixed_point::FixedTriangle;
use crate::octree::triangle_cell::BROAD_PHASE_MARGIN;
use crate::quantize::{Frame, QuantizeError};
use crate::triangle::Triangle;
use crate::two_objects::on_both;
use load::SceneObject;
use octree::{BatchCost, LocalFrames, OctreeSchedule};

/// A quantized triangle with the index it has in its object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TaggedTriangle {
    pub id: u32,
    pub triangle: FixedTriangle,
}

/// One load of the hardware's memories: every triangle of `a` is tested
/// against every triangle of `b`. All batches of a scene share one frame.
/// The arrays are slices of the scene's kept arrays (a large scene has
/// many tiles; copying each would cost `O(tiles * D)` memory).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Batch<'a> {
    pub a: &'a [TaggedTriangle],
    pub b: &'a [TaggedTriangle],
}

impl Batch<'_> {
    pub fn pairs(&self) -> u64 {
        self.a.len() as u64 * self.b.len() as u64
    }
}

/// What the scene is prepared for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneOptions {
    /// Coordinate width W.
    pub grid_bits: u32,
    /// Memory depth: the most triangles one array memory holds.
    pub depth: usize,
    /// Split arrays longer than `depth` into tiles; if false, refuse them.
    pub split: bool,
}

/// Why a scene could not be prepared.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error(transparent)]
    Quantize(#[from] QuantizeError),
    #[error("memory depth must be at least 1")]
    ZeroDepth,
    #[error(
        "the arrays in the common BV hold {kept_a} (A) and {kept_b} (B) triangles, more than the memory depth {depth}; \
         allow splitting into tiles (drop --no-split) or generate hardware with --depth {needed}"
    )]
    ExceedsDepth {
        kept_a: usize,
        kept_b: usize,
        depth: usize,
        needed: usize,
    },
}

/// How the arrays were cut to fit the memories.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tiling {
    pub depth: usize,
    /// Number of A-tiles and of B-tiles; batches = `a_tiles * b_tiles`.
    pub a_tiles: usize,
    pub b_tiles: usize,
}

impl Tiling {
    pub fn is_split(&self) -> bool {
        self.a_tiles > 1 || self.b_tiles > 1
    }
}

/// A scene ready for the hardware, with everything worth reporting.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedScene {
    pub n_a: usize,
    pub n_b: usize,
    pub box_a: Option<Aabb<f64>>,
    pub box_b: Option<Aabb<f64>>,
    /// The common BV; `None`: the objects' boxes do not meet, zero pairs.
    pub common: Option<Aabb<f64>>,
    /// Triangles kept by the conservative f64 filter (indices, ascending).
    pub candidates_a: Vec<u32>,
    pub candidates_b: Vec<u32>,
    /// The one frame of every batch (fitted over the candidates of both objects).
    pub frame: Option<Frame>,
    /// The integer common box of the exact filter.
    pub integer_box: Option<Aabb<i64>>,
    /// The arrays sent to the hardware: triangles that touch the integer box.
    pub kept_a: Vec<TaggedTriangle>,
    pub kept_b: Vec<TaggedTriangle>,
    pub tiling: Tiling,
    /// The octree broad phase's leaves ([`prepare_octree`]); `None`: the
    /// flat system of the thesis, every kept pair in one (tiled) batch.
    pub octree: Option<OctreeSchedule>,
}

impl PreparedScene {
    /// The batches: with the octree, each scheduled leaf's arrays (tiled
    /// when a leaf exceeds the depth); flat, A-tile by A-tile, each against
    /// every B-tile ([`Tiling`]). None when either array is empty.
    pub fn batches(&self) -> Vec<Batch<'_>> {
        match &self.octree {
            Some(octree) => self.leaf_batches(&octree.a, &octree.b),
            None => tile(&self.kept_a, &self.kept_b, self.tiling.depth),
        }
    }

    /// The octree leaves' batches over arrays parallel to the schedule's
    /// (`a[i]` stands for `octree.a[i]`), for example the same triangles
    /// with slots for ids ([`owner_slots::OwnerSlots::slotted`]). Empty
    /// without an octree.
    pub fn leaf_batches<'a>(
        &self,
        a: &'a [TaggedTriangle],
        b: &'a [TaggedTriangle],
    ) -> Vec<Batch<'a>> {
        let Some(octree) = &self.octree else {
            return Vec::new();
        };
        octree
            .leaves
            .iter()
            .flat_map(|leaf| tile(&a[leaf.a.clone()], &b[leaf.b.clone()], self.tiling.depth))
            .collect()
    }

    /// Pairs the hardware tests, the sum over batches: `|kept A| * |kept B|`
    /// flat, the sum over leaves with the octree.
    pub fn pairs_tested(&self) -> u64 {
        match &self.octree {
            Some(octree) => octree
                .leaves
                .iter()
                .map(|l| l.a.len() as u64 * l.b.len() as u64)
                .sum(),
            None => self.kept_a.len() as u64 * self.kept_b.len() as u64,
        }
    }

    /// What the host decides on the grid instead of the hardware, as
    /// batches: triangles too long for a leaf's window ([`LocalFrames`])
    /// against the other object. Grid coordinates.
    pub fn host_batches(&self) -> Vec<Batch<'_>> {
        self.octree.as_ref().map_or(Vec::new(), |o| {
            o.host_arrays.iter().map(|(a, b)| Batch { a, b }).collect()
        })
    }

    /// Pairs in [`Self::host_batches`].
    pub fn host_pairs(&self) -> u64 {
        self.host_batches().iter().map(Batch::pairs).sum()
    }

    /// `N1 * N2`: what testing every pair would cost.
    pub fn all_pairs(&self) -> u64 {
        self.n_a as u64 * self.n_b as u64
    }

    /// Share of all triangles (of both objects) that reach the hardware.
    pub fn fraction_in_common_bv(&self) -> f64 {
        let total = self.n_a + self.n_b;
        if total == 0 {
            0.0
        } else {
            (self.kept_a.len() + self.kept_b.len()) as f64 / total as f64
        }
    }
}

/// Runs steps 1–5 of the module documentation on objects `a` and `b` (B
/// already posed).
///
/// The integer box is the overlap of the integer AABBs of the quantized
/// candidates of A and of B, each grown by one grid step
/// ([`BROAD_PHASE_MARGIN`]); a triangle is kept when, grown by one step, it
/// touches that box ([`grown_triangle_touches_box`]). No pair is lost that
/// touches on the grid or on the original coordinates: if the original
/// triangles meet at `p`, quantization moved each by at most half a step,
/// so each quantized triangle has a point within half a step of `p`; that
/// point lies in its object's integer AABB, so `p` lies in both grown
/// AABBs, hence in the box, and both grown triangles contain `p`. (A pair
/// that meets on the grid is the case of a `p` on both quantized
/// triangles.) The octree's cells keep the same grown triangles
/// ([`octree::schedule`]), so the pair shares the leaf holding `p`.
/// A pair whose f64 triangles intersect is never dropped by the f64 filter
/// either: the meeting point lies in both objects' boxes, so in the common
/// BV, and the comparisons of the box filter are exact.
pub fn prepare(
    a: &SceneObject,
    b: &SceneObject,
    options: &SceneOptions,
) -> Result<PreparedScene, SceneError> {
    if options.depth == 0 {
        return Err(SceneError::ZeroDepth);
    }
    let box_a = Aabb::of_triangles(&a.triangles);
    let box_b = Aabb::of_triangles(&b.triangles);
    let common = match (&box_a, &box_b) {
        (Some(x), Some(y)) => x.overlap(y),
        _ => None,
    };
    let mut scene = PreparedScene {
        n_a: a.triangles.len(),
        n_b: b.triangles.len(),
        box_a,
        box_b,
        common,
        candidates_a: Vec::new(),
        candidates_b: Vec::new(),
        frame: None,
        integer_box: None,
        kept_a: Vec::new(),
        kept_b: Vec::new(),
        tiling: Tiling {
            depth: options.depth,
            a_tiles: 0,
            b_tiles: 0,
        },
        octree: None,
    };
    let Some(common) = common else {
        return Ok(scene);
    };

    // Each object's candidates (triangles whose box meets the common box)
    // and their bounds, the objects on two threads when they are large
    // (`on_both`).
    let triangles = a.triangles.len() + b.triangles.len();
    let candidates_and_bounds = |ts: &[Triangle]| {
        let ids: Vec<u32> = ts
            .iter()
            .enumerate()
            .filter(|(_, t)| triangle_box_overlap_conservative(t, &common))
            .map(|(i, _)| i as u32)
            .collect();
        let bounds = candidate_bounds(&ids, ts);
        (ids, bounds)
    };
    let ((candidates_a, bounds_a), (candidates_b, bounds_b)) = on_both(
        triangles,
        || candidates_and_bounds(&a.triangles),
        || candidates_and_bounds(&b.triangles),
    );
    scene.candidates_a = candidates_a;
    scene.candidates_b = candidates_b;
    // The candidates' bounds, one pass over each object's: the frame
    // is fitted over both (as `Frame::fit` over the candidates would), and
    // since quantizing is monotone on each axis (a difference, a division
    // by the positive step, a rounding: none reorders two values), the
    // candidates' quantized box is their f64 box quantized, so the integer
    // common box is known before any triangle is quantized. Then one pass
    // quantizes each candidate and keeps it at once if its grown triangle
    // touches that box: no array of every quantized candidate is written
    // and read again (at 72 bytes a triangle, that was most of the time).
    let frame = match (bounds_a, bounds_b) {
        (Ok(x), Ok(y)) => {
            let (lo, hi) = union_bounds(x, y);
            Frame::fit_bounds(lo, hi, options.grid_bits)?
        }
        // A coordinate that is not finite: the error names it.
        _ => Frame::fit(
            scene
                .candidates_a
                .iter()
                .map(|&i| &a.triangles[i as usize])
                .chain(scene.candidates_b.iter().map(|&i| &b.triangles[i as usize])),
            options.grid_bits,
        )?,
    };
    scene.frame = Some(frame);

    let margin = BROAD_PHASE_MARGIN as i64;
    let quantized_box = |bounds: Result<Option<([f64; 3], [f64; 3])>, ()>| {
        bounds.ok().flatten().map(|(lo, hi)| Aabb {
            lo: frame.quantize_point(lo),
            hi: frame.quantize_point(hi),
        })
    };
    let integer_box = match (quantized_box(bounds_a), quantized_box(bounds_b)) {
        (Some(x), Some(y)) => x.grown(margin).overlap(&y.grown(margin)),
        _ => None,
    };
    scene.integer_box = integer_box;
    if let Some(ibox) = integer_box {
        let kept = |ids: &[u32], ts: &[Triangle]| -> Vec<TaggedTriangle> {
            // Room for every candidate at once: most are kept, and a
            // growing array would copy them again.
            let mut kept = Vec::with_capacity(ids.len());
            for &id in ids {
                let triangle = frame.quantize(&ts[id as usize]);
                if grown_triangle_touches_box(&triangle, BROAD_PHASE_MARGIN, &ibox) {
                    kept.push(TaggedTriangle { id, triangle });
                }
            }
            kept
        };
        (scene.kept_a, scene.kept_b) = on_both(
            triangles,
            || kept(&scene.candidates_a, &a.triangles),
            || kept(&scene.candidates_b, &b.triangles),
        );
    }
    let (ka, kb, depth) = (scene.kept_a.len(), scene.kept_b.len(), options.depth);
    if (ka > depth || kb > depth) && !options.split {
        return Err(SceneError::ExceedsDepth {
            kept_a: ka,
            kept_b: kb,
            depth,
            needed: ka.max(kb),
        });
    }
    scene.tiling = Tiling {
        depth,
        a_tiles: ka.div_ceil(depth),
        b_tiles: kb.div_ceil(depth),
    };
    Ok(scene)
}

/// The bounds of the triangles `ids` of `ts`: `Ok(None)` for none, `Err`
/// if a coordinate is not finite.
fn candidate_bounds(ids: &[u32], ts: &[Triangle]) -> Result<Option<([f64; 3], [f64; 3])>, ()> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut finite = true;
    for &id in ids {
        for p in &ts[id as usize] {
            for k in 0..3 {
                let v = p[k];
                finite &= v.is_finite();
                lo[k] = if v < lo[k] { v } else { lo[k] };
                hi[k] = if v > hi[k] { v } else { hi[k] };
            }
        }
    }
    match (finite, ids.is_empty()) {
        (false, _) => Err(()),
        (true, true) => Ok(None),
        (true, false) => Ok(Some((lo, hi))),
    }
}

/// Both objects' bounds together (`lo[0] > hi[0]` for none).
fn union_bounds(
    x: Option<([f64; 3], [f64; 3])>,
    y: Option<([f64; 3], [f64; 3])>,
) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    // Compared as `Frame::fit` compares, A's bounds first.
    for (l, h) in x.into_iter().chain(y) {
        for k in 0..3 {
            lo[k] = if l[k] < lo[k] { l[k] } else { lo[k] };
            hi[k] = if h[k] > hi[k] { h[k] } else { hi[k] };
        }
    }
    (lo, hi)
}

/// [`prepare`], then the octree broad phase ([`octree`]) over the kept
/// arrays inside the integer common box, its leaves costed by `cost` (the
/// system's cycle model). With `split: false`, a leaf that still exceeds
/// the memory depth is refused. With `local_frames`, `options.grid_bits` is
/// the grid's width and the leaves go to hardware of `local_frames.width`
/// bits in frames of their own ([`LocalFrames`]).
pub fn prepare_octree(
    a: &SceneObject,
    b: &SceneObject,
    options: &SceneOptions,
    cost: &dyn BatchCost,
    local_frames: Option<LocalFrames>,
) -> Result<PreparedScene, SceneError> {
    let mut scene = prepare(
        a,
        b,
        &SceneOptions {
            split: true,
            ..*options
        },
    )?;
    let Some(ibox) = scene.integer_box else {
        return Ok(scene);
    };
    let octree = octree::schedule(
        &scene.kept_a,
        &scene.kept_b,
        &ibox,
        options.depth,
        cost,
        local_frames,
    );
    if let Some(leaf) = octree
        .leaves
        .iter()
        .find(|l| l.a.len() > options.depth || l.b.len() > options.depth)
    {
        if !options.split {
            let (kept_a, kept_b) = (leaf.a.len(), leaf.b.len());
            return Err(SceneError::ExceedsDepth {
                kept_a,
                kept_b,
                depth: options.depth,
                needed: kept_a.max(kept_b),
            });
        }
    }
    scene.octree = Some(octree);
    Ok(scene)
}

/// Every A-tile against every B-tile, tiles of at most `depth` triangles;
/// no batch when either array is empty.
pub fn tile<'a>(a: &'a [TaggedTriangle], b: &'a [TaggedTriangle], depth: usize) -> Vec<Batch<'a>> {
    let mut out = Vec::new();
    for ta in a.chunks(depth) {
        for tb in b.chunks(depth) {
            out.push(Batch { a: ta, b: tb });
        }
    }
    out
}

#[cfg(test)]
mod tests;
