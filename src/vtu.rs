//! A solution for ParaView: the body and Γ_C as VTK XML unstructured grids (`.vtu`), written
//! with the vtkio crate.
//!
//! Two files, because the body and Γ_C carry different arrays and a VTK reader expects every
//! piece of one file to carry the same ones:
//! - `FILE.vtu`, the body: the mesh's nodes and elements (Q1 as VTK_QUAD, Q2 as
//!   VTK_BIQUADRATIC_QUAD = 28, P1 as two VTK_TRIANGLEs per cell); point data `u` (the
//!   displacement, a 3-vector with z = 0, for ParaView's Warp By Vector) and the recovered
//!   stresses of [`crate::stress`] (`sigma_xx`, `sigma_yy`, `sigma_xy`, `sigma_zz`,
//!   `von_mises`, `tau1`); cell data: the same stresses averaged over each element.
//! - `FILE.contact.vtu`, Γ_C as a line set: one cell per edge (VTK_LINE, or
//!   VTK_QUADRATIC_EDGE = 21 for Q2) with its own copy of the edge's nodes, so that a pressure
//!   that jumps between edges (gauss1, gauss2) is drawn as it is; point data `p` (the raw
//!   pressure (12) as its function in Q_h, evaluated on the edge), `pbar` (the smoothed p̄ of
//!   (16)–(17), linear between vertices) and `u`.
//!
//! Coordinates are the undeformed ones of the modelled body: a half model is exported as the
//! half (ParaView's Reflect filter about x = 0 gives the whole). Files are written atomically
//! (see [`crate::plot::write_file`]); an existing file is replaced only when asked, and only a
//! regular file: see [`check_target`].

use std::io;
use std::path::{Path, PathBuf};

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

use crate::contact::ContactPoints;
use crate::contact::solution::Solution;
use crate::discretization::Discretization;
use crate::mesh::{Diagonal, Element, Mesh};
use crate::plot::write_file;
use crate::stress::{Stress, StressField};

/// Why a VTU export failed.
#[derive(Debug, thiserror::Error)]
pub enum VtuError {
    /// The file name does not end in `.vtu`.
    #[error("{0}: the file name must end in .vtu (ParaView chooses its reader by it)")]
    Extension(PathBuf),
    /// The file exists and replacing it was not asked for (`--force`).
    #[error("{0}: exists; not overwritten (--force replaces it)")]
    Exists(PathBuf),
    /// The path exists and is not a regular file.
    #[error("{0}: not a regular file (a directory, link, FIFO or device); not replaced")]
    NotRegular(PathBuf),
    /// Reading or writing the path failed.
    #[error("{0}: {1}")]
    Io(PathBuf, io::Error),
    /// vtkio could not write the VTK XML.
    #[error("VTK XML: {0}")]
    Vtk(#[source] vtkio::Error),
}

/// The Γ_C file that goes with the body's `path`: `FILE.vtu` → `FILE.contact.vtu`.
pub fn contact_path(path: &Path) -> PathBuf {
    path.with_extension("contact.vtu")
}

/// Whether `path` may be written: a name ending in `.vtu`, and no file there unless
/// `overwrite`; with `overwrite` only a regular file is replaced (never a link, a FIFO, a
/// device or a directory). Checked before any work is done, for the body and Γ_C files.
///
/// # Errors
///
/// A name not ending in `.vtu`, a file there without `overwrite`, or one that is not a regular
/// file.
pub fn check_targets(path: &Path, overwrite: bool) -> Result<[PathBuf; 2], VtuError> {
    if path.extension().is_none_or(|e| e != "vtu") {
        return Err(VtuError::Extension(path.to_path_buf()));
    }
    let paths = [path.to_path_buf(), contact_path(path)];
    for p in &paths {
        check_target(p, overwrite)?;
    }
    Ok(paths)
}

/// Whether one file may be written at `path` (see [`check_targets`]).
///
/// # Errors
///
/// As [`check_targets`]'s for one file.
pub fn check_target(path: &Path, overwrite: bool) -> Result<(), VtuError> {
    crate::plot::check_target(path, overwrite).map_err(|e| match e.kind() {
        io::ErrorKind::AlreadyExists => VtuError::Exists(path.to_path_buf()),
        io::ErrorKind::InvalidInput => VtuError::NotRegular(path.to_path_buf()),
        _ => VtuError::Io(path.to_path_buf(), e),
    })
}

/// Write the body to `path` and Γ_C next to it ([`contact_path`]); returns both paths.
///
/// # Errors
///
/// As [`check_targets`]'s, or a file cannot be written ([`VtuError::Io`]).
pub fn write(
    path: &Path,
    disc: &Discretization,
    sol: &Solution,
    field: &StressField,
    overwrite: bool,
) -> Result<[PathBuf; 2], VtuError> {
    let paths = check_targets(path, overwrite)?;
    let u = sol.displacement(disc);
    let files = [
        xml(body(&disc.mesh, &u, field))?,
        xml(contact(&disc.mesh, sol, &u))?,
    ];
    for (p, bytes) in paths.iter().zip(&files) {
        write_file(p, bytes, overwrite).map_err(|e| match e.kind() {
            io::ErrorKind::AlreadyExists => VtuError::Exists(p.clone()),
            _ => VtuError::Io(p.clone(), e),
        })?;
    }
    Ok(paths)
}

/// The VTK XML text of `vtk`.
///
/// # Errors
///
/// The XML writer failed ([`VtuError`]).
pub fn xml(vtk: Vtk) -> Result<Vec<u8>, VtuError> {
    let mut out = Vec::new();
    vtk.write_xml(&mut out).map_err(VtuError::Vtk)?;
    Ok(out)
}

fn unstructured(title: &str, piece: UnstructuredGridPiece) -> Vtk {
    Vtk {
        version: Version::new_xml(1, 0),
        title: title.to_string(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(piece),
    }
}

/// A piece of points (x, y, z flattened), cells (connectivity, offsets, types) and the
/// point and cell arrays.
fn piece(
    points: Vec<f64>,
    (connectivity, offsets, types): (Vec<u64>, Vec<u64>, Vec<CellType>),
    point: Vec<Attribute>,
    cell: Vec<Attribute>,
) -> UnstructuredGridPiece {
    UnstructuredGridPiece {
        points: points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types,
        },
        data: Attributes { point, cell },
    }
}

/// The arrays of the stress quantities for a list of stresses.
fn stress_arrays(stresses: &[Stress]) -> Vec<Attribute> {
    type Get = fn(&Stress) -> f64;
    let columns: [(&str, Get); 6] = [
        ("sigma_xx", |s| s.xx),
        ("sigma_yy", |s| s.yy),
        ("sigma_xy", |s| s.xy),
        ("sigma_zz", |s| s.zz),
        ("von_mises", Stress::von_mises),
        ("tau1", Stress::principal_shear),
    ];
    columns
        .iter()
        .map(|(name, get)| {
            Attribute::generic(*name, 1).with_data(stresses.iter().map(get).collect::<Vec<f64>>())
        })
        .collect()
}

/// The displacement at the given nodes as 3-vectors (z = 0).
fn displacement_array(u: &[f64], nodes: impl Iterator<Item = usize>) -> Attribute {
    Attribute::vectors("u").with_data(
        nodes
            .flat_map(|n| [u[2 * n], u[2 * n + 1], 0.0])
            .collect::<Vec<f64>>(),
    )
}

/// The local corner indices (tensor order: 0 = lower left, 1 = lower right, 2 = upper left,
/// 3 = upper right) of a P1 cell's two triangles, counter-clockwise, in the order of
/// [`crate::fem::basis::cell_points`] (and so of [`StressField::elements`]).
fn triangles(diagonal: Diagonal) -> [[usize; 3]; 2] {
    match diagonal {
        Diagonal::Rising => [[0, 1, 3], [0, 3, 2]],
        Diagonal::Falling => [[0, 1, 2], [1, 3, 2]],
    }
}

/// The body: nodes, elements (in [`StressField::elements`]' order), `u`, and the stresses.
pub fn body(mesh: &Mesh, u: &[f64], field: &StressField) -> Vtk {
    let points: Vec<f64> = (0..mesh.n_nodes())
        .flat_map(|n| {
            let (x, y) = mesh.node_coords(n);
            [x, y, 0.0]
        })
        .collect();
    let (mut connectivity, mut offsets, mut types) = (Vec::new(), Vec::new(), Vec::new());
    let mut push = |nodes: &[usize], t: CellType| {
        connectivity.extend(nodes.iter().map(|&n| n as u64));
        offsets.push(connectivity.len() as u64);
        types.push(t);
    };
    for cj in 0..mesh.ny() {
        for ci in 0..mesh.nx() {
            let local = mesh.cell_nodes(ci, cj);
            match mesh.element {
                Element::Q1 => push(&[local[0], local[1], local[3], local[2]], CellType::Quad),
                // VTK's order: corners counter-clockwise, then the mid-edge nodes of the
                // bottom, right, top and left edges, then the centre.
                Element::Q2 => push(
                    &[0, 2, 8, 6, 1, 5, 7, 3, 4].map(|k| local[k]),
                    CellType::BiquadraticQuad,
                ),
                Element::P1 => {
                    for tri in triangles(mesh.diagonal(ci)) {
                        push(&tri.map(|k| local[k]), CellType::Triangle);
                    }
                }
            }
        }
    }
    let mut point = vec![displacement_array(u, 0..mesh.n_nodes())];
    point.extend(stress_arrays(&field.nodal));
    let cells = (connectivity, offsets, types);
    let piece = piece(points, cells, point, stress_arrays(&field.element_averages()));
    unstructured("riplab body", piece)
}

/// Γ_C of `sol` (with `u` its displacement on every dof): one line cell per edge with its own
/// nodes, `p`, `pbar` and `u` there.
pub fn contact(mesh: &Mesh, sol: &Solution, u: &[f64]) -> Vtk {
    let cp: &ContactPoints = &sol.points;
    let top_nodes = mesh.top_nodes();
    let top = mesh.ys[mesh.ys.len() - 1];
    let order = mesh.element.order();
    let (mut points, mut nodes, mut p, mut pbar) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut connectivity, mut offsets, mut types) = (Vec::new(), Vec::new(), Vec::new());
    for e in 0..cp.n_edges() {
        // Ends first, then the middle (VTK_QUADRATIC_EDGE's order).
        let local: &[(usize, f64)] = if order == 2 {
            &[(0, 0.0), (2, 1.0), (1, 0.5)]
        } else {
            &[(0, 0.0), (1, 1.0)]
        };
        for &(k, s) in local {
            let node = top_nodes[order * e + k];
            connectivity.push((points.len() / 3) as u64);
            points.extend([mesh.node_coords(node).0, top, 0.0]);
            nodes.push(node);
            let raw: f64 = cp.edge_points[e]
                .iter()
                .zip(cp.edge_basis(e, s))
                .map(|(&q, phi)| sol.p[q] * phi)
                .sum();
            p.push(raw);
            pbar.push((1.0 - s) * sol.pbar[e] + s * sol.pbar[e + 1]);
        }
        offsets.push(connectivity.len() as u64);
        types.push(if order == 2 {
            CellType::QuadraticEdge
        } else {
            CellType::Line
        });
    }
    let point = vec![
        Attribute::generic("p", 1).with_data(p),
        Attribute::generic("pbar", 1).with_data(pbar),
        displacement_array(u, nodes.into_iter()),
    ];
    let piece = piece(points, (connectivity, offsets, types), point, Vec::new());
    unstructured("riplab contact side", piece)
}
