//! The Bezier level-of-detail system's hardware (`bezier_lod_gpu.txt`):
//! the patch tessellation unit, its triangles assembled, and the
//! cone-of-normals unit.
pub mod cone_unit;
pub mod patch_tessellator;
pub mod patch_triangles;
