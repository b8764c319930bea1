//! Tags: sharp edges (creases), sharp vertices (corners) and hole faces, as OpenSubdiv's
//! `Far::TopologyDescriptor` and the `t` lines of its OBJ files describe them, plus the two
//! scheme options the OBJ files carry with them (`creasemethod`, `smoothtriangles`).
//!
//! Sharpness is a number per edge or vertex: 0 is smooth, [`SHARPNESS_INFINITE`] (10) or more is
//! infinitely sharp, anything between is semi-sharp: the sharp rule for about that many levels,
//! then a blend, then the smooth rule (DeRose, Kass and Truong 1998, as OpenSubdiv 3 does it). The
//! rules themselves are in [`crate::rules::crease`]. Catmull-Clark and Loop use tags, bilinear and
//! midpoint carry them to the next level of a scheme list, and Doo-Sabin, √3 and Quad/Triangle
//! refuse non-trivial tags.

use crate::error::{Error, Result};
pub use crate::options::CreaseMethod;

/// Sharpness at or above which an edge or vertex is infinitely sharp (OpenSubdiv's
/// `Sdc::Crease::SHARPNESS_INFINITE`).
pub const SHARPNESS_INFINITE: f32 = 10.0;

/// A sharp edge: the two vertices of an existing edge (either order) and its sharpness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crease {
    pub vertices: [u32; 2],
    pub sharpness: f32,
}

/// A sharp vertex and its sharpness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    pub vertex: u32,
    pub sharpness: f32,
}

/// The tags of a base mesh. The default has none: every edge and vertex smooth, no holes.
///
/// Indices refer to the mesh given to [`crate::scheme::subdivide_with_tags`]: vertices
/// `0..V`, faces `0..F` in input order. An edge or vertex named twice takes the last value, as in
/// OpenSubdiv. Invalid tags (a vertex pair that is not an edge, an index out of range, a
/// negative or NaN sharpness) are an [`Error::InvalidTag`] naming the tag.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tags {
    /// Sharp edges.
    pub creases: Vec<Crease>,
    /// Sharp vertices.
    pub corners: Vec<Corner>,
    /// Faces left out of the result, together with all their descendants. They still shape
    /// their neighbours, and every vertex is still output (vertex order does not change).
    pub holes: Vec<u32>,
    /// How semi-sharp edges lose sharpness from one level to the next.
    pub crease_method: CreaseMethod,
    /// Catmull-Clark only: OpenSubdiv's `TRI_SUB_SMOOTH` (OBJ `smoothtriangles smooth`), a
    /// modified edge rule next to triangles that makes the limit surface over a triangle rounder.
    pub smooth_triangles: bool,
}

impl Tags {
    /// True when some crease or corner has a sharpness above 0, or some face is a hole: the
    /// only tags that change a result. The crease method and `smooth_triangles` alone do not count.
    pub fn is_trivial(&self) -> bool {
        self.creases.iter().all(|c| c.sharpness <= 0.0)
            && self.corners.iter().all(|c| c.sharpness <= 0.0)
            && self.holes.is_empty()
    }

    /// Checks indices against a mesh of `vertices` vertices and `faces` faces, and every
    /// sharpness; the edge check needs the mesh and happens when subdividing.
    pub fn validate(&self, vertices: usize, faces: usize) -> Result<()> {
        for (i, c) in self.creases.iter().enumerate() {
            let [a, b] = c.vertices;
            let what = || format!("crease {i} (vertices {a}, {b})");
            for v in [a, b] {
                if v as usize >= vertices {
                    return Err(Error::InvalidTag(format!(
                        "{}: vertex {v} does not exist; the mesh has {vertices} vertices",
                        what()
                    )));
                }
            }
            if a == b {
                return Err(Error::InvalidTag(format!(
                    "{}: names one vertex twice; a crease names the two vertices of an edge",
                    what()
                )));
            }
            check_sharpness(c.sharpness, &what)?;
        }
        for (i, c) in self.corners.iter().enumerate() {
            let v = c.vertex;
            let what = || format!("corner {i} (vertex {v})");
            if v as usize >= vertices {
                return Err(Error::InvalidTag(format!(
                    "{}: vertex {v} does not exist; the mesh has {vertices} vertices",
                    what()
                )));
            }
            check_sharpness(c.sharpness, &what)?;
        }
        for (i, &f) in self.holes.iter().enumerate() {
            if f as usize >= faces {
                return Err(Error::InvalidTag(format!(
                    "hole {i} (face {f}): face {f} does not exist; the mesh has {faces} faces"
                )));
            }
        }
        Ok(())
    }
}

fn check_sharpness(s: f32, what: &dyn Fn() -> String) -> Result<()> {
    if s.is_nan() {
        return Err(Error::InvalidTag(format!(
            "{}: sharpness is NaN; give a number from 0 (smooth) to 10 (infinitely sharp)",
            what()
        )));
    }
    if s < 0.0 {
        return Err(Error::InvalidTag(format!(
            "{}: sharpness {s} is negative; give a number from 0 (smooth) to 10 (infinitely sharp)",
            what()
        )));
    }
    Ok(())
}
