//! Tessellation driven by a collision query ("model only what a scene
//! needs"): only the parts of the patches that can touch the other object
//! become triangles, each only as fine as the query's tolerance asks.
//!
//! A patch lies in the convex hull of its control net, so in the net's
//! box; so does every tessellation of it (its triangles are convex
//! combinations of surface points). A patch whose net's box misses the
//! *region* (the box where the two objects can meet: the overlap of their
//! conservative boxes) has no triangle that can touch the other object and
//! is left out. A patch that meets the region without lying inside it is
//! cut in four by De Casteljau, up to [`MAX_SPLITS`] times, and each quarter
//! is judged again, so a large patch with a small contact yields triangles
//! near the contact only. Each kept piece is tessellated at the fewest
//! samples per side whose deviation bound ([`super::lod::error_level`]) is
//! within the tolerance.
//!
//! What is left out cannot intersect the other object
//! (`teapot_patches_left_out_touch_nothing` in `tests/shared_testdata.rs`
//! checks it on the teapot against spheres).

use super::lod::{deviation_bound, error_level};
use super::BezierPatch;
use crate::bounding_volume::Aabb;
use crate::triangle::Triangle;

/// Cuts into quarters at most this many times per patch.
pub const MAX_SPLITS: u32 = 4;

pub use super::MAX_SAMPLES;

/// An object's patches tessellated for one query.
#[derive(Clone, Debug, PartialEq)]
pub struct QueryTessellation {
    pub triangles: Vec<Triangle>,
    /// The patch (index in the file) each triangle comes from.
    pub face_of: Vec<usize>,
    /// Patches with at least one piece kept, and the pieces tessellated.
    pub patches_kept: usize,
    pub pieces: usize,
    /// Samples per side that every patch needs for the tolerance when all
    /// are tessellated alike, and the triangles that uniform tessellation
    /// of every patch gives.
    pub uniform_samples: usize,
    pub uniform_triangles: usize,
    /// The largest deviation bound of a tessellated piece at its samples:
    /// at most the tolerance, unless a piece needed more than
    /// [`MAX_SAMPLES`] a side.
    pub bound: f64,
}

/// The box of a patch's control net.
pub fn net_box(patch: &BezierPatch) -> Aabb<f64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in patch.net.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Aabb { lo, hi }
}

/// The box of every patch's net (`None` for no patches).
pub fn patches_box(patches: &[BezierPatch]) -> Option<Aabb<f64>> {
    patches.iter().map(net_box).reduce(|a, b| Aabb {
        lo: [0, 1, 2].map(|k| a.lo[k].min(b.lo[k])),
        hi: [0, 1, 2].map(|k| a.hi[k].max(b.hi[k])),
    })
}

fn inside(inner: &Aabb<f64>, outer: &Aabb<f64>) -> bool {
    (0..3).all(|k| outer.lo[k] <= inner.lo[k] && inner.hi[k] <= outer.hi[k])
}

/// One kept piece of a patch: the patch's index, the piece (the patch or a
/// De Casteljau quarter of it) and its samples per side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QueryPiece {
    pub patch: usize,
    pub piece: BezierPatch,
    pub samples: usize,
}

/// The pieces of `patches` a query over `region` keeps (module docs), each
/// with the fewest samples per side within `tolerance`, and the number of
/// patches with a piece kept.
pub fn query_pieces(
    patches: &[BezierPatch],
    region: Option<&Aabb<f64>>,
    tolerance: f64,
    max_splits: u32,
) -> (Vec<QueryPiece>, usize) {
    let mut out = Vec::new();
    let mut patches_kept = 0;
    let Some(region) = region else {
        return (out, 0);
    };
    for (index, patch) in patches.iter().enumerate() {
        let mut pieces = vec![(*patch, 0)];
        let mut kept = false;
        while let Some((piece, splits)) = pieces.pop() {
            let bounds = net_box(&piece);
            if bounds.overlap(region).is_none() {
                continue;
            }
            if splits < max_splits && !inside(&bounds, region) {
                pieces.extend(quarters(&piece).map(|q| (q, splits + 1)));
                continue;
            }
            out.push(QueryPiece {
                patch: index,
                piece,
                samples: error_level(&piece, tolerance, MAX_SAMPLES),
            });
            kept = true;
        }
        patches_kept += kept as usize;
    }
    (out, patches_kept)
}

/// A patch cut in four by De Casteljau.
fn quarters(patch: &BezierPatch) -> [BezierPatch; 4] {
    let (a, b) = patch.split_u();
    let ((c, d), (e, f)) = (a.split_v(), b.split_v());
    [c, d, e, f]
}

/// The pieces recut until each needs at most `most` samples a side (the
/// tessellation unit takes `2^3` or `2^4`): a piece that needs more is cut
/// in four and each quarter's samples found again, within the same
/// tolerance. The quarters' own levels are at most half their parent's
/// plus one (the second differences shrink fourfold).
pub fn pieces_within(pieces: &[QueryPiece], most: usize, tolerance: f64) -> Vec<QueryPiece> {
    let mut out = Vec::new();
    let mut todo: Vec<QueryPiece> = pieces.iter().rev().copied().collect();
    while let Some(p) = todo.pop() {
        if p.samples <= most {
            out.push(p);
            continue;
        }
        for q in quarters(&p.piece).into_iter().rev() {
            todo.push(QueryPiece {
                patch: p.patch,
                piece: q,
                samples: error_level(&q, tolerance, MAX_SAMPLES),
            });
        }
    }
    out
}

/// The patches tessellated for a query over `region` to within `tolerance`
/// (module docs); `None` for the region: nothing can touch.
pub fn tessellate_for_query(
    patches: &[BezierPatch],
    region: Option<&Aabb<f64>>,
    tolerance: f64,
    max_splits: u32,
) -> QueryTessellation {
    let uniform_samples = patches
        .iter()
        .map(|p| error_level(p, tolerance, MAX_SAMPLES))
        .max()
        .unwrap_or(1);
    let uniform_triangles = patches
        .iter()
        .map(|p| p.tessellate(uniform_samples).len())
        .sum();
    let (pieces, patches_kept) = query_pieces(patches, region, tolerance, max_splits);
    let mut out = QueryTessellation {
        triangles: Vec::new(),
        face_of: Vec::new(),
        patches_kept,
        pieces: pieces.len(),
        uniform_samples,
        uniform_triangles,
        bound: 0.0,
    };
    for p in &pieces {
        out.bound = out.bound.max(deviation_bound(&p.piece, p.samples));
        let triangles = p.piece.tessellate(p.samples);
        out.face_of
            .extend(std::iter::repeat_n(p.patch, triangles.len()));
        out.triangles.extend(triangles);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    /// A region around everything keeps every patch whole (no cut), at the
    /// error level; a region beside the patch keeps nothing; a small region
    /// at a corner keeps a few quarters and fewer triangles than the whole.
    #[test]
    fn only_what_meets_the_region_is_tessellated() {
        let patch = wavy_patch();
        let whole = net_box(&patch);
        let tolerance = 1e-3 * whole.extent();
        let all = tessellate_for_query(&[patch], Some(&whole.expanded(1.0)), tolerance, MAX_SPLITS);
        let n = error_level(&patch, tolerance, MAX_SAMPLES);
        assert_eq!(
            (all.patches_kept, all.pieces, all.triangles.len()),
            (1, 1, patch.tessellate(n).len())
        );
        assert_eq!(
            (all.uniform_samples, all.uniform_triangles),
            (n, all.triangles.len())
        );
        assert!(deviation_bound(&patch, n) <= tolerance);
        assert!(all.bound <= tolerance && all.bound == deviation_bound(&patch, n));
        // A tolerance no piece can meet at MAX_SAMPLES a side: the bound
        // says what was reached instead.
        let tight = tessellate_for_query(&[patch], Some(&whole.expanded(1.0)), 1e-12, 0);
        assert!(tight.bound > 1e-12, "{}", tight.bound);

        let beside = Aabb {
            lo: whole.hi.map(|c| c + 1.0),
            hi: whole.hi.map(|c| c + 2.0),
        };
        let none = tessellate_for_query(&[patch], Some(&beside), tolerance, MAX_SPLITS);
        assert_eq!((none.patches_kept, none.triangles.len()), (0, 0));
        assert!(tessellate_for_query(&[patch], None, tolerance, MAX_SPLITS)
            .triangles
            .is_empty());

        // A small box around the surface's corner S(0, 0) = net[0][0].
        let c = patch.net[0][0];
        let corner = Aabb {
            lo: [0, 1, 2].map(|k| c[k] - 0.05 * whole.extent()),
            hi: [0, 1, 2].map(|k| c[k] + 0.05 * whole.extent()),
        };
        let some = tessellate_for_query(&[patch], Some(&corner), tolerance, MAX_SPLITS);
        assert_eq!(some.patches_kept, 1);
        assert!(
            some.pieces >= 1 && some.pieces < 4usize.pow(MAX_SPLITS),
            "{}",
            some.pieces
        );
        assert!(
            !some.triangles.is_empty() && some.triangles.len() < all.triangles.len() / 4,
            "{} of {}",
            some.triangles.len(),
            all.triangles.len()
        );
        assert!(some.face_of.iter().all(|&f| f == 0));
    }

    /// Recut for the unit: every piece needs at most 16 samples a side and
    /// still meets the tolerance by its bound; a piece that needed more is
    /// replaced by quarters of it.
    #[test]
    fn pieces_within_the_units_samples() {
        let patch = wavy_patch();
        let tolerance = 1e-5 * net_box(&patch).extent();
        let whole = net_box(&patch).expanded(1.0);
        let (pieces, kept) = query_pieces(&[patch], Some(&whole), tolerance, MAX_SPLITS);
        assert_eq!((pieces.len(), kept), (1, 1));
        assert!(pieces[0].samples > 16, "{}", pieces[0].samples);
        let recut = pieces_within(&pieces, 16, tolerance);
        assert!(recut.len() >= 4 && recut.iter().all(|p| p.samples <= 16 && p.patch == 0));
        assert!(recut
            .iter()
            .all(|p| deviation_bound(&p.piece, p.samples) <= tolerance));
    }
}
