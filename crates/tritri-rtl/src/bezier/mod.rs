//! The Bezier level-of-detail system's hardware (`bezier_lod_gpu.txt`):
//! the patch tessellation unit.
pub mod patch_tessellator;
