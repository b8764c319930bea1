//! The public vocabulary of a call: the schemes, the options every scheme shares (what happens
//! at the boundary and how semi-sharp creases decay, as OpenSubdiv's `Sdc::Options`), and the
//! guards. A leaf module: the rules, the hosts and the driver all read it, and it reads none of
//! them.

use crate::error::{Error, Result};
use std::fmt;
use std::str::FromStr;

/// A subdivision scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
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

    /// True for the schemes that follow [`crate::Tags`] (creases, corners, holes): Catmull-Clark and
    /// Loop use them, bilinear and midpoint carry them to the next level of a list.
    pub fn supports_tags(self) -> bool {
        matches!(self, Scheme::CatmullClark | Scheme::Loop | Scheme::Bilinear | Scheme::Midpoint)
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

impl FromStr for Scheme {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        parse_name("scheme", s, Scheme::ALL, Scheme::name)
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The default memory guard: the most output faces one call may produce. 16 M quads with their
/// positions, indices and a triangle list take about 1 GiB, which fits a wasm32 memory next to
/// the level before it.
pub const DEFAULT_MAX_FACES: u64 = 1 << 24;

/// The default byte guard: 1 GiB for the result's arrays (positions, indices, face sizes and a
/// triangle list), which leaves room in a 4 GiB wasm32 memory for the level it is made from.
pub const DEFAULT_MAX_BYTES: u64 = 1 << 30;

/// The most levels one call accepts: beyond any guard for a mesh with faces, and it bounds the
/// work on meshes without any.
pub const MAX_LEVELS: usize = 32;

/// How to subdivide.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The scheme of each level, first level first. Its length is the number of levels.
    pub schemes: Vec<Scheme>,
    pub boundary: Boundary,
    /// Refuse, before any work, when the last level would have more faces than this.
    pub max_faces: u64,
    /// Refuse, before any work, when the result's arrays would take more bytes than this
    /// (see [`crate::predict::Prediction::bytes`]).
    pub max_bytes: u64,
    /// Where face-varying channels (UVs) are linear rather than smooth.
    pub fvar_linear: FVarLinear,
    /// Move the last level's points, vertex-varying and face-varying values to the limit
    /// surface (OpenSubdiv's `PrimvarRefiner::Limit` and `LimitFaceVarying`). Defined when the
    /// last level is Catmull-Clark, Loop or Quad/Triangle (whose points where quads meet
    /// triangles stay, see [`crate::rules::limit::LimitRules::scheme`]); bilinear and midpoint
    /// points are already on their limit and stay.
    pub limit: bool,
    /// Give unit vertex normals: the limit normals after Catmull-Clark, Loop and Quad/Triangle
    /// (the points stay unless `limit`), normals from the faces after any other scheme (see
    /// [`crate::refined::Refined::normals`]).
    pub normals: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            schemes: vec![Scheme::CatmullClark],
            boundary: Boundary::default(),
            max_faces: DEFAULT_MAX_FACES,
            max_bytes: DEFAULT_MAX_BYTES,
            fvar_linear: FVarLinear::default(),
            limit: false,
            normals: false,
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

    pub fn with_fvar_linear(mut self, fvar_linear: FVarLinear) -> Self {
        self.fvar_linear = fvar_linear;
        self
    }

    pub fn levels(&self) -> usize {
        self.schemes.len()
    }
}

/// What happens on boundary edges and vertices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
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
    /// No boundary interpolation. Catmull-Clark and Loop do as OpenSubdiv's `VTX_BOUNDARY_NONE`
    /// (OBJ `interpolateboundary 0`): the faces at a vertex with a boundary edge that is not
    /// tagged infinitely sharp become holes, so they and their descendants are left out of the
    /// result (their vertices stay, placed as under `EdgeOnly`). Doo-Sabin leaves out the faces of boundary edges and vertices, so the
    /// surface retracts from the boundary, as CGAL's Doo-Sabin does. Bilinear and midpoint alone
    /// ignore it (before a Catmull-Clark or Loop level of a list they carry its holes);
    /// Quad/Triangle and √3 refuse it.
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

/// Where a face-varying channel is interpolated linearly instead of smoothly: OpenSubdiv's
/// `Sdc::Options::FVarLinearInterpolation`, named after USD's `faceVaryingLinearInterpolation`
/// tokens. A face-varying channel has its own boundary wherever its values are split (a seam),
/// besides the mesh's boundary; these modes say how sharp those boundaries are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FVarLinear {
    /// Smooth everywhere, seams and corners included (`FVAR_LINEAR_NONE`).
    None,
    /// Sharp corners (a value of one face) only (`FVAR_LINEAR_CORNERS_ONLY`).
    CornersOnly,
    /// Sharp corners, and both values where a seam meets another seam, a sharp edge or a third
    /// value (`FVAR_LINEAR_CORNERS_PLUS1`; USD's default, and ours).
    #[default]
    CornersPlus1,
    /// As `corners-plus1`, and sharp darts and both values when either is a corner
    /// (`FVAR_LINEAR_CORNERS_PLUS2`).
    CornersPlus2,
    /// Linear along every boundary and seam, smooth inside (`FVAR_LINEAR_BOUNDARIES`).
    Boundaries,
    /// Linear everywhere: the values of the bilinear scheme (`FVAR_LINEAR_ALL`).
    All,
}

impl FVarLinear {
    pub const ALL: &'static [FVarLinear] = &[
        FVarLinear::None,
        FVarLinear::CornersOnly,
        FVarLinear::CornersPlus1,
        FVarLinear::CornersPlus2,
        FVarLinear::Boundaries,
        FVarLinear::All,
    ];

    pub fn name(self) -> &'static str {
        match self {
            FVarLinear::None => "none",
            FVarLinear::CornersOnly => "corners-only",
            FVarLinear::CornersPlus1 => "corners-plus1",
            FVarLinear::CornersPlus2 => "corners-plus2",
            FVarLinear::Boundaries => "boundaries",
            FVarLinear::All => "all",
        }
    }
}

impl FromStr for FVarLinear {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        parse_name("face-varying linear mode", s, FVarLinear::ALL, FVarLinear::name)
    }
}

impl fmt::Display for FVarLinear {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How semi-sharp creases lose sharpness from one level to the next.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CreaseMethod {
    /// Every level subtracts 1 (OpenSubdiv `CREASE_UNIFORM`; OBJ `creasemethod normal`).
    #[default]
    Uniform,
    /// Each half of an edge takes 3/4 of its own sharpness and 1/4 of the mean of the other
    /// semi-sharp edges at its end vertex, then subtracts 1, so a crease of varying sharpness
    /// decays smoothly along its length (OpenSubdiv `CREASE_CHAIKIN`; OBJ `creasemethod chaikin`).
    Chaikin,
}

impl CreaseMethod {
    pub const ALL: &'static [CreaseMethod] = &[CreaseMethod::Uniform, CreaseMethod::Chaikin];

    pub fn name(self) -> &'static str {
        match self {
            CreaseMethod::Uniform => "uniform",
            CreaseMethod::Chaikin => "chaikin",
        }
    }
}

impl FromStr for CreaseMethod {
    type Err = Error;
    /// `uniform` (or OpenSubdiv's `normal`) and `chaikin`.
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "uniform" | "normal" => Ok(CreaseMethod::Uniform),
            "chaikin" => Ok(CreaseMethod::Chaikin),
            other => Err(Error::InvalidOption(format!(
                "unknown crease method '{other}'; use 'uniform' (OpenSubdiv's 'normal') or 'chaikin'"
            ))),
        }
    }
}

impl fmt::Display for CreaseMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

pub(crate) fn parse_name<T: Copy>(
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

impl FromStr for Boundary {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        parse_name("boundary", s, Boundary::ALL, Boundary::name)
    }
}

impl fmt::Display for Boundary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
