//! Face-varying channels through a Doo-Sabin level (the dual split, [`crate::refine::dqq`]).
//!
//! # Values
//!
//! Every child vertex belongs to one parent face: the corner point of corner `h` to `h`'s cell,
//! a Chaikin boundary point to the cell of its boundary half-edge. Its **own value** is the
//! rule's weights (the same as the positions': [`CornerRules::corner_point`] and
//! [`CornerRules::boundary_point`]) over that face's corner values, summed by [`FVarSum`], whose
//! `corner(h)` reads the value corner `h` sees. Each child vertex has one own value, numbered as
//! the child vertices are, so a channel without seams refines exactly as a vertex-varying one.
//! The weights of a point are an affine combination of one face's corners, so every own value
//! is the same affine combination of that face's values as its position is of the face's
//! positions: the level is piecewise linear in every mode, and the [`crate::FVarLinear`] modes
//! all give the same values here.
//!
//! # Charts of the child faces
//!
//! A face face (the corner points of one parent face) sees its corners' own values. An edge
//! face (across parent edge `[h, g]`, corners `(next(h), h, next(g), g)`) and a vertex face
//! (around a parent vertex, starting at the vertex's first outgoing half-edge) take corners from
//! several parent faces; each takes the **chart** of its first corner's face: the face of `h`
//! for an edge face, the face of the vertex's first outgoing half-edge for a vertex face. A
//! corner of such a face from a face that sees the same value at that parent vertex as the chart
//! face does sees its own value; a corner from a face that sees a different value (across a
//! seam) sees instead a **copy of the chart face's parent value at that vertex**: one child
//! value per parent vertex and sibling value that some corner needs, shared by every face of
//! that chart at that vertex. So
//!
//! - no child face mixes charts: across a seam, an edge face reaches from the chart face's
//!   corner points to the parent seam edge's values as the chart face sees them (and a vertex
//!   face from the chart's corner points to the chart's value at the vertex), all within the
//!   chart's range;
//! - a seam stays a seam: a child vertex's own value and a copy are different indices, so the
//!   faces on the two sides of the cut see different values at every child vertex they share,
//!   while faces of one chart agree at every child vertex they share (the own value, or the
//!   one copy of the chart's value at that parent vertex);
//! - where no seam is involved, every corner sees its own value.
//!
//! Boundary edge faces (Chaikin) lie in one parent face. With the boundary retracting
//! (`boundary: none`) boundary edges and vertices have no faces.
//!
//! The child level is not analysed (a primal level after it analyses it afresh): its values are
//! `[own values in child vertex order | copies]` (numbered as the rest of `fvar` numbers them: a
//! vertex's first value as the vertex, so where nothing mismatches the corner values are the
//! child faces' indices), its corner values parallel to the child faces' corners.

use super::siblings::{Siblings, NONE};
use super::{FVarChannel, FVarLevel};
use crate::mesh::HalfEdgeMesh;
use crate::primvar::FVarSum;
use crate::refine::dqq::DualBoundary;
use crate::rules::CornerRules;

impl FVarChannel<'_> {
    /// Refines the channel with one Doo-Sabin level (the dual split of `mesh` with `rules` and
    /// `boundary`), whose child faces' corners are `child_corners` (the child's face indices,
    /// or its half-edges' from-vertices, in face order). See the module docs.
    pub fn refine_doo_sabin<R: CornerRules>(
        &mut self,
        mesh: &HalfEdgeMesh,
        rules: &R,
        boundary: DualBoundary,
        child_corners: &[u32],
    ) {
        let parent = std::mem::take(self.level_mut());
        let chaikin = boundary == DualBoundary::Chaikin;
        let (values, corner_values) = dual(mesh, rules, chaikin, &parent, child_corners);
        self.level =
            FVarLevel { width: parent.width, values, corner_values, ..FVarLevel::default() };
        self.analysed = false;
    }
}

/// The child values and corner values of one Doo-Sabin level (module docs).
fn dual<R: CornerRules>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    chaikin: bool,
    parent: &FVarLevel,
    child_corners: &[u32],
) -> (Vec<f32>, Vec<u32>) {
    let (width, cv) = (parent.width, &parent.corner_values[..]);
    let (nv, nh) = (mesh.num_vertices(), mesh.num_half_edges());
    let twin = |h: u32| mesh.he_next_around_edge[h as usize];
    let boundary: Vec<u32> =
        if chaikin { (0..nh as u32).filter(|&h| twin(h) == h).collect() } else { Vec::new() };
    let own_count = nh + 2 * boundary.len();

    // The copies: per vertex with several values, those the chart of some edge or vertex face
    // there needs; `copy[h]` is the child copy of the value corner `h` sees (or `NONE`).
    let siblings = Siblings::new(mesh, cv);
    let mut copy = vec![NONE; nh];
    let mut copied: Vec<u32> = Vec::new();
    let (mut need, mut slot) = (Vec::new(), Vec::new());
    for v in 0..nv as u32 {
        let k = siblings.count[v as usize] as usize;
        if k < 2 {
            continue;
        }
        let out = mesh.out_half_edges(v);
        need.clear();
        need.resize(k, false);
        // The vertex face (the host's rule: an interior vertex of valence 3 or more; a
        // boundary vertex when the boundary is kept) takes the chart of its first corner.
        let start = out[0];
        if if twin(start) == start { chaikin } else { out.len() >= 3 } {
            need[siblings.rank[start as usize] as usize] = true;
        }
        // The edge face of each interior edge here takes the chart of the edge's first
        // half-edge's face: that face's corner at `v` is the chart corner.
        for &h in out {
            let g = twin(h);
            if g == h {
                continue;
            }
            let other = mesh.next_in_cell(g);
            let first =
                mesh.edge_half_edges[mesh.edge_range(mesh.he_edge[h as usize] as usize).start];
            let (chart, other) = if first == h { (h, other) } else { (other, h) };
            if cv[chart as usize] != cv[other as usize] {
                need[siblings.rank[chart as usize] as usize] = true;
            }
        }
        slot.clear();
        slot.resize(k, NONE);
        for &h in out {
            let r = siblings.rank[h as usize] as usize;
            if need[r] && slot[r] == NONE {
                slot[r] = (own_count + copied.len()) as u32;
                copied.push(cv[h as usize]);
            }
            copy[h as usize] = slot[r];
        }
    }

    let mut values = vec![0.0f32; (own_count + copied.len()) * width];
    let (own, copies) = values.split_at_mut(own_count * width);
    let (corners, chaikin_points) = own.split_at_mut(nh * width);
    let mut sum = FVarSum::new(&parent.values, width, cv, &[]);
    let ends = [(0, 0); 2];
    for (h, out) in corners.chunks_exact_mut(width).enumerate() {
        sum.eval_into(out, ends, |w| rules.corner_point(mesh, h as u32, w));
    }
    for (k, out) in chaikin_points.chunks_exact_mut(width).enumerate() {
        sum.eval_into(out, ends, |w| rules.boundary_point(mesh, boundary[k / 2], k % 2, w));
    }
    for (out, &value) in copies.chunks_exact_mut(width).zip(&copied) {
        let at = value as usize * width;
        out.copy_from_slice(&parent.values[at..at + width]);
    }

    // The corner each child vertex belongs to.
    let own_corner = |x: u32| {
        if (x as usize) < nh {
            return x;
        }
        let k = x as usize - nh;
        let b = boundary[k / 2];
        if k.is_multiple_of(2) {
            b
        } else {
            mesh.next_in_cell(b)
        }
    };
    // Child faces are `[face faces (nh corners) | edge faces (4 corners each) | vertex faces]`.
    let edge_faces = (0..mesh.num_edges())
        .filter(|&e| match mesh.edge_range(e).len() {
            2 => true,
            1 => chaikin,
            _ => false,
        })
        .count();
    let vertex_faces = nh + 4 * edge_faces;
    let corner_values = child_corners
        .iter()
        .enumerate()
        .map(|(k, &x)| {
            if k < nh {
                return x;
            }
            let own = own_corner(x);
            let chart = if k < vertex_faces {
                // Edge face `(next(h), h, next(g), g)`: `next(g)` sits at `h`'s vertex and `g`
                // at `next(h)`'s (a boundary edge face's Chaikin points likewise).
                let j = (k - nh) % 4;
                let [a, b] = [child_corners[k - j], child_corners[k - j + 1]].map(own_corner);
                [a, b, b, a][j]
            } else {
                mesh.out_half_edges(mesh.he_from[own as usize])[0]
            };
            let copied = copy[chart as usize];
            debug_assert!(cv[own as usize] == cv[chart as usize] || copied != NONE);
            if cv[own as usize] == cv[chart as usize] || copied == NONE {
                x
            } else {
                copied
            }
        })
        .collect();
    (values, corner_values)
}
