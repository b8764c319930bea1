//! Face-varying channels through a √3 level ([`crate::refine::sqrt3`]).
//!
//! # Values
//!
//! - **Old vertices.** A vertex **matches** when its corners all see one value and no seam
//!   touches it (every edge at it has the same values at its far end on both sides): that value
//!   takes the √3 vertex rule, the same weights as the position ([`Sqrt3Rules::vertex_point`]),
//!   with [`FVarSum`] reading each neighbour through the corner it is seen from. Each value of a
//!   vertex that does not match stays (a corner): one child value per distinct value at the
//!   vertex. A vertex without faces has no values.
//! - **Face points** are the rule's face point over the face's corner values (the centroid).
//! - **Boundary points** (two per split boundary edge, on the levels that refine the boundary)
//!   take the positions' weights over that edge's values in its face (Kobbelt's
//!   `(q + 16t + 10s)/27`, with `q` the boundary neighbour beyond `t`, read through its own face,
//!   which sees `t` as this one does) when the end they are near matches; otherwise the linear
//!   third, `(2t + s)/3`: Kobbelt's point with `q` reflected (`q = 2t - s`), as befits an end
//!   whose value stays.
//! - **Seam midpoints**: one child value per side of each seam edge, the midpoint of that
//!   edge's two values as that side's face sees them (below).
//!
//! The modes ([`FVarLinear`]): `boundaries` makes every value of a mesh boundary vertex stay
//! and every boundary point the linear third; `all` is piecewise linear: old values stay, face
//! points are centroids, boundary points the linear thirds (each child value the affine
//! combination of one parent face's values with the weights of its position in the linear
//! split). The others (`none`, `corners-only`, `corners-plus1`, `corners-plus2`) are the rules
//! above: √3 has no crease rule, so a seam's values are corners in all of them.
//!
//! # Charts of the child triangles
//!
//! Child triangle `h` belongs to parent half-edge `h = u → v` of face `f1` and takes `f1`'s
//! chart: its corner at an old vertex sees the child of the value `f1` sees there, its corner
//! at `f1`'s own new point that point's value. The flipped triangle `(u, a(g), a(h))` of an
//! interior edge also reaches the new point `a(g)` of the face `f2` across (`g = v → u`): when
//! the edge is not a seam, that point's value; when it is a seam, the **midpoint of the edge's
//! values as `f1` sees them** (where the seam edge was, in `f1`'s chart). The two triangles of a
//! seam edge thus see different values at both ends of the flipped edge between them and at
//! `u` and `v`: a seam stays a seam, and no child triangle interpolates across charts.
//!
//! The child level is not analysed (a primal level after it analyses it afresh). Its values
//! are numbered as the rest of `fvar` numbers them: an old vertex's first value as the vertex,
//! a new point as its child vertex, then the further values of old vertices with several, then
//! the seam midpoints; so where nothing mismatches the corner values are the child triangles'
//! indices. The corner values are parallel to the child triangles' corners.

use super::siblings::{is_seam, Siblings, NONE};
use super::{FVarChannel, FVarLevel};
use crate::mesh::HalfEdgeMesh;
use crate::options::FVarLinear;
use crate::primvar::FVarSum;
use crate::refine::sqrt3::{first_child_vertices, split_half_edges};
use crate::rules::{centroid, Sqrt3Rules, Weights};

impl FVarChannel<'_> {
    /// Refines the channel with one √3 level of `mesh` with `rules` (`refine_boundary` as the
    /// host's), whose child triangles' corners are `child_corners` (the child's face indices, or
    /// its half-edges' from-vertices, in face order), under `mode`. See the module docs.
    pub fn refine_sqrt3<R: Sqrt3Rules>(
        &mut self,
        mesh: &HalfEdgeMesh,
        rules: &R,
        refine_boundary: bool,
        mode: FVarLinear,
        child_corners: &[u32],
    ) {
        let parent = std::mem::take(self.level_mut());
        let level = Sqrt3Level { mesh, rules, refine_boundary, mode, parent: &parent };
        let (values, corner_values) = level.refine(child_corners);
        self.level =
            FVarLevel { width: parent.width, values, corner_values, ..FVarLevel::default() };
        self.analysed = false;
    }
}

struct Sqrt3Level<'a, R> {
    mesh: &'a HalfEdgeMesh,
    rules: &'a R,
    refine_boundary: bool,
    mode: FVarLinear,
    parent: &'a FVarLevel,
}

impl<R: Sqrt3Rules> Sqrt3Level<'_, R> {
    fn refine(&self, child_corners: &[u32]) -> (Vec<f32>, Vec<u32>) {
        let (mesh, rules, parent) = (self.mesh, self.rules, self.parent);
        let (width, cv) = (parent.width, &parent.corner_values[..]);
        let (nv, nh) = (mesh.num_vertices(), mesh.num_half_edges());
        let twin = |h: u32| mesh.he_next_around_edge[h as usize];
        let linear = self.mode == FVarLinear::All;
        let linear_boundaries = matches!(self.mode, FVarLinear::Boundaries | FVarLinear::All);

        let siblings = Siblings::new(mesh, cv);
        let seam: Vec<bool> = (0..nh as u32).map(|h| is_seam(mesh, cv, h)).collect();
        let matching: Vec<bool> = (0..nv as u32)
            .map(|v| {
                let out = mesh.out_half_edges(v);
                // A manifold boundary vertex lists its boundary half-edge first.
                let boundary = out.first().is_some_and(|&h| twin(h) == h);
                !linear
                    && siblings.count[v as usize] == 1
                    && !(linear_boundaries && boundary)
                    && out.iter().all(|&h| !seam[h as usize])
            })
            .collect();
        // Child values: `[child vertices | further values of old vertices | seam midpoints]`.
        // An old vertex's first value is numbered as the vertex, a new point as its child
        // vertex; `further[i]` is the parent value of further value `i`, and `corner_value[h]`
        // the child value of the value corner `h` sees (each vertex writes its own corners').
        let split = split_half_edges(mesh, self.refine_boundary);
        let (first, num_child_vertices) = first_child_vertices(mesh, &split);
        let mut corner_value = vec![0u32; nh];
        let mut further: Vec<u32> = Vec::new();
        for v in 0..nv as u32 {
            let out = mesh.out_half_edges(v);
            if matching[v as usize] || siblings.count[v as usize] < 2 {
                out.iter().for_each(|&h| corner_value[h as usize] = v);
                continue;
            }
            let (start, mut pushed) = ((num_child_vertices + further.len()) as u32, 0);
            for &h in out {
                // Ranks are numbered in the order they are first met.
                let r = siblings.rank[h as usize];
                if r > pushed {
                    further.push(cv[h as usize]);
                    pushed += 1;
                }
                corner_value[h as usize] = if r == 0 { v } else { start + r - 1 };
            }
        }
        // One value per side of each seam edge.
        let mut mid = vec![NONE; nh];
        let mut at = (num_child_vertices + further.len()) as u32;
        for (slot, &seam) in mid.iter_mut().zip(&seam) {
            if seam {
                *slot = at;
                at += 1;
            }
        }
        let total = at as usize;

        let mut values = vec![0.0f32; total * width];
        let row = |i: u32| &parent.values[i as usize * width..(i as usize + 1) * width];
        let mut sum = FVarSum::new(&parent.values, width, cv, &[]);
        let (old, rest) = values.split_at_mut(nv * width);
        let (new, rest) = rest.split_at_mut((num_child_vertices - nv) * width);
        let (further_values, mids) = rest.split_at_mut(further.len() * width);
        for (v, out) in old.chunks_exact_mut(width).enumerate() {
            let v = v as u32;
            // A vertex without faces keeps a value no corner sees.
            let Some(&corner) = mesh.out_half_edges(v).first() else { continue };
            if matching[v as usize] {
                let ends = [(v, cv[corner as usize]); 2];
                sum.eval_into(out, ends, |w| rules.vertex_point(mesh, v, self.refine_boundary, w));
            } else {
                out.copy_from_slice(row(cv[corner as usize]));
            }
        }
        for (out, &value) in further_values.chunks_exact_mut(width).zip(&further) {
            out.copy_from_slice(row(value));
        }
        // Each cell writes its own one or two new points.
        let ends = [(0, 0); 2];
        for (c, (&b, &slot)) in split.iter().zip(&first).enumerate() {
            let at = (slot as usize - nv) * width;
            if b == NONE {
                let out = &mut new[at..at + width];
                if linear {
                    sum.eval_into(out, ends, |w| centroid(mesh, c as u32, w));
                } else {
                    sum.eval_into(out, ends, |w| rules.face_point(mesh, c as u32, w));
                }
                continue;
            }
            for near in 0..2 {
                let (near_end, far_end) =
                    if near == 0 { (b, mesh.next_in_cell(b)) } else { (mesh.next_in_cell(b), b) };
                let out = &mut new[at + near * width..at + (near + 1) * width];
                if matching[mesh.he_from[near_end as usize] as usize] {
                    sum.eval_into(out, ends, |w| rules.boundary_point(mesh, b, near, w));
                } else {
                    sum.eval_into(out, ends, |w| {
                        w.corner(near_end, 2.0 / 3.0);
                        w.corner(far_end, 1.0 / 3.0);
                    });
                }
            }
        }
        let mid_base = num_child_vertices + further.len();
        for (h, &slot) in mid.iter().enumerate() {
            if slot != NONE {
                let at = (slot as usize - mid_base) * width;
                let (a, b) = (row(cv[h]), row(cv[mesh.next_in_cell(h as u32) as usize]));
                for ((out, &x), &y) in mids[at..at + width].iter_mut().zip(a).zip(b) {
                    *out = 0.5 * (x + y);
                }
            }
        }

        // The cell of each new child vertex; each cell writes its own.
        let mut owner = vec![0u32; num_child_vertices - nv];
        for (c, (&b, &slot)) in split.iter().zip(&first).enumerate() {
            let at = slot as usize - nv;
            owner[at] = c as u32;
            if b != NONE {
                owner[at + 1] = c as u32;
            }
        }
        let corner_values = child_corners
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let h = (k / 3) as u32;
                let cell = mesh.cell_of(h);
                if (x as usize) < nv {
                    if matching[x as usize] {
                        return x;
                    }
                    // The value this triangle's parent face sees at `x`.
                    let corner = mesh
                        .cell_range(cell as usize)
                        .find(|&y| mesh.he_from[y] == x)
                        .map_or(h, |y| y as u32);
                    return corner_value[corner as usize];
                }
                if owner[x as usize - nv] == cell || mid[h as usize] == NONE {
                    x
                } else {
                    mid[h as usize]
                }
            })
            .collect();
        (values, corner_values)
    }
}
