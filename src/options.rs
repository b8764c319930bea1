//! The options every scheme shares, apart from the scheme itself: what happens at the boundary
//! and how semi-sharp creases decay (OpenSubdiv's `Sdc::Options`). A leaf module: the rules,
//! the hosts and the public vocabulary all read it, and it reads none of them.

use crate::error::{Error, Result};
use std::fmt;
use std::str::FromStr;

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
