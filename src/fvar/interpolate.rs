//! The values of a refined level (OpenSubdiv's `Far::PrimvarRefiner::InterpolateFaceVarying`):
//! face points are centroids, a matching value takes the surface's own rule, a seam's edge
//! point is the midpoint on each side, and a mismatched vertex value stays (a corner) or
//! follows its crease, blended while semi-sharp features decay.

use super::tag;
use super::topology::{for_each_marked, span_inner_edges, FVarLevel, LevelSharpness, Split};
use crate::mesh::HalfEdgeMesh;
use crate::primvar::{FVarSum, RowSum};
use crate::refine::PrimalSplit;
use crate::rules::crease::decay;
use crate::rules::{MixedSplitRules, Weights};
use std::marker::PhantomData;

/// The rules of a split as the face-varying interpolation calls them: the weights of an edge
/// point and of a vertex's new value (face points are always centroids).
pub trait ValueRules {
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights);
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights);
}

/// The rules `R` of the primal split `S`.
pub struct PrimalRules<'r, S, R>(&'r R, PhantomData<S>);

impl<'r, S: PrimalSplit<R>, R> PrimalRules<'r, S, R> {
    pub fn new(rules: &'r R) -> Self {
        PrimalRules(rules, PhantomData)
    }
}

impl<S: PrimalSplit<R>, R> ValueRules for PrimalRules<'_, S, R> {
    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        S::edge_rule(self.0, mesh, edge, w)
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        S::vertex_rule(self.0, mesh, vertex, w)
    }
}

/// The rules of the mixed split (Quad/Triangle).
pub struct MixedRules<'r, R>(pub &'r R);

impl<R: MixedSplitRules> ValueRules for MixedRules<'_, R> {
    #[inline]
    fn edge_point(&self, mesh: &HalfEdgeMesh, edge: u32, w: &mut impl Weights) {
        self.0.edge_point(mesh, edge, w)
    }

    #[inline]
    fn vertex_point(&self, mesh: &HalfEdgeMesh, vertex: u32, w: &mut impl Weights) {
        self.0.vertex_point(mesh, vertex, w)
    }
}

/// Fills `child`'s values (its topology from `FVarLevel::child_topology`) from `parent`'s,
/// on `split` with `rules`. With `linear` (mode `all`, or a linear scheme), every value is
/// interpolated linearly. `sharp` is the parent level's sharpness. `joint`, when given, holds
/// the values numbered as the child's vertices as the surface's rules make them from the
/// parent's vertex-numbered values (see [`crate::fvar::FVarChannel::vertex_values`]): they are
/// right away from the cells `near_seams` (`FVarLevel::cells_near_seams` of `parent`), so
/// only the rest is computed here.
#[allow(clippy::too_many_arguments)]
pub fn interpolate<F: ValueRules>(
    mesh: &HalfEdgeMesh,
    split: Split,
    rules: &F,
    parent: &FVarLevel,
    child: &mut FVarLevel,
    linear: bool,
    sharp: &LevelSharpness,
    near_seams: &[u32],
    joint: Option<Vec<f32>>,
) {
    let width = parent.width;
    let nv = mesh.num_vertices();
    let (face_point_of, face_points) = split.face_points(mesh);
    let edge_base = nv + face_points;
    // The mixed split's rules read the centroids of triangles too, which get no face point.
    let joint = joint.filter(|_| split != Split::Mixed && !linear);
    let near = joint.is_some().then(|| NearSeams::new(mesh, near_seams));
    let mut values = joint.unwrap_or_default();
    values.resize(child.num_values() * width, 0.0);
    let row = |i: u32| &parent.values[i as usize * width..(i as usize + 1) * width];
    let centroid = |face: &mut [f32], c: usize| {
        let range = mesh.cell_range(c);
        let scale = 1.0 / range.len() as f32;
        face.fill(0.0);
        for h in range {
            RowSum::add(face, row(parent.corner_values[h]), 1.0);
        }
        face.iter_mut().for_each(|x| *x *= scale);
    };

    // Every cell's centroid when the rules may weight it; the child has those of the cells
    // that get a face point. With joint values, the quad split's face points are every cell's
    // centroid in cell order, and only those of cells near a seam are recomputed.
    let mut own_faces = Vec::new();
    match &near {
        Some(near) if split == Split::Quad => {
            for &c in near.cells {
                let at = (nv + c as usize) * width;
                centroid(&mut values[at..at + width], c as usize);
            }
        }
        Some(_) => {}
        None if split != Split::Triangle => {
            own_faces = vec![0.0f32; mesh.num_cells() * width];
            for (c, face) in own_faces.chunks_exact_mut(width.max(1)).enumerate() {
                centroid(face, c);
                if let Some(k) = face_point_of.of(c as u32) {
                    let at = (nv + k as usize) * width;
                    values[at..at + width].copy_from_slice(face);
                }
            }
        }
        None => {}
    }
    let (head, tail) = values.split_at_mut(edge_base * width);
    let (vertex_values, joint_faces) = head.split_at_mut(nv * width);
    let face_values = if near.is_some() { &*joint_faces } else { &own_faces[..] };
    let spare = vec![0.0; width];
    let mut out = Targets { vertex_values, tail, edge_base, width, spare };
    let mut sum = FVarSum::new(&parent.values, width, &parent.corner_values, face_values);
    let midpoint = |out: &mut [f32], a: u32, b: u32| {
        for ((o, &x), &y) in out.iter_mut().zip(row(a)).zip(row(b)) {
            *o = 0.5 * (x + y);
        }
    };

    let loops = mesh.has_repeated_corners();
    let ne = mesh.num_edges();
    // With joint values, only the edges near seams and those whose point mismatches: listed
    // from the sparse marks eight at a time rather than tested one by one.
    let marks = near.as_ref().filter(|_| !loops).map(|n| n.edges.clone());
    for e in visits(marks, child.tags.get(edge_base..edge_base + ne), ne) {
        let cv = edge_base as u32 + e;
        let matches = child.tags[cv as usize] & tag::MISMATCH == 0;
        // Most edges: away from seams, their values refined with the surface's (read nothing
        // else).
        if matches && !loops && near.as_ref().is_some_and(|n| n.edges[e as usize] == 0) {
            continue;
        }
        let [a, b] = mesh.edge_vertices[e as usize];
        let hs = &mesh.edge_half_edges[mesh.edge_range(e as usize)];
        if a == b {
            // An edge from a vertex to itself (a face that repeats a vertex): infinitely sharp,
            // between the values of its face's two corners at the vertex.
            let x = hs[0];
            let (from, to) = (parent.corner_values[x as usize], mesh.next_in_cell(x));
            midpoint(out.at(cv), from, parent.corner_values[to as usize]);
            continue;
        }
        if matches {
            if near.as_ref().is_some_and(|n| n.edges[e as usize] == 0) {
                continue;
            }
            let ends = [(a, parent.value_at(mesh, hs[0], a)), (b, parent.value_at(mesh, hs[0], b))];
            if linear {
                midpoint(out.at(cv), ends[0].1, ends[1].1);
            } else {
                sum.eval_into(out.at(cv), ends, |w| rules.edge_point(mesh, e, w));
            }
            continue;
        }
        for (j, &x) in hs.iter().take(child.count(cv) as usize).enumerate() {
            let (va, vb) = (parent.value_at(mesh, x, a), parent.value_at(mesh, x, b));
            midpoint(out.at(child.value(cv, j as u32)), va, vb);
        }
    }

    // With joint values, only the vertices near seams, those that mismatch and those without
    // faces, listed as the edges are.
    let marks = near.as_ref().map(|n| {
        let mut marks = n.vertices.clone();
        for (mark, range) in marks.iter_mut().zip(mesh.vertex_offsets.windows(2)) {
            *mark |= u8::from(range[0] == range[1]);
        }
        marks
    });
    for v in visits(marks, parent.tags.get(..nv), nv) {
        if parent.tags[v as usize] & tag::MISMATCH == 0 {
            let isolated = mesh.out_half_edges(v).is_empty();
            if !isolated && near.as_ref().is_some_and(|n| n.vertices[v as usize] == 0) {
                continue;
            }
            if linear || isolated {
                out.at(v).copy_from_slice(row(v));
            } else {
                sum.eval_into(out.at(v), [(v, v); 2], |w| rules.vertex_point(mesh, v, w));
            }
            continue;
        }
        let count = parent.count(v);
        for j in 0..count {
            let (p, c) = (parent.value(v, j), child.value(v, j));
            let child_tag = child.tags[c as usize];
            if linear || child_tag & tag::CREASE == 0 {
                out.at(c).copy_from_slice(row(p));
                continue;
            }
            // A crease, or a corner turning into one: its ends are across the span's two
            // bounding edges.
            let [e0, e1] = parent.crease_end_values(mesh, p);
            let parent_tag = parent.tags[p as usize];
            let (mut vertex_weight, mut end_weight) = (0.75f32, 0.125f32);
            if parent_tag & tag::SEMI_SHARP != 0 {
                // A value sharpened by the other one takes that one's transition.
                let source = if parent_tag & tag::DEP_SHARP != 0 {
                    parent.value(v, 1 - j.min(1))
                } else {
                    p
                };
                let corner = fractional_weight(mesh, parent, sharp, v, source);
                let crease = 1.0 - corner;
                vertex_weight = crease * 0.75 + corner;
                end_weight = crease * 0.125;
            }
            let target = out.at(c);
            target.fill(0.0);
            RowSum::add(target, row(e0), end_weight);
            RowSum::add(target, row(e1), end_weight);
            RowSum::add(target, row(p), vertex_weight);
        }
    }
    child.values = values;
}

/// Where a level's new values go, but for the face points, which the rules read meanwhile:
/// the old vertices' values, and the edge points' values with the extra values after them.
struct Targets<'o> {
    vertex_values: &'o mut [f32],
    tail: &'o mut [f32],
    edge_base: usize,
    width: usize,
    /// What a face point's slot would get: nothing writes one (they are all set before), but a
    /// wrong index must not panic.
    spare: Vec<f32>,
}

impl Targets<'_> {
    #[inline(always)]
    fn at(&mut self, i: u32) -> &mut [f32] {
        let (i, width) = (i as usize, self.width);
        let (target, at) = if i >= self.edge_base {
            (&mut *self.tail, i - self.edge_base)
        } else if (i + 1) * width <= self.vertex_values.len() {
            (&mut *self.vertex_values, i)
        } else {
            (&mut self.spare[..], 0)
        };
        &mut target[at * width..(at + 1) * width]
    }
}

/// The edges or vertices (`0..count`) whose values a level must visit: with joint values,
/// those `marks` marks (near a seam, or without faces) and those whose `tags` mismatch (all of
/// them when there are no tags), listed from the bytes eight at a time; else every one.
fn visits(marks: Option<Vec<u8>>, tags: Option<&[u8]>, count: usize) -> impl Iterator<Item = u32> {
    let listed = marks.map(|mut marks| {
        match tags {
            Some(tags) => for_each_marked(tags, tag::MISMATCH, |i| marks[i] = 1),
            None => marks.fill(1),
        }
        let mut list = Vec::new();
        for_each_marked(&marks, 1, |i| list.push(i as u32));
        list
    });
    let all = if listed.is_some() { 0..0 } else { 0..count as u32 };
    listed.unwrap_or_default().into_iter().chain(all)
}

/// The cells next to seams (`FVarLevel::cells_near_seams`) and their vertices and edges: the
/// rules of every other new value read vertex-numbered values only.
struct NearSeams<'c> {
    cells: &'c [u32],
    /// 1 for a vertex of a cell near a seam (bytes, for [`for_each_marked`]).
    vertices: Vec<u8>,
    /// 1 for an edge near a seam (bytes, for [`for_each_marked`]).
    edges: Vec<u8>,
}

impl<'c> NearSeams<'c> {
    fn new(mesh: &HalfEdgeMesh, cells: &'c [u32]) -> Self {
        let mut vertices = vec![0u8; mesh.num_vertices()];
        let mut edges = vec![0u8; mesh.num_edges()];
        for &c in cells {
            for h in mesh.cell_range(c as usize) {
                vertices[mesh.he_from[h] as usize] = 1;
                edges[mesh.he_edge[h] as usize] = 1;
            }
        }
        NearSeams { cells, vertices, edges }
    }
}

/// How much of the corner rule a value keeps as its span's sharpness decays to smooth: the mean
/// sharpness of what turns smooth at this level (the vertex, the edges inside the span), at
/// most 1 (OpenSubdiv's `Crease::ComputeFractionalWeightAtVertex` over the span).
fn fractional_weight(
    mesh: &HalfEdgeMesh,
    level: &FVarLevel,
    sharp: &LevelSharpness,
    v: u32,
    value: u32,
) -> f32 {
    let (mut sum, mut count) = (0.0f32, 0u32);
    let vertex = sharp.vertex(mesh, v);
    if vertex > 0.0 && decay(vertex) <= 0.0 {
        sum += vertex;
        count += 1;
    }
    span_inner_edges(mesh, level.crease_ends(value), |e| {
        let s = sharp.edge(mesh, e);
        if s > 0.0 && sharp.child_edge(mesh, e, v) <= 0.0 {
            sum += s;
            count += 1;
        }
    });
    if count == 0 {
        0.0
    } else {
        (sum / count as f32).min(1.0)
    }
}
