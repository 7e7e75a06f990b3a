//! The VTU export of `riplab::vtu`: read back with the same crate (vtkio), the
//! counts, cell types, array names and values checked against the solution they came from,
//! and the rules for existing files.

use std::path::{Path, PathBuf};

use crate::common::riplab;
use riplab::contact::solution::Solution;
use riplab::discretization::Discretization;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_scenario;
use riplab::vtu::{VtuError, check_target, check_targets, contact_path, write};
use vtkio::model::{Attribute, CellType, DataSet, Piece, UnstructuredGridPiece, Vtk};

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("riplab-vtu-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn solve(element: Element, rule: &str, level: u32) -> (Scenario, Discretization, Solution) {
    let mut s = Scenario::paper();
    s.element = element;
    s.rule = riplab::Rule::ALL.into_iter().find(|r| r.name() == rule).unwrap();
    s.level = level;
    let (d, sol) = solve_scenario(&s).unwrap();
    (s, d, sol)
}

/// The one inline piece of an unstructured grid read from `path` by vtkio.
fn read(path: &Path) -> UnstructuredGridPiece {
    let vtk = Vtk::import(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid")
    };
    assert_eq!(pieces.len(), 1);
    match pieces.into_iter().next().unwrap() {
        Piece::Inline(p) => *p,
        _ => panic!("piece not inline"),
    }
}

/// The named array of `attrs` as f64 values with its number of components.
fn array(attrs: &[Attribute], name: &str) -> (Vec<f64>, usize) {
    let found = attrs.iter().find(|a| a.name() == name);
    match found {
        Some(Attribute::DataArray(a)) => (a.data.cast_into::<f64>().unwrap(), a.elem.num_comp() as usize),
        _ => panic!(
            "no array {name} among {:?}",
            attrs.iter().map(|a| a.name()).collect::<Vec<_>>()
        ),
    }
}

fn names(attrs: &[Attribute]) -> Vec<&str> {
    attrs.iter().map(|a| a.name()).collect()
}

const STRESSES: [&str; 6] = [
    "sigma_xx",
    "sigma_yy",
    "sigma_xy",
    "sigma_zz",
    "von_mises",
    "tau1",
];

#[test]
fn body_and_contact_side_read_back_with_their_counts_names_and_values() {
    let dir = scratch("read");
    for (element, rule, cell, edge, nodes_per_cell) in [
        (Element::Q1, "gauss1", CellType::Quad, CellType::Line, 4),
        (
            Element::Q2,
            "simpson",
            CellType::BiquadraticQuad,
            CellType::QuadraticEdge,
            9,
        ),
        (Element::P1, "trapezoid", CellType::Triangle, CellType::Line, 3),
    ] {
        let (_, disc, sol) = solve(element, rule, 1);
        let field = sol.stress_field(&disc).unwrap();
        let path = dir.join(format!("{}.vtu", element.name()));
        let [body_path, contact] = write(&path, &disc, &sol, &field, false).unwrap();
        assert_eq!(
            (body_path.as_path(), contact.clone()),
            (
                path.as_path(),
                dir.join(format!("{}.contact.vtu", element.name()))
            )
        );

        // The body.
        let mesh = disc.mesh();
        let body = read(&path);
        assert_eq!(body.num_points(), mesh.n_nodes(), "{element:?}");
        assert_eq!(body.cells.types.len(), mesh.n_elements());
        assert!(body.cells.types.iter().all(|&t| t == cell));
        let (conn, offsets) = body.cells.cell_verts.clone().into_xml();
        assert_eq!(conn.len(), nodes_per_cell * mesh.n_elements());
        assert_eq!(offsets.last().copied(), Some(conn.len() as u64));
        let mut point_names = vec!["u"];
        point_names.extend(STRESSES);
        assert_eq!(names(&body.data.point), point_names);
        assert_eq!(names(&body.data.cell), STRESSES.to_vec());
        let points = body.points.cast_into::<f64>().unwrap();
        // The top-right node: its position, u_y (against the Γ_C trace of the solve) and σ̂.
        let n = mesh.n_nodes() - 1;
        assert_eq!(&points[3 * n..3 * n + 3], &[8.0, 4.0, 0.0]);
        let (u, comps) = array(&body.data.point, "u");
        assert_eq!(comps, 3);
        let uy_right = *sol.vertex_uy.last().unwrap();
        assert!((u[3 * n + 1] - uy_right).abs() < 1e-12 * uy_right.abs().max(1e-9));
        // Under the cylinder's axis the top is pushed down by about the depth.
        let top_left = mesh.top_nodes()[0];
        assert!((u[3 * top_left + 1] - sol.vertex_uy[0]).abs() < 1e-12);
        assert!(u[3 * top_left + 1] < -0.5);
        for (k, name) in STRESSES.iter().enumerate() {
            let (v, c) = array(&body.data.point, name);
            assert_eq!((v.len(), c), (mesh.n_nodes(), 1));
            let s = field.nodal[top_left];
            let expect = [s.xx, s.yy, s.xy, s.zz, s.von_mises(), s.principal_shear()][k];
            assert_eq!(v[top_left], expect, "{name}");
            let (cells, _) = array(&body.data.cell, name);
            assert_eq!(cells.len(), mesh.n_elements());
        }
        // Each cell is the element of the same index in the stress field: the mean of its
        // corners is the weighted mean of that element's quadrature points (its centroid).
        let corners = if element == Element::Q2 { 4 } else { nodes_per_cell };
        for (e, pts) in field.elements.iter().enumerate() {
            let cell_nodes = &conn[nodes_per_cell * e..nodes_per_cell * e + corners];
            let cx = cell_nodes.iter().map(|&k| points[3 * k as usize]).sum::<f64>() / corners as f64;
            let cy = cell_nodes
                .iter()
                .map(|&k| points[3 * k as usize + 1])
                .sum::<f64>()
                / corners as f64;
            let w: f64 = pts.iter().map(|p| p.weight).sum();
            let qx = pts.iter().map(|p| p.weight * p.x).sum::<f64>() / w;
            let qy = pts.iter().map(|p| p.weight * p.y).sum::<f64>() / w;
            assert!(
                (cx - qx).abs() < 1e-12 && (cy - qy).abs() < 1e-12,
                "{element:?} cell {e}"
            );
        }
        let (syy, _) = array(&body.data.cell, "sigma_yy");
        let avg = field.element_averages();
        assert_eq!(syy[7], avg[7].yy);

        // Γ_C: one cell per edge with its own nodes.
        let gc = read(&contact);
        let edges = sol.points.n_edges();
        let per_edge = element.order() + 1;
        assert_eq!(gc.cells.types, vec![edge; edges]);
        assert_eq!(gc.num_points(), per_edge * edges);
        assert_eq!(names(&gc.data.point), vec!["p", "pbar", "u"]);
        let (p, _) = array(&gc.data.point, "p");
        let (pbar, _) = array(&gc.data.point, "pbar");
        let gx = gc.points.cast_into::<f64>().unwrap();
        for e in 0..edges {
            let (a, b) = (per_edge * e, per_edge * e + 1);
            assert_eq!(
                (gx[3 * a], gx[3 * b]),
                (sol.points.vertex_x[e], sol.points.vertex_x[e + 1])
            );
            assert_eq!((pbar[a], pbar[b]), (sol.pbar[e], sol.pbar[e + 1]));
            match rule {
                // One point per edge: p is the edge's constant at both ends.
                "gauss1" => assert_eq!((p[a], p[b]), (sol.p[e], sol.p[e])),
                // Points at the vertices (and the middle): p there is the point's value.
                _ => {
                    assert!((p[a] - sol.p[sol.points.edge_points[e][0]]).abs() < 1e-9 * (1.0 + p[a].abs()));
                    let last = *sol.points.edge_points[e].last().unwrap();
                    assert!((p[b] - sol.p[last]).abs() < 1e-9 * (1.0 + p[b].abs()));
                }
            }
        }
        if element == Element::Q2 {
            // The middle node of edge e is the Simpson point in the middle.
            let mid = sol.points.edge_points[3][1];
            assert!((p[3 * 3 + 2] - sol.p[mid]).abs() < 1e-9 * (1.0 + sol.p[mid]));
            assert!((gx[3 * (3 * 3 + 2)] - sol.points.points[mid].x).abs() < 1e-15);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn existing_files_are_kept_unless_forced_and_only_regular_files_are_replaced() {
    let dir = scratch("keep");
    let (_, disc, sol) = solve(Element::Q1, "gauss1", 0);
    let field = sol.stress_field(&disc).unwrap();
    let path = dir.join("out.vtu");
    // The name must end in .vtu.
    assert!(matches!(
        check_targets(&dir.join("out.txt"), true),
        Err(VtuError::Extension(_))
    ));
    // Either existing file refuses the write, and nothing is written.
    std::fs::write(contact_path(&path), "mine").unwrap();
    let err = write(&path, &disc, &sol, &field, false).unwrap_err();
    assert!(matches!(err, VtuError::Exists(_)), "{err}");
    assert!(err.to_string().contains("--force"));
    assert!(!path.exists());
    write(&path, &disc, &sol, &field, true).unwrap();
    assert!(
        std::fs::read_to_string(contact_path(&path))
            .unwrap()
            .contains("<VTKFile")
    );
    // Not a regular file: refused even when forced.
    let link = dir.join("link.vtu");
    std::os::unix::fs::symlink(&path, &link).unwrap();
    assert!(matches!(check_targets(&link, true), Err(VtuError::NotRegular(_))));
    std::fs::create_dir(dir.join("d.vtu")).unwrap();
    assert!(matches!(
        check_targets(&dir.join("d.vtu"), true),
        Err(VtuError::NotRegular(_))
    ));
    let fifo = dir.join("f.vtu");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        assert!(matches!(check_targets(&fifo, true), Err(VtuError::NotRegular(_))));
    }
    assert!(matches!(
        check_target(Path::new("/dev/null"), true),
        Err(VtuError::NotRegular(_))
    ));
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cli_writes_vtu_and_refuses_to_overwrite_before_solving() {
    let dir = scratch("cli");
    let path = dir.join("m1.vtu");
    let p = path.to_str().unwrap();
    let (code, out, err) = riplab(&["solve", "--level", "1", "--vtu", p, "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.trim_start().starts_with('{'),
        "stdout stays the JSON object: {out}"
    );
    assert!(err.contains("m1.contact.vtu"), "{err}");
    assert_eq!(read(&path).cells.types.len(), 128);
    // Again: refused before the solve (nothing printed), exit 2, the file kept.
    let before = std::fs::read(&path).unwrap();
    let (code, out, err) = riplab(&["solve", "--level", "1", "--vtu", p]);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains("--vtu") && err.contains("exists") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(&path).unwrap(), before);
    // --force replaces it (a different level: a different file).
    let (code, _, err) = riplab(&["solve", "--level", "0", "--vtu", p, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(read(&path).cells.types.len(), 32);
    // --force applies to --plot too, and means nothing alone.
    let svg = dir.join("m1.svg");
    std::fs::write(&svg, "mine").unwrap();
    let s = svg.to_str().unwrap();
    let (code, _, err) = riplab(&["solve", "--plot", s]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(std::fs::read_to_string(&svg).unwrap(), "mine");
    assert_eq!(riplab(&["solve", "--plot", s, "--force"]).0, 0);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    assert_eq!(riplab(&["solve", "--force"]).0, 2);
    // A sweep has several solutions: refused.
    let (code, _, err) = riplab(&[
        "solve",
        "--epsilon",
        "1e-4,1e-6",
        "--vtu",
        dir.join("s.vtu").to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
