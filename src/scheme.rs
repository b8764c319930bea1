//! The public vocabulary: schemes, boundary rules, options, and [`subdivide`].

use crate::error::{Error, Result};
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::refine::dqq::{self, DualBoundary};
use crate::refine::{pqq, ptq, quad_tri, sqrt3};
use crate::rules::Sqrt3;
use crate::rules::{
    Bilinear, CatmullClark, DooSabin, Loop, Midpoint, QuadSplitRules, QuadTriangle, TriSplitRules,
};
use serde::Deserialize;
use std::fmt;
use std::str::FromStr;

/// A subdivision scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scheme {
    /// Catmull-Clark: any polygons in, quads out.
    #[default]
    CatmullClark,
    /// Loop: triangles in, triangles out.
    Loop,
    /// Doo-Sabin: the dual quadratic scheme; any polygons.
    DooSabin,
    /// Bilinear: the quad split with centroids and midpoints; any polygons.
    Bilinear,
    /// Midpoint: the triangle split with midpoints; triangles only.
    Midpoint,
    /// Quad/Triangle (Stam & Loop 2003): Catmull-Clark on quads, Loop on triangles, and a
    /// blend where they meet; other polygons split into quads at the first level.
    QuadTriangle,
    /// √3 (Kobbelt 2000): a centroid per triangle, old edges flipped; triangles only. Boundary
    /// edges are split on every second level of a run of √3 levels, as CGAL does.
    Sqrt3,
}

impl Scheme {
    pub const ALL: &'static [Scheme] = &[
        Scheme::CatmullClark,
        Scheme::Loop,
        Scheme::DooSabin,
        Scheme::QuadTriangle,
        Scheme::Sqrt3,
        Scheme::Bilinear,
        Scheme::Midpoint,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Scheme::CatmullClark => "catmull-clark",
            Scheme::Loop => "loop",
            Scheme::DooSabin => "doo-sabin",
            Scheme::Bilinear => "bilinear",
            Scheme::Midpoint => "midpoint",
            Scheme::QuadTriangle => "quad-triangle",
            Scheme::Sqrt3 => "sqrt3",
        }
    }

    /// True for the schemes defined on triangles only.
    pub fn triangles_only(self) -> bool {
        matches!(self, Scheme::Loop | Scheme::Midpoint | Scheme::Sqrt3)
    }

    /// Parses one name or a comma-separated list of names, one per level.
    pub fn parse_list(list: &str) -> Result<Vec<Scheme>> {
        list.split(',').map(|name| name.trim().parse()).collect()
    }
}

/// What happens on boundary edges and vertices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Boundary {
    /// Boundary edges are sharp creases and vertices with one face stay put, as OpenSubdiv's
    /// `VTX_BOUNDARY_EDGE_AND_CORNER`.
    #[default]
    EdgeAndCorner,
    /// Boundary edges are sharp creases, every boundary vertex follows the crease rule
    /// `(a + 6v + b) / 8`, as OpenSubdiv's `VTX_BOUNDARY_EDGE_ONLY` and CGAL.
    EdgeOnly,
    /// Boundary vertices keep their position; boundary edge points are midpoints (seed 000).
    Fixed,
    /// A boundary vertex moves to the mean of itself and its boundary edges' midpoints (seed 003).
    Average,
    /// No boundary interpolation: Doo-Sabin leaves out the faces of boundary edges and vertices,
    /// so the surface retracts from the boundary, as CGAL's Doo-Sabin does. Doo-Sabin only.
    None,
}

impl Boundary {
    pub const ALL: &'static [Boundary] = &[
        Boundary::EdgeAndCorner,
        Boundary::EdgeOnly,
        Boundary::Fixed,
        Boundary::Average,
        Boundary::None,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Boundary::EdgeAndCorner => "edge-and-corner",
            Boundary::EdgeOnly => "edge-only",
            Boundary::Fixed => "fixed",
            Boundary::Average => "average",
            Boundary::None => "none",
        }
    }
}

fn parse_name<T: Copy>(
    what: &str,
    value: &str,
    all: &[T],
    name: fn(T) -> &'static str,
) -> Result<T> {
    all.iter().copied().find(|&t| name(t) == value).ok_or_else(|| {
        let allowed: Vec<_> = all.iter().map(|&t| format!("'{}'", name(t))).collect();
        Error::InvalidOption(format!("unknown {what} '{value}'; use one of {}", allowed.join(", ")))
    })
}

impl FromStr for Scheme {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        parse_name("scheme", s, Scheme::ALL, Scheme::name)
    }
}

impl FromStr for Boundary {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        parse_name("boundary", s, Boundary::ALL, Boundary::name)
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for Boundary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The default memory guard: the most output faces one call may produce. 16 M quads with their
/// positions, indices and a triangle list take about 1 GiB, which fits a wasm32 memory next to
/// the level before it.
pub const DEFAULT_MAX_FACES: u64 = 1 << 24;

/// How to subdivide.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The scheme of each level, first level first. Its length is the number of levels.
    pub schemes: Vec<Scheme>,
    pub boundary: Boundary,
    /// Refuse, before any work, when the last level would have more faces than this.
    pub max_faces: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            schemes: vec![Scheme::CatmullClark],
            boundary: Boundary::default(),
            max_faces: DEFAULT_MAX_FACES,
        }
    }
}

impl Options {
    /// `levels` levels of one scheme.
    pub fn new(scheme: Scheme, levels: u32) -> Self {
        Options { schemes: vec![scheme; levels as usize], ..Options::default() }
    }

    pub fn with_boundary(mut self, boundary: Boundary) -> Self {
        self.boundary = boundary;
        self
    }

    pub fn levels(&self) -> usize {
        self.schemes.len()
    }
}

/// Predicted `(vertices, faces)` after all levels, saturating instead of overflowing. Exact for
/// the primal schemes; for Doo-Sabin an upper bound.
pub fn predict_counts(mesh: &HalfEdgeMesh, options: &Options) -> (u64, u64) {
    let mut counts =
        [mesh.num_vertices(), mesh.num_edges(), mesh.num_half_edges(), mesh.num_cells()]
            .map(|n| n as u64);
    for (level, scheme) in options.schemes.iter().enumerate() {
        let [v, e, h, f] = counts;
        counts = match scheme {
            Scheme::CatmullClark | Scheme::Bilinear => pqq::child_counts(v, e, h, f),
            Scheme::Loop | Scheme::Midpoint => ptq::child_counts(v, e, h, f),
            Scheme::DooSabin => dqq::child_counts(v, e, h, f),
            Scheme::Sqrt3 => {
                sqrt3::child_counts(v, e, h, f, sqrt3_refines_boundary(&options.schemes, level))
            }
            Scheme::QuadTriangle => {
                // Upper bound: as if every face were a triangle (four children, no centroid)
                // and as if none were (a centroid each); exact counts need the face sizes.
                let [v2, f2] = quad_tri::child_counts(v, e, h, f, 0);
                [v2, 2 * e + h, 4 * h, f2.max(4 * f)]
            }
        };
        if counts[3] > u64::MAX / 64 {
            break;
        }
    }
    (counts[0], counts[3])
}

/// √3 splits boundary edges on every second level of a run of √3 levels, starting with the
/// second, as CGAL's `Sqrt3_subdivision` does on steps 2, 4, ... of one call. A splitting level
/// thus always follows a √3 level, which leaves at most one boundary edge per triangle.
fn sqrt3_refines_boundary(schemes: &[Scheme], level: usize) -> bool {
    let run = schemes.iter().take(level).rev();
    run.take_while(|&&s| s == Scheme::Sqrt3).count() % 2 == 1
}

/// Subdivides `mesh` as `options` says. The input is only read.
pub fn subdivide(mesh: &PolyMesh, options: &Options) -> Result<PolyMesh> {
    let base = HalfEdgeMesh::from_poly(mesh)?;
    subdivide_mesh(base, options)
}

/// Refuses a scheme on a mesh it is not defined on, naming the first offending face.
fn check_scheme(
    mesh: &HalfEdgeMesh,
    scheme: Scheme,
    boundary: Boundary,
    level: usize,
) -> Result<()> {
    let at = |what: String| Error::Unsupported(format!("level {}: {what}", level + 1));
    if scheme.triangles_only() {
        if let Some(c) = mesh
            .cell_indices()
            .find(|&c| mesh.cell_offsets[c as usize + 1] - mesh.cell_offsets[c as usize] != 3)
        {
            let n = mesh.cell_offsets[c as usize + 1] - mesh.cell_offsets[c as usize];
            let when = if level == 0 { "the input" } else { "the previous level's result" };
            return Err(at(format!(
                "{scheme} is defined on triangles only, but face {c} of {when} has {n} vertices; use 'quad-triangle' for meshes with quads, or triangulate first"
            )));
        }
    }
    if boundary == Boundary::None && scheme != Scheme::DooSabin {
        return Err(at(format!(
            "boundary 'none' is only defined for doo-sabin; use 'edge-and-corner', 'edge-only', 'fixed' or 'average' with {scheme}"
        )));
    }
    if matches!(scheme, Scheme::DooSabin | Scheme::Sqrt3) {
        dqq::check(mesh, scheme.name()).map_err(|e| match e {
            Error::Unsupported(message) => at(message),
            other => other,
        })?;
    }
    Ok(())
}

/// Subdivides an already built half-edge mesh.
pub fn subdivide_mesh(base: HalfEdgeMesh, options: &Options) -> Result<PolyMesh> {
    let (_, faces) = predict_counts(&base, options);
    if faces > options.max_faces {
        return Err(Error::TooLarge(format!(
            "{} level(s) would make {faces} faces, more than the limit of {}; use fewer levels or raise maxFaces (CLI --max-faces)",
            options.levels(),
            options.max_faces
        )));
    }
    let mut mesh = base;
    let levels = options.schemes.len();
    for (level, &scheme) in options.schemes.iter().enumerate() {
        check_scheme(&mesh, scheme, options.boundary, level)?;
        let last = level + 1 == levels;
        let boundary = options.boundary;
        let child = match scheme {
            Scheme::CatmullClark => quad_split(mesh, &CatmullClark { boundary }, last),
            Scheme::Bilinear => quad_split(mesh, &Bilinear, last),
            Scheme::Loop => tri_split(&mesh, &Loop { boundary }),
            Scheme::Midpoint => tri_split(&mesh, &Midpoint),
            Scheme::QuadTriangle => {
                Level::Poly(quad_tri::refine(&mesh, &QuadTriangle { boundary }))
            }
            Scheme::DooSabin => {
                let mode = if boundary == Boundary::None {
                    DualBoundary::Retract
                } else {
                    DualBoundary::Chaikin
                };
                Level::Poly(dqq::refine(&mesh, &DooSabin, mode))
            }
            Scheme::Sqrt3 => {
                let refine_boundary = sqrt3_refines_boundary(&options.schemes, level);
                Level::Poly(sqrt3::refine(&mesh, &Sqrt3 { boundary }, refine_boundary))
            }
        };
        mesh = match child {
            Level::Poly(poly) if last => return Ok(poly),
            Level::Poly(poly) => HalfEdgeMesh::from_poly(&poly)?,
            Level::Mesh(mesh) => mesh,
        };
    }
    Ok(mesh.to_poly())
}

/// One level's result: flat arrays (always for the last level), or a mesh built by index
/// arithmetic where a host can do that.
enum Level {
    Poly(PolyMesh),
    Mesh(HalfEdgeMesh),
}

fn quad_split<R: QuadSplitRules>(mesh: HalfEdgeMesh, rules: &R, last: bool) -> Level {
    let count = pqq::num_child_vertices(&mesh);
    if last {
        // Written straight into the output array: no copy of the largest buffer.
        let mut positions = vec![0.0f32; 3 * count];
        pqq::refine_points(&mesh, rules, positions.as_chunks_mut::<3>().0);
        let indices = pqq::child_face_indices(&mesh);
        let face_sizes = vec![4; mesh.num_half_edges()];
        return Level::Poly(PolyMesh { positions, indices, face_sizes });
    }
    let mut positions = vec![[0.0f32; 3]; count];
    pqq::refine_points(&mesh, rules, &mut positions);
    Level::Mesh(pqq::child_mesh(&mesh, positions))
}

fn tri_split<R: TriSplitRules>(mesh: &HalfEdgeMesh, rules: &R) -> Level {
    let mut positions = vec![0.0f32; 3 * ptq::num_child_vertices(mesh)];
    ptq::refine_points(mesh, rules, positions.as_chunks_mut::<3>().0);
    let indices = ptq::child_face_indices(mesh);
    let face_sizes = vec![3; indices.len() / 3];
    Level::Poly(PolyMesh { positions, indices, face_sizes })
}
