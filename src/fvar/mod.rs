//! Face-varying channels (UVs split at seams): the value topology of each level and the
//! interpolation of its values, as OpenSubdiv 3 defines them (`Vtr::FVarLevel`,
//! `Vtr::FVarRefinement`, `Far::PrimvarRefiner::InterpolateFaceVarying`), read from its sources
//! and written anew over our half-edge levels.
//!
//! # Values and seams
//!
//! A face-varying channel gives each face corner a value index, so a vertex may carry several
//! values ("siblings"). An edge whose faces disagree on the value at either end is
//! **discontinuous** (a seam): the channel has its own boundary there while the surface stays
//! smooth across it. A vertex **mismatches** when the channel's neighbourhood differs from the
//! surface's: a seam touches it, or a boundary rule of the mode applies to it (below). A vertex
//! that matches has one value, and that value takes exactly the surface's weights
//! ([`crate::rules`]), with each neighbour read through the corner it is seen from.
//!
//! # The modes ([`FVarLinear`])
//!
//! Each value of a mismatched vertex covers a *span*: a run of consecutive faces around the
//! vertex with that value, bounded by seams or boundary edges. A value is either a **corner**
//! (it stays) or a **crease** (`3/4 v + 1/8 (a + b)`, `a` and `b` across the span's two
//! bounding edges). It is a corner when
//!
//! - the mode is `boundaries` or `all` (every boundary value is linear), the vertex is
//!   infinitely sharp or non-manifold, or, under `corners-plus1`/`corners-plus2`, it has more
//!   than two values; darts (one value, one seam ending here) too under `corners-plus2`,
//!   `boundaries` and `all`;
//! - under `corners-plus1`/`corners-plus2` with two values, either span holds an infinitely
//!   sharp edge or a seam, or (`corners-plus2`) is a single face: then both are corners;
//! - its span holds an infinitely sharp edge, is a single face (every mode but `none`), or is
//!   not one run of faces (a value met twice around the vertex).
//!
//! A value whose span holds semi-sharp edges, or whose vertex is semi-sharp, is a corner until
//! that sharpness has decayed, then a crease; at the level where it changes, it blends the two
//! by OpenSubdiv's fractional weight of the edges inside its span. Under
//! `corners-plus1`/`corners-plus2`, when only one of two values has such edges, the other
//! follows its sharpness ("dependent sharpness"). A mesh boundary vertex with one face is a
//! corner unless the mode is `none` or the surface's own boundary rule makes it one already
//! (`edge-and-corner`).
//!
//! # Levels
//!
//! The first level's topology is analysed from the indices (`FVarLevel::base`); refined
//! levels inherit it (`FVarLevel::child_topology`): each value of an old vertex has one child
//! value, a face point has one, and the edge point of a seam one per face of the edge (each the
//! midpoint of that side's values); a child keeps its parent value's tag, halves of a seam are
//! seams, and inner edges are not. `all` and the bilinear and midpoint schemes interpolate every
//! value linearly (face points are centroids, edge points midpoints, old values stay).

mod doo_sabin;
mod interpolate;
mod siblings;
mod sqrt3;
mod topology;

pub use interpolate::{interpolate, MixedRules, PrimalRules, ValueRules};
pub use topology::{FVarLevel, LevelSharpness, SeamCorners, Split};

use crate::options::FVarLinear;

/// The value tag bits (OpenSubdiv's `FVarLevel::ValueTag`, the members interpolation reads).
pub(crate) mod tag {
    /// The value's neighbourhood differs from the surface's: it follows the face-varying rules.
    pub const MISMATCH: u8 = 1;
    /// A crease value (`3/4 v + 1/8 (a + b)`); without it a mismatched value is a corner.
    pub const CREASE: u8 = 2;
    /// A corner until its span's semi-sharp edges (or its vertex) decay, then a crease.
    pub const SEMI_SHARP: u8 = 4;
    /// Semi-sharp because the vertex's other value is.
    pub const DEP_SHARP: u8 = 8;
}

/// The edge tag bits (OpenSubdiv's `FVarLevel::ETag`).
pub(crate) mod edge_tag {
    /// A seam: the edge's faces disagree on the value at an end.
    pub const MISMATCH: u8 = 1;
    /// Linear: the edge point's values are corners at the next level.
    pub const LINEAR: u8 = 2;
}

/// What a mode decides, as OpenSubdiv's `FVarLevel::completeTopologyFromFaceValues` reads it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ModeRules {
    /// `all`: every value is interpolated linearly.
    pub linear: bool,
    /// `boundaries` and `all`: every boundary value is a corner.
    pub linear_boundaries: bool,
    /// `corners-plus1` and `corners-plus2`: one of two values may sharpen the other.
    pub dependent_sharpness: bool,
    /// Every mode but `none`: a value of one face is a corner.
    pub corners_sharp: bool,
    /// `corners-plus2`: a value of one face makes both values corners.
    pub sharpen_both_if_one_corner: bool,
    /// `corners-plus2`, `boundaries`, `all`: a dart's value is a corner.
    pub sharpen_darts: bool,
}

impl ModeRules {
    pub fn new(mode: FVarLinear) -> Self {
        let linear_boundaries = matches!(mode, FVarLinear::Boundaries | FVarLinear::All);
        let plus2 = mode == FVarLinear::CornersPlus2;
        ModeRules {
            linear: mode == FVarLinear::All,
            linear_boundaries,
            dependent_sharpness: matches!(
                mode,
                FVarLinear::CornersPlus1 | FVarLinear::CornersPlus2
            ),
            corners_sharp: mode != FVarLinear::None,
            sharpen_both_if_one_corner: plus2,
            sharpen_darts: plus2 || linear_boundaries,
        }
    }

    /// True when a crease value keeps the ends of its crease (every mode whose boundaries are
    /// smooth).
    pub fn smooth_boundaries(&self) -> bool {
        !self.linear_boundaries
    }
}

use crate::mesh::HalfEdgeMesh;
use crate::primvar::Channel;
use std::borrow::Cow;

/// A face-varying channel between levels (several channels with the same indices travel as
/// one, side by side).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FVarChannel<'a> {
    level: FVarLevel,
    /// False until a primal level analysed the topology: the level's values are then values as
    /// given and its corner values indices as given.
    pub analysed: bool,
    /// The values and indices as given, until a level reads them (`level` is then without
    /// them): borrowed from the caller's channel where they can be, since the first level
    /// reads them only (a copy was 24 MB of the textured 1M-quad torus's uv).
    given: Option<Given<'a>>,
}

/// A channel's values and indices as given.
type Given<'a> = (Cow<'a, [f32]>, Cow<'a, [u32]>);

/// A channel's next level between [`FVarChannel::begin`] and [`FVarChannel::finish`]: its
/// topology, and the parent's cells next to seams (`FVarLevel::cells_near_seams`), which both
/// steps read.
#[derive(Debug)]
pub struct FVarStep {
    child: FVarLevel,
    near_seams: Vec<u32>,
}

impl FVarStep {
    /// Number of values of the next level.
    pub fn num_values(&self) -> usize {
        self.child.num_values()
    }
}

impl<'a> FVarChannel<'a> {
    /// A channel of `width` floats per value, one index per face corner.
    pub fn new(width: usize, values: Cow<'a, [f32]>, indices: Cow<'a, [u32]>) -> Self {
        let level = FVarLevel { width, ..FVarLevel::default() };
        FVarChannel { level, analysed: false, given: Some((values, indices)) }
    }

    /// The channel's level, holding the values and indices as given if no level read them.
    pub fn level_mut(&mut self) -> &mut FVarLevel {
        if let Some((values, indices)) = self.given.take() {
            self.level.values = values.into_owned();
            self.level.corner_values = indices.into_owned();
        }
        &mut self.level
    }

    /// [`FVarChannel::level_mut`], taken out of the channel.
    pub fn into_level(mut self) -> FVarLevel {
        self.level_mut();
        self.level
    }

    /// Refines the channel with one level of `split` of `mesh` with `rules` (linear ones when
    /// `linear`), whose sharpness is `sharp`.
    pub fn refine(
        &mut self,
        mesh: &HalfEdgeMesh,
        split: Split,
        rules: &impl ValueRules,
        linear: bool,
        sharp: &LevelSharpness,
        mode: FVarLinear,
    ) {
        let step = self.begin(mesh, split, sharp, mode, false);
        self.finish(mesh, split, rules, step, linear, sharp, mode, None);
    }

    /// True when the values that match the surface take the surface's own rules (see
    /// [`FVarChannel::vertex_values`]): every mode but `all`, on a scheme that is not linear.
    pub fn follows_surface(linear: bool, mode: FVarLinear) -> bool {
        !linear && !ModeRules::new(mode).linear
    }

    /// The first step of [`FVarChannel::refine`]: the next level's topology, without values.
    /// `implicit` when the next level is a result whose faces stay implicit (a last quad split
    /// without holes): its corner values are then left implicit too ([`SeamCorners`]).
    pub fn begin(
        &mut self,
        mesh: &HalfEdgeMesh,
        split: Split,
        sharp: &LevelSharpness,
        mode: FVarLinear,
        implicit: bool,
    ) -> FVarStep {
        let mode = ModeRules::new(mode);
        if !self.analysed {
            let level = std::mem::take(&mut self.level);
            let (values, indices) = match &self.given {
                Some((values, indices)) => (&values[..], &indices[..]),
                None => (&level.values[..], &level.corner_values[..]),
            };
            self.level = FVarLevel::base(mesh, values, level.width, indices, sharp, mode);
            self.given = None;
            self.analysed = true;
        }
        let near_seams = self.level.cells_near_seams(mesh);
        let child = self.level.child_topology(mesh, split, sharp, mode, &near_seams, implicit);
        FVarStep { child, near_seams }
    }

    /// The values numbered as the vertices of `mesh` (each vertex's first value), as one
    /// vertex-varying channel: where no seam is near, a value's rule reads only these, so the
    /// host can refine them in its own walk of the rules (after [`FVarChannel::begin`]).
    pub fn vertex_values(&self, mesh: &HalfEdgeMesh) -> Channel<'_> {
        let width = self.level.width;
        let end = (mesh.num_vertices() * width).min(self.level.values.len());
        Channel { width, values: Cow::Borrowed(&self.level.values[..end]) }
    }

    /// The second step of [`FVarChannel::refine`]: the values of `step`'s child. With `joint`, the
    /// values numbered as `child`'s vertices that the host refined from
    /// [`FVarChannel::vertex_values`] with the surface's rules: only the values near seams and
    /// the mismatched ones are computed here.
    #[allow(clippy::too_many_arguments)]
    pub fn finish(
        &mut self,
        mesh: &HalfEdgeMesh,
        split: Split,
        rules: &impl ValueRules,
        step: FVarStep,
        linear: bool,
        sharp: &LevelSharpness,
        mode: FVarLinear,
        joint: Option<Vec<f32>>,
    ) {
        let linear = linear || ModeRules::new(mode).linear;
        let FVarStep { mut child, near_seams } = step;
        let parent = &self.level;
        interpolate(mesh, split, rules, parent, &mut child, linear, sharp, &near_seams, joint);
        self.level = child;
    }

    /// Keeps the corners of the faces `keep` says, faces of `size` corners.
    pub fn keep_faces(&mut self, size: usize, keep: impl Fn(usize) -> bool) {
        crate::mesh::retain_faces(&mut self.level_mut().corner_values, size, keep);
    }
}
