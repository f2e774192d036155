//! Voxel models in files other tools open: `.binvox` (Patrick Min's
//! voxelizer format, read by many voxel tools) and the model's boundary as
//! a triangle mesh (OBJ), both in the placement's units.

use super::tree::Placement;
use super::voxels::VoxelGrid;
use std::collections::HashMap;
use std::io::{self, Write};

/// Writes `.binvox`: a text header (`dim`, `translate` = the grid's
/// origin, `scale` = the grid's side in the placement's units), then the
/// voxels as run-length pairs (value, count 1 to 255), `y` running fastest,
/// then `z`, then `x`, as the format orders them.
pub fn write_binvox(
    grid: &VoxelGrid,
    placement: &Placement,
    out: &mut dyn Write,
) -> io::Result<()> {
    let n = grid.side();
    let o = placement.origin;
    writeln!(out, "#binvox 1")?;
    writeln!(out, "dim {n} {n} {n}")?;
    writeln!(out, "translate {} {} {}", o[0], o[1], o[2])?;
    writeln!(out, "scale {}", placement.voxel_size * n as f64)?;
    writeln!(out, "data")?;
    let mut run: Option<(bool, u8)> = None;
    let mut bytes = Vec::with_capacity(4096);
    for x in 0..n {
        for z in 0..n {
            for y in 0..n {
                let v = grid.get([x, y, z]);
                run = match run {
                    Some((value, count)) if value == v && count < 255 => Some((value, count + 1)),
                    Some((value, count)) => {
                        bytes.extend_from_slice(&[value as u8, count]);
                        Some((v, 1))
                    }
                    None => Some((v, 1)),
                };
            }
        }
        out.write_all(&bytes)?;
        bytes.clear();
    }
    if let Some((value, count)) = run {
        out.write_all(&[value as u8, count])?;
    }
    Ok(())
}

/// The boundary of the model: one quad (two triangles) per face between an
/// occupied voxel and an empty one or the grid's outside, outward facing,
/// vertices shared.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BoundaryMesh {
    pub vertices: Vec<[f64; 3]>,
    /// Vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

pub fn boundary_mesh(grid: &VoxelGrid, placement: &Placement) -> BoundaryMesh {
    let n = grid.side() as i64;
    let occupied =
        |p: [i64; 3]| p.iter().all(|&c| (0..n).contains(&c)) && grid.get(p.map(|c| c as usize));
    let mut mesh = BoundaryMesh::default();
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut vertex = |mesh: &mut BoundaryMesh, p: [i64; 3]| -> u32 {
        *index.entry(p).or_insert_with(|| {
            mesh.vertices
                .push([0, 1, 2].map(|k| placement.origin[k] + p[k] as f64 * placement.voxel_size));
            (mesh.vertices.len() - 1) as u32
        })
    };
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let p = [x, y, z];
                if !occupied(p) {
                    continue;
                }
                for axis in 0..3 {
                    for upper in [false, true] {
                        let mut q = p;
                        q[axis] += if upper { 1 } else { -1 };
                        if occupied(q) {
                            continue;
                        }
                        // The face's corners in the plane of the other two axes.
                        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                        let corner = |da: i64, db: i64| {
                            let mut c = p;
                            c[axis] += i64::from(upper);
                            c[a] += da;
                            c[b] += db;
                            c
                        };
                        let mut quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                        // (a, b, axis) is right-handed: counter-clockwise in
                        // (a, b) faces +axis; the lower face turns round.
                        if !upper {
                            quad.reverse();
                        }
                        let ids = quad.map(|c| vertex(&mut mesh, c));
                        mesh.triangles.push([ids[0], ids[1], ids[2]]);
                        mesh.triangles.push([ids[0], ids[2], ids[3]]);
                    }
                }
            }
        }
    }
    mesh
}

impl BoundaryMesh {
    pub fn write_obj(&self, out: &mut dyn Write) -> io::Result<()> {
        writeln!(out, "# boundary of a voxel model, written by tritri")?;
        for v in &self.vertices {
            writeln!(out, "v {} {} {}", v[0], v[1], v[2])?;
        }
        for t in &self.triangles {
            writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Run lengths decode back to the voxels in the format's order.
    #[test]
    fn binvox_runs_decode_to_the_voxels() {
        let mut g = VoxelGrid::empty(3);
        g.fill_cube([0, 4, 2], 1);
        g.set([7, 7, 7]);
        let mut bytes = Vec::new();
        write_binvox(&g, &Placement::default(), &mut bytes).unwrap();
        let data_at = bytes.windows(5).position(|w| w == b"data\n").unwrap() + 5;
        let mut values = Vec::new();
        for pair in bytes[data_at..].chunks(2) {
            values.extend(std::iter::repeat(pair[0] == 1).take(pair[1] as usize));
        }
        assert_eq!(values.len(), 512);
        for x in 0..8 {
            for z in 0..8 {
                for y in 0..8 {
                    assert_eq!(values[x * 64 + z * 8 + y], g.get([x, y, z]));
                }
            }
        }
    }

    /// A 2 x 2 x 2 block has 24 unit faces; its boundary is closed (every
    /// edge used twice) and encloses volume 8.
    #[test]
    fn boundary_of_a_block_is_closed_and_outward() {
        let mut g = VoxelGrid::empty(2);
        g.fill_cube([1, 1, 1], 1);
        let m = boundary_mesh(&g, &Placement::default());
        assert_eq!(m.triangles.len(), 48);
        let mut edges = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *edges
                    .entry((t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])))
                    .or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&c| c == 2));
        // Divergence theorem: volume = sum over triangles of det / 6.
        let volume: f64 = m
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.vertices[i as usize]);
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum();
        assert!((volume - 8.0).abs() < 1e-9, "{volume}");
    }
}
