//! Voxel and octree models in and out of files, chosen by extension:
//! `.oct` (tritri's octree format, `docs/octree-format.md`; read and
//! written), and for writing only `.binvox`, MagicaVoxel `.vox` (through
//! the `dot_vox` crate, up to 256^3), `.obj` (the model's boundary faces)
//! and `.png` (a shaded render).

use crate::output_file::OutputFile;
use anyhow::Context;
use std::path::Path;
use tritri_geom::octree::export::{boundary_mesh, write_binvox};
use tritri_geom::octree::render::{render, Image, View};
use tritri_geom::octree::tree::{Octree, OctreeFile, Placement};
use tritri_geom::octree::voxels::VoxelGrid;

/// What an output file holds, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    Octree,
    Binvox,
    MagicaVoxel,
    BoundaryObj,
    Png,
}

/// Largest side MagicaVoxel's format stores in one model.
const VOX_MAX_SIDE: usize = 256;

impl ModelFormat {
    pub fn of(path: &str) -> anyhow::Result<ModelFormat> {
        let ext = Path::new(path)
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        Ok(match ext.as_deref() {
            Some("oct") => ModelFormat::Octree,
            Some("binvox") => ModelFormat::Binvox,
            Some("vox") => ModelFormat::MagicaVoxel,
            Some("obj") => ModelFormat::BoundaryObj,
            Some("png") => ModelFormat::Png,
            _ => anyhow::bail!(
                "{path}: unknown model format (expected .oct, .binvox, .vox, .obj or .png)"
            ),
        })
    }
}

/// An output checked before the work: its format known, its file writable.
pub struct ModelOutput {
    pub path: String,
    pub format: ModelFormat,
    file: OutputFile,
}

impl ModelOutput {
    /// Checks the extension, and for `.vox` the grid's side, before any
    /// work is done; reserves the file.
    pub fn reserve(path: &str, side: usize, inputs: &[&str]) -> anyhow::Result<ModelOutput> {
        let format = ModelFormat::of(path)?;
        if format == ModelFormat::MagicaVoxel && side > VOX_MAX_SIDE {
            anyhow::bail!("{path}: MagicaVoxel .vox models hold at most {VOX_MAX_SIDE}^3 voxels, this grid is {side}^3 (write .oct or .binvox)");
        }
        if path == "-" {
            anyhow::bail!("models are written to files, not standard output (`-`)");
        }
        Ok(ModelOutput {
            path: path.to_string(),
            format,
            file: OutputFile::reserve_apart(path, inputs)?,
        })
    }

    /// Writes the model; returns the file's size in bytes.
    pub fn write(
        self,
        tree: &Octree,
        grid: &VoxelGrid,
        placement: &Placement,
        view: &View,
    ) -> anyhow::Result<u64> {
        let ModelOutput { path, format, file } = self;
        match format {
            ModelFormat::Octree => {
                let bytes = OctreeFile {
                    tree: tree.clone(),
                    placement: *placement,
                }
                .to_bytes();
                file.commit(|w| w.write_all(&bytes))?;
            }
            ModelFormat::Binvox => file.commit(|w| write_binvox(grid, placement, w))?,
            ModelFormat::MagicaVoxel => {
                let data = magica_voxel(grid);
                file.commit(|mut w| data.write_vox(&mut w))?;
            }
            ModelFormat::BoundaryObj => {
                let mesh = boundary_mesh(grid, placement);
                file.commit(|w| mesh.write_obj(w))?;
            }
            ModelFormat::Png => {
                let image = render(grid, view);
                file.commit(|w| write_png(&image, w))?;
            }
        }
        Ok(std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0))
    }
}

/// Reads a `.oct` file.
pub fn read_octree(path: &str) -> anyhow::Result<OctreeFile> {
    // Only `.oct` is read: the error must not list the formats that are
    // only written (ModelFormat::of's list).
    if !matches!(ModelFormat::of(path), Ok(ModelFormat::Octree)) {
        anyhow::bail!("{path}: models are read from .oct files only (tritri octree format; `tritri voxelize` makes one from a mesh)");
    }
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {path}"))?;
    OctreeFile::from_bytes(&bytes).with_context(|| format!("{path}"))
}

pub fn write_png(image: &Image, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    let mut encoder = png::Encoder::new(out, image.width, image.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    let data: Vec<u8> = image.pixels.iter().flatten().copied().collect();
    writer
        .write_image_data(&data)
        .map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

/// One model of the grid's side, every voxel in palette colour 1.
fn magica_voxel(grid: &VoxelGrid) -> dot_vox::DotVoxData {
    let n = grid.side();
    let mut voxels = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                if grid.get([x, y, z]) {
                    voxels.push(dot_vox::Voxel {
                        x: x as u8,
                        y: y as u8,
                        z: z as u8,
                        i: 0,
                    });
                }
            }
        }
    }
    let size = dot_vox::Size {
        x: n as u32,
        y: n as u32,
        z: n as u32,
    };
    dot_vox::DotVoxData {
        version: 150,
        index_map: Vec::new(),
        models: vec![dot_vox::Model { size, voxels }],
        palette: dot_vox::DEFAULT_PALETTE.to_vec(),
        materials: Vec::new(),
        scenes: Vec::new(),
        layers: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What dot_vox reads back is the model's voxels.
    #[test]
    fn vox_files_read_back() {
        let mut g = VoxelGrid::empty(3);
        g.fill_cube([0, 4, 2], 1);
        g.set([7, 6, 5]);
        let mut bytes = Vec::new();
        magica_voxel(&g).write_vox(&mut bytes).unwrap();
        let read = dot_vox::load_bytes(&bytes).unwrap();
        let mut back = VoxelGrid::empty(3);
        for v in &read.models[0].voxels {
            back.set([v.x as usize, v.y as usize, v.z as usize]);
        }
        assert_eq!(back, g);
    }
}
