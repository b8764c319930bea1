//! Evaluation at the limit (OpenSubdiv's `Far::PrimvarRefiner::Limit`): the limit masks of
//! [`crate::rules::limit`] applied to one level's positions, and to its vertex-varying rows,
//! through the same sinks that refine them ([`PointSum`], [`RowSum`]).

use crate::mesh::HalfEdgeMesh;
use crate::primvar::{PointSum, RowSum, Rows};
use crate::rules::limit::{LimitRules, Neighbourhood};
use crate::rules::Stencil;
use glam::Vec3;

/// The limit positions, tangents and normals of one level's vertices, three floats each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LimitFrame {
    pub positions: Vec<f32>,
    /// OpenSubdiv's `tan1` and `tan2` (see [`crate::rules::limit`]).
    pub tangents: [Vec<f32>; 2],
    /// `tangents[0] × tangents[1]`, normalised; zero where that cross product is zero or not
    /// finite (an isolated vertex, or tangents along one line).
    pub normals: Vec<f32>,
}

/// The unit vector along `first × second`, or zero when there is none.
pub fn normal(first: [f32; 3], second: [f32; 3]) -> [f32; 3] {
    let n = Vec3::from_array(first).cross(Vec3::from_array(second));
    let length = n.length();
    if length > 0.0 && length.is_finite() {
        (n / length).to_array()
    } else {
        [0.0; 3]
    }
}

/// The limit frame of every vertex of `mesh` (whose positions are the level's), and the limit
/// of `rows` (the level's vertex-varying rows, possibly empty) under the position masks.
pub fn evaluate(mesh: &HalfEdgeMesh, rules: &LimitRules, rows: &Rows) -> (LimitFrame, Rows) {
    let n = mesh.num_vertices();
    let points = &mesh.positions;
    let mut frame = LimitFrame {
        positions: Vec::with_capacity(3 * n),
        tangents: [Vec::with_capacity(3 * n), Vec::with_capacity(3 * n)],
        normals: Vec::with_capacity(3 * n),
    };
    let mut out_rows = Rows { width: rows.width, values: Vec::with_capacity(rows.values.len()) };
    let mut row_sum = RowSum::new(&rows.values, rows.width, &mesh.he_from, &[]);
    let mut hood = Neighbourhood::default();
    for v in mesh.vertex_indices() {
        rules.gather(mesh, v, &mut hood);
        let mut sum = PointSum::new(points, &mesh.he_from, &[]);
        frame.positions.extend(sum.eval(|w| rules.position(&hood, w)));
        let mut second = PointSum::new(points, &mesh.he_from, &[]);
        let first = sum.eval(|w| {
            rules.tangents(&hood, w, &mut second);
        });
        let second = second.sum.to_array();
        frame.tangents[0].extend(first);
        frame.tangents[1].extend(second);
        frame.normals.extend(normal(first, second));
        if rows.width > 0 {
            row_sum.eval_into(&mut out_rows.values, |w| rules.position(&hood, w));
        }
    }
    (frame, out_rows)
}

/// The weights of vertex `vertex`'s limit position and tangents, recorded (for tests and for
/// stencil tables).
pub fn stencils(mesh: &HalfEdgeMesh, rules: &LimitRules, vertex: u32) -> [Stencil; 3] {
    let mut hood = Neighbourhood::default();
    let mut out: [Stencil; 3] = Default::default();
    if vertex as usize >= mesh.num_vertices() {
        return out;
    }
    rules.gather(mesh, vertex, &mut hood);
    let [position, first, second] = &mut out;
    rules.position(&hood, position);
    rules.tangents(&hood, first, second);
    out
}
