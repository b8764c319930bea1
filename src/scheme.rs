//! The public vocabulary: schemes, boundary rules, options, and [`subdivide`].

use crate::error::{Error, Result};
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::refine::pqq;
use crate::rules::CatmullClark;
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
}

impl Scheme {
    pub const ALL: &'static [Scheme] = &[Scheme::CatmullClark];

    pub fn name(self) -> &'static str {
        match self {
            Scheme::CatmullClark => "catmull-clark",
        }
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
}

impl Boundary {
    pub const ALL: &'static [Boundary] = &[
        Boundary::EdgeAndCorner,
        Boundary::EdgeOnly,
        Boundary::Fixed,
        Boundary::Average,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Boundary::EdgeAndCorner => "edge-and-corner",
            Boundary::EdgeOnly => "edge-only",
            Boundary::Fixed => "fixed",
            Boundary::Average => "average",
        }
    }
}

fn parse_name<T: Copy>(
    what: &str,
    value: &str,
    all: &[T],
    name: fn(T) -> &'static str,
) -> Result<T> {
    all.iter()
        .copied()
        .find(|&t| name(t) == value)
        .ok_or_else(|| {
            let allowed: Vec<_> = all.iter().map(|&t| format!("'{}'", name(t))).collect();
            Error::InvalidOption(format!(
                "unknown {what} '{value}'; use one of {}",
                allowed.join(", ")
            ))
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
        Options {
            schemes: vec![scheme; levels as usize],
            ..Options::default()
        }
    }

    pub fn with_boundary(mut self, boundary: Boundary) -> Self {
        self.boundary = boundary;
        self
    }

    pub fn levels(&self) -> usize {
        self.schemes.len()
    }
}

/// Predicted `(vertices, faces)` after all levels, saturating instead of overflowing.
pub fn predict_counts(mesh: &HalfEdgeMesh, options: &Options) -> (u64, u64) {
    let (mut v, mut e, mut h, mut f) = (
        mesh.num_vertices() as u64,
        mesh.num_edges() as u64,
        mesh.num_half_edges() as u64,
        mesh.num_cells() as u64,
    );
    for scheme in &options.schemes {
        match scheme {
            Scheme::CatmullClark => {
                let [v2, e2, h2, f2] = pqq::child_counts(v, e, h, f);
                (v, e, h, f) = (v2, e2, h2, f2);
            }
        }
        if f > u64::MAX / 16 {
            break;
        }
    }
    (v, f)
}

/// Subdivides `mesh` as `options` says. The input is only read.
pub fn subdivide(mesh: &PolyMesh, options: &Options) -> Result<PolyMesh> {
    let base = HalfEdgeMesh::from_poly(mesh)?;
    subdivide_mesh(base, options)
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
    for (level, scheme) in options.schemes.iter().enumerate() {
        let last = level + 1 == levels;
        match scheme {
            Scheme::CatmullClark => {
                let rules = CatmullClark {
                    boundary: options.boundary,
                };
                let count = pqq::num_child_vertices(&mesh);
                if last {
                    // Written straight into the output array: no copy of the largest buffer.
                    let mut positions = vec![0.0f32; 3 * count];
                    pqq::refine_points(&mesh, &rules, positions.as_chunks_mut::<3>().0);
                    let indices = pqq::child_face_indices(&mesh);
                    let face_sizes = vec![4; mesh.num_half_edges()];
                    return Ok(PolyMesh {
                        positions,
                        indices,
                        face_sizes,
                    });
                }
                let mut positions = vec![[0.0f32; 3]; count];
                pqq::refine_points(&mesh, &rules, &mut positions);
                mesh = pqq::child_mesh(&mesh, positions);
            }
        }
    }
    Ok(mesh.to_poly())
}
