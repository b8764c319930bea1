//! Triangle soups made into a surface: what a triangle list from a renderer (a three.js
//! `BufferGeometry`, a glTF primitive) needs before it can be subdivided.
//!
//! Renderers split a vertex wherever a UV, a normal or a colour differs, so their triangles do
//! not share vertices along seams and hard edges. These functions, used in this order by
//! `subsurf/three`, give the surface back:
//!
//! 1. [`weld_triangles`] ([`weld`]): one vertex per bit-identical position, then optionally per
//!    cluster of positions within a distance; triangles whose corners weld together are dropped.
//! 2. [`TriangleEdges`] ([`edges`]): the edges of the welded triangles, and
//!    [`triangle_normals`].
//! 3. [`sharp`]: edges made sharp by a dihedral angle ([`crease_angle_edges`]) or by the
//!    input's split normals ([`normal_split_edges`]).
//! 4. [`join_quads`] ([`quads`]): pairs of triangles joined into quads as Blender's "Tris to
//!    Quads" does.
//! 5. [`smoothing_fans`] and [`side_normals`] ([`sides`]): the corners around a vertex grouped
//!    between sharp edges, and a normal per group for the refined surface.
//!
//! [`triangle_faces`] runs steps 2 to 5 (those asked for) on the result of step 1.
//!
//! This module sits beside `scheme` and `evaluation`: it reads flat arrays and returns flat
//! arrays, and nothing below it (`mesh`, `refine`, `rules`) knows about it. Hot loops sort and
//! index flat arrays; there is no hash map.
//!
//! ```
//! use subsurf::triangles::{weld_triangles, join_quads, QuadLimits, TriangleEdges};
//!
//! // A unit square as two triangles that do not share vertices (as a renderer may store it).
//! let positions = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 0., 0., 1., 1., 0., 0., 1., 0.];
//! let welded = weld_triangles(&positions, &[0, 1, 2, 3, 4, 5], 0.0).unwrap();
//! assert_eq!(welded.positions.len(), 4 * 3);
//! let edges = TriangleEdges::new(&welded.corners).unwrap();
//! let marks = vec![0; edges.len()];
//! let quads = join_quads(&welded.positions, &welded.corners, &edges, &marks,
//!     &Default::default(), QuadLimits::default()).unwrap();
//! assert_eq!(quads.face_sizes, [4]);
//! ```

pub mod edges;
pub mod faces;
pub mod quads;
pub mod sharp;
pub mod sides;
pub mod weld;

pub use edges::{triangle_normals, TriangleEdges};
pub use faces::{triangle_faces, FaceOptions, Faces};
pub use quads::{join_quads, quad_error, JoinConstraints, Polygons, QuadLimits};
pub use sharp::{crease_angle_edges, normal_split_edges};
pub use sides::{side_normals, smoothing_fans};
pub use weld::{weld_triangles, Welded, UNUSED};

/// The corner after corner `h` in its triangle (corners are numbered `3 t + j`).
#[inline]
pub(crate) fn next3(h: usize) -> usize {
    if h % 3 == 2 {
        h - 2
    } else {
        h + 1
    }
}
