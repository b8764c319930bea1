//! The public vocabulary: schemes, boundary rules, options, and [`subdivide`].

use crate::error::{Error, Result};
use crate::mesh::{chunked, HalfEdgeMesh, PolyMesh};
use crate::options::parse_name;
pub use crate::options::Boundary;
use crate::refine::dqq::{self, DualBoundary};
use crate::refine::{pqq, ptq, quad_tri, sqrt3};
use crate::rules::Sqrt3;
use crate::rules::{
    Bilinear, CatmullClark, CreasedCatmullClark, CreasedLoop, DooSabin, LevelTags, Loop, Midpoint,
    QuadSplitRules, QuadTriangle, TriSplitRules,
};
use crate::tags::Tags;
use std::borrow::Cow;
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

    /// True for the schemes that follow [`Tags`] (creases, corners, holes): Catmull-Clark and
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
    /// (see [`Prediction::bytes`]).
    pub max_bytes: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            schemes: vec![Scheme::CatmullClark],
            boundary: Boundary::default(),
            max_faces: DEFAULT_MAX_FACES,
            max_bytes: DEFAULT_MAX_BYTES,
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

/// The predicted size after all levels of `options`, from the counts formulas of each level.
pub fn predict(mesh: &HalfEdgeMesh, options: &Options) -> Prediction {
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
                // Upper bound: T triangles make 4T faces and the other faces H - 3T, so H + T
                // <= H + F faces, and a centroid for each non-triangle, at most F.
                [v + e + f, 2 * e + h, 4 * h, h + f]
            }
        };
        if counts.iter().any(|&c| c > u64::MAX / 64) {
            // Saturate: a level grows every count less than 64-fold, so nothing overflowed yet,
            // and no guard lets this through.
            return Prediction { vertices: u64::MAX, faces: u64::MAX, corners: u64::MAX };
        }
    }
    Prediction { vertices: counts[0], faces: counts[3], corners: counts[2] }
}

/// The predicted size of a result, before any work: exact for the primal schemes, an upper
/// bound for Doo-Sabin, √3 and Quad/Triangle; every count is `u64::MAX` when it would not fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Prediction {
    pub vertices: u64,
    pub faces: u64,
    /// Face corners: the length of the index array.
    pub corners: u64,
}

impl Prediction {
    /// Bytes of the result's arrays as the JS API returns them: 12 per vertex, 4 per index,
    /// 4 per face size and 12 per triangle of the fan triangulation (corners - 2 per face).
    pub fn bytes(&self) -> u64 {
        let triangles = self.corners.saturating_sub(2 * self.faces);
        12u64
            .saturating_mul(self.vertices)
            .saturating_add(4u64.saturating_mul(self.corners))
            .saturating_add(4u64.saturating_mul(self.faces))
            .saturating_add(12u64.saturating_mul(triangles))
    }
}

/// Refuses, before any allocation, a call whose result would break a guard of `options`.
pub fn check_guards(mesh: &HalfEdgeMesh, options: &Options) -> Result<()> {
    let levels = options.levels();
    if levels > MAX_LEVELS {
        return Err(Error::InvalidOption(format!(
            "{levels} levels is more than the {MAX_LEVELS} subsurf accepts; every level multiplies the faces by about four"
        )));
    }
    let predicted = predict(mesh, options);
    if predicted.faces == u64::MAX {
        return Err(Error::TooLarge(format!(
            "{levels} level(s) would make more faces than a 64-bit count holds, beyond any maxFaces (CLI --max-faces); use fewer levels"
        )));
    }
    if predicted.faces > options.max_faces {
        return Err(Error::TooLarge(format!(
            "{levels} level(s) would make {} faces, more than the limit of {}; use fewer levels or raise maxFaces (CLI --max-faces)",
            predicted.faces, options.max_faces
        )));
    }
    let bytes = predicted.bytes();
    if bytes > options.max_bytes {
        return Err(Error::TooLarge(format!(
            "{levels} level(s) would make a result of {bytes} bytes (positions, indices, face sizes and triangles), more than the limit of {} bytes; use fewer levels or raise maxBytes (CLI --max-bytes)",
            options.max_bytes
        )));
    }
    Ok(())
}

/// Predicted `(vertices, faces)` after all levels; see [`predict`].
pub fn predict_counts(mesh: &HalfEdgeMesh, options: &Options) -> (u64, u64) {
    let p = predict(mesh, options);
    (p.vertices, p.faces)
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
    subdivide_with_tags(mesh, options, &Tags::default())
}

/// Subdivides `mesh` with creases, corners and holes (see [`Tags`]): Catmull-Clark and Loop use
/// them as OpenSubdiv 3 does, bilinear and midpoint carry them to the next level, and Doo-Sabin,
/// Quad/Triangle and √3 refuse non-trivial tags. Invalid tags are an [`Error::InvalidTag`].
pub fn subdivide_with_tags(mesh: &PolyMesh, options: &Options, tags: &Tags) -> Result<PolyMesh> {
    subdivide_refined(mesh, options, tags).map(Refined::into_poly)
}

/// [`subdivide_with_tags`], returning the result as a [`Refined`], whose arrays can be copied out
/// piece by piece.
pub fn subdivide_refined(
    mesh: &PolyMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'static>> {
    let base = HalfEdgeMesh::from_poly(mesh)?;
    subdivide_mesh_refined(base, options, tags)
}

/// A subdivision result. After an untagged quad split (Catmull-Clark, bilinear) its face list is
/// implicit: it keeps the last level's parent mesh, from which the faces follow by index
/// arithmetic ([`pqq`]), so that a caller can copy indices, face sizes and triangles out in
/// cache-sized pieces without the arrays ever being stored whole (the wasm bindings do). The
/// pieces, joined, are the arrays of [`Refined::into_poly`].
///
/// The lifetime is the base mesh's when [`subdivide_mesh_borrowed`] made the result with a single
/// quad split (the base is then the parent its faces follow from); `'static` otherwise.
pub struct Refined<'a>(Form<'a>);

enum Form<'a> {
    Poly(PolyMesh),
    /// The last level's positions and the mesh it refined.
    Quads {
        positions: Vec<f32>,
        parent: Box<Cow<'a, HalfEdgeMesh>>,
    },
}

impl Refined<'_> {
    pub fn positions(&self) -> &[f32] {
        match &self.0 {
            Form::Poly(poly) => &poly.positions,
            Form::Quads { positions, .. } => positions,
        }
    }

    pub fn num_faces(&self) -> usize {
        match &self.0 {
            Form::Poly(poly) => poly.num_faces(),
            Form::Quads { parent, .. } => parent.num_half_edges(),
        }
    }

    /// Length of the face index list.
    pub fn num_indices(&self) -> usize {
        match &self.0 {
            Form::Poly(poly) => poly.indices.len(),
            Form::Quads { parent, .. } => 4 * parent.num_half_edges(),
        }
    }

    /// Length of the fan triangulation ([`PolyMesh::triangles`]).
    pub fn num_triangle_indices(&self) -> usize {
        match &self.0 {
            Form::Poly(poly) => poly.num_triangle_indices(),
            Form::Quads { parent, .. } => 6 * parent.num_half_edges(),
        }
    }

    /// The face index list to `faces` and the fan triangulation ([`PolyMesh::triangles`]) to
    /// `triangles`, each in consecutive pieces (made in one pass where the faces are implicit).
    pub fn index_and_triangle_chunks(
        &self,
        mut faces: impl FnMut(&[u32]),
        triangles: impl FnMut(&[u32]),
    ) {
        match &self.0 {
            Form::Poly(poly) => {
                faces(&poly.indices);
                poly.triangle_chunks(triangles);
            }
            Form::Quads { parent, .. } => {
                pqq::child_face_and_triangle_chunks(parent, faces, triangles)
            }
        }
    }

    /// The size of every face, when all faces are known to have one size without a scan (the
    /// implicit quads of a quad split), so that a caller can fill the array instead of copying it.
    pub fn uniform_face_size(&self) -> Option<u32> {
        match &self.0 {
            Form::Poly(_) => None,
            Form::Quads { .. } => Some(4),
        }
    }

    /// The face sizes, in consecutive pieces.
    pub fn face_size_chunks(&self, mut sink: impl FnMut(&[u32])) {
        match &self.0 {
            Form::Poly(poly) => sink(&poly.face_sizes),
            Form::Quads { parent, .. } => chunked(parent.num_half_edges(), |_| [4], sink),
        }
    }

    /// The flat arrays.
    pub fn into_poly(self) -> PolyMesh {
        match self.0 {
            Form::Poly(poly) => poly,
            Form::Quads { positions, parent } => PolyMesh {
                positions,
                indices: pqq::child_face_indices(&parent),
                face_sizes: vec![4; parent.num_half_edges()],
            },
        }
    }
}

/// Refuses a scheme on a mesh it is not defined on, naming the first offending face.
fn check_scheme(
    mesh: &HalfEdgeMesh,
    scheme: Scheme,
    boundary: Boundary,
    level: usize,
) -> Result<()> {
    let at = |what: String| Error::Unsupported(format!("level {}: {what}", level + 1));
    // An all-triangle mesh says so (`cell_size`); only others are scanned for the culprit.
    if scheme.triangles_only() && mesh.cell_size != 3 {
        let size = |c: u32| mesh.cell_range(c as usize).len();
        if let Some(c) = mesh.cell_indices().find(|&c| size(c) != 3) {
            let n = size(c);
            let when = if level == 0 { "the input" } else { "the previous level's result" };
            return Err(at(format!(
                "{scheme} is defined on triangles only, but face {c} of {when} has {n} vertices; use 'quad-triangle' for meshes with quads, or triangulate first"
            )));
        }
    }
    if boundary == Boundary::None && matches!(scheme, Scheme::QuadTriangle | Scheme::Sqrt3) {
        return Err(at(format!(
            "boundary 'none' is defined for catmull-clark, loop and doo-sabin; use 'edge-and-corner', 'edge-only', 'fixed' or 'average' with {scheme}"
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

fn tags_unsupported(scheme: Scheme, level: usize) -> Error {
    Error::Unsupported(format!(
        "level {}: {scheme} does not support creases/corners/holes; remove them or use catmull-clark or loop",
        level + 1
    ))
}

/// Subdivides an already built half-edge mesh.
pub fn subdivide_mesh(base: HalfEdgeMesh, options: &Options) -> Result<PolyMesh> {
    subdivide_mesh_with_tags(base, options, &Tags::default())
}

/// Subdivides an already built half-edge mesh with tags; see [`subdivide_with_tags`].
///
/// Without tags, on a 2-manifold mesh (no non-manifold edge or vertex) and with a boundary other
/// than `none`, every level takes the plain path (no sharpness data at all). Otherwise the levels that
/// follow tags carry one sharpness per edge and vertex and a hole flag per face from level to
/// level (see [`crate::rules::crease`]).
pub fn subdivide_mesh_with_tags(
    base: HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<PolyMesh> {
    subdivide_mesh_refined(base, options, tags).map(Refined::into_poly)
}

/// [`subdivide_mesh_with_tags`], returning a [`Refined`].
pub fn subdivide_mesh_refined(
    base: HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'static>> {
    refine_levels(Cow::Owned(base), options, tags)
}

/// [`subdivide_mesh_refined`] that leaves `base` to the caller, to subdivide again with other
/// options or, after [`HalfEdgeMesh::set_positions`], other positions: the build from flat
/// arrays (OpenSubdiv's `TopologyRefinerFactory::Create`) is then paid once.
pub fn subdivide_mesh_borrowed<'a>(
    base: &'a HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'a>> {
    refine_levels(Cow::Borrowed(base), options, tags)
}

fn refine_levels<'a>(
    base: Cow<'a, HalfEdgeMesh>,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'a>> {
    check_guards(&base, options)?;
    tags.validate(base.num_vertices(), base.num_cells())?;
    let crease_edges = crate::rules::crease::crease_edges(&base, tags)?;
    let user_tags = !tags.is_trivial();
    if user_tags {
        if let Some((level, &scheme)) =
            options.schemes.iter().enumerate().find(|(_, s)| !s.supports_tags())
        {
            return Err(tags_unsupported(scheme, level));
        }
    }
    let boundary = options.boundary;
    let mut mesh = base;
    if options.schemes.is_empty() {
        if tags.holes.is_empty() {
            return Ok(Refined(Form::Poly(mesh.to_poly())));
        }
        let level_tags = LevelTags::base_with_edges(&mesh, tags, &crease_edges, false);
        let mut poly = mesh.to_poly();
        let sizes = std::mem::take(&mut poly.face_sizes);
        let indices = std::mem::take(&mut poly.indices);
        let (mut start, mut kept) = (0usize, Vec::with_capacity(indices.len()));
        for (f, &n) in sizes.iter().enumerate() {
            if !level_tags.is_hole(f as u32) {
                kept.extend_from_slice(&indices[start..start + n as usize]);
                poly.face_sizes.push(n);
            }
            start += n as usize;
        }
        poly.indices = kept;
        return Ok(Refined(Form::Poly(poly)));
    }
    let mut level_tags: Option<LevelTags> = None;
    let levels = options.schemes.len();
    for (level, &scheme) in options.schemes.iter().enumerate() {
        check_scheme(&mesh, scheme, boundary, level)?;
        let last = level + 1 == levels;
        if level_tags.is_none() && scheme.supports_tags() {
            // The tagged path: for the user's tags (base level), and for what only the crease
            // rules handle: boundary 'none', non-manifold input, smooth triangles. Decided for
            // the run of levels that carry tags from here on (bilinear and midpoint carry them
            // to a later Catmull-Clark or Loop level), on this level's mesh.
            let run = options.schemes[level..].iter().take_while(|s| s.supports_tags());
            let (mut creased, mut catmull_clark) = (false, false);
            for &s in run {
                creased |= matches!(s, Scheme::CatmullClark | Scheme::Loop);
                catmull_clark |= s == Scheme::CatmullClark;
            }
            let needed = (level == 0 && user_tags)
                || (creased
                    && (boundary == Boundary::None
                        || mesh.is_non_manifold()
                        || (tags.smooth_triangles && catmull_clark)));
            if needed {
                // The user's creases, corners and holes belong to the base mesh; a later level
                // (after a scheme that does not carry tags) starts from the options only.
                let options_only = Tags {
                    crease_method: tags.crease_method,
                    smooth_triangles: tags.smooth_triangles,
                    ..Tags::default()
                };
                let (level_input, edges) =
                    if level == 0 { (tags, &crease_edges[..]) } else { (&options_only, &[][..]) };
                let holes_at_boundary = boundary == Boundary::None && creased;
                level_tags =
                    Some(LevelTags::base_with_edges(&mesh, level_input, edges, holes_at_boundary));
            }
        }
        if !scheme.supports_tags() {
            if level_tags.as_ref().is_some_and(|t| t.has_holes()) {
                return Err(tags_unsupported(scheme, level));
            }
            level_tags = None;
        }
        let (child, next_tags) = match (scheme, &level_tags) {
            (Scheme::CatmullClark, Some(t)) => {
                quad_split_tagged(&mesh, &CreasedCatmullClark { boundary, tags: t }, t, last)
            }
            (Scheme::CatmullClark, None) => {
                (quad_split(mesh, &CatmullClark { boundary }, last), None)
            }
            (Scheme::Bilinear, Some(t)) => quad_split_tagged(&mesh, &Bilinear, t, last),
            (Scheme::Bilinear, None) => (quad_split(mesh, &Bilinear, last), None),
            (Scheme::Loop, Some(t)) => {
                tri_split_tagged(&mesh, &CreasedLoop { boundary, tags: t }, t, last)
            }
            (Scheme::Loop, None) => (tri_split(&mesh, &Loop { boundary }, last), None),
            (Scheme::Midpoint, Some(t)) => tri_split_tagged(&mesh, &Midpoint, t, last),
            (Scheme::Midpoint, None) => (tri_split(&mesh, &Midpoint, last), None),
            (Scheme::QuadTriangle, _) => {
                (Level::Poly(quad_tri::refine(&mesh, &QuadTriangle { boundary })), None)
            }
            (Scheme::DooSabin, _) => {
                let mode = if boundary == Boundary::None {
                    DualBoundary::Retract
                } else {
                    DualBoundary::Chaikin
                };
                if last || mesh.num_cells() == 0 {
                    (Level::Poly(dqq::refine(&mesh, &DooSabin, mode)), None)
                } else {
                    (Level::Mesh(dqq::child_mesh(&mesh, &DooSabin, mode)?), None)
                }
            }
            (Scheme::Sqrt3, _) => {
                let refine_boundary = sqrt3_refines_boundary(&options.schemes, level);
                let rules = Sqrt3 { boundary };
                if last {
                    (Level::Poly(sqrt3::refine(&mesh, &rules, refine_boundary)), None)
                } else {
                    (Level::Mesh(sqrt3::child_mesh(&mesh, &rules, refine_boundary)?), None)
                }
            }
        };
        level_tags = next_tags;
        mesh = match child {
            // A mesh without vertices (Doo-Sabin of a mesh without faces) stays empty.
            Level::Poly(poly) if last || poly.positions.is_empty() => {
                return Ok(Refined(Form::Poly(poly)));
            }
            Level::Poly(poly) => Cow::Owned(HalfEdgeMesh::from_poly(&poly)?),
            Level::Mesh(mesh) => Cow::Owned(mesh),
            Level::Quads { positions, parent } => {
                return Ok(Refined(Form::Quads { positions, parent: Box::new(parent) }));
            }
        };
    }
    Ok(Refined(Form::Poly(mesh.to_poly())))
}

/// One level's result: flat arrays, or for the last quad split the positions with the parent
/// mesh (the faces are implicit, see [`Refined`]), or a mesh built by index arithmetic where a
/// host can do that.
enum Level<'a> {
    Poly(PolyMesh),
    Quads { positions: Vec<f32>, parent: Cow<'a, HalfEdgeMesh> },
    Mesh(HalfEdgeMesh),
}

fn quad_split<'a, R: QuadSplitRules>(
    mesh: Cow<'a, HalfEdgeMesh>,
    rules: &R,
    last: bool,
) -> Level<'a> {
    if last {
        let positions = pqq::refine_points(&mesh, rules).into_flattened();
        return Level::Quads { positions, parent: mesh };
    }
    let positions = pqq::refine_points(&mesh, rules);
    Level::Mesh(pqq::child_mesh(&mesh, positions))
}

/// [`quad_split`] with tags: the last level leaves out the children of holes; other levels
/// return the child level's tags too.
fn quad_split_tagged<R: QuadSplitRules>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    tags: &LevelTags,
    last: bool,
) -> (Level<'static>, Option<LevelTags>) {
    if last {
        let positions = pqq::refine_points(mesh, rules).into_flattened();
        let indices = pqq::child_face_indices(mesh);
        // Child cell h comes from parent half-edge h's cell.
        let hole = |f: usize| tags.is_hole(mesh.cell_of(f as u32));
        return (Level::Poly(without_holes(positions, indices, 4, tags.has_holes(), hole)), None);
    }
    let positions = pqq::refine_points(mesh, rules);
    let child = pqq::child_mesh(mesh, positions);
    let child_tags = pqq::child_tags(mesh, &child, tags);
    (Level::Mesh(child), Some(child_tags))
}

fn tri_split<R: TriSplitRules>(mesh: &HalfEdgeMesh, rules: &R, last: bool) -> Level<'static> {
    if last {
        let positions = ptq::refine_points(mesh, rules).into_flattened();
        let indices = ptq::child_face_indices(mesh);
        let face_sizes = vec![3; indices.len() / 3];
        return Level::Poly(PolyMesh { positions, indices, face_sizes });
    }
    let positions = ptq::refine_points(mesh, rules);
    Level::Mesh(ptq::child_mesh(mesh, positions))
}

/// [`tri_split`] with tags: the last level leaves out the children of holes; other levels
/// return the child level's tags too.
fn tri_split_tagged<R: TriSplitRules>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    tags: &LevelTags,
    last: bool,
) -> (Level<'static>, Option<LevelTags>) {
    if last {
        let positions = ptq::refine_points(mesh, rules).into_flattened();
        let indices = ptq::child_face_indices(mesh);
        // Child triangle f comes from parent triangle f / 4.
        let hole = |f: usize| tags.is_hole((f / 4) as u32);
        return (Level::Poly(without_holes(positions, indices, 3, tags.has_holes(), hole)), None);
    }
    let positions = ptq::refine_points(mesh, rules);
    let child = ptq::child_mesh(mesh, positions);
    let child_tags = ptq::child_tags(mesh, &child, tags);
    (Level::Mesh(child), Some(child_tags))
}

/// The output of a last level whose faces all have `size` corners, without the faces `hole`
/// names (when `any` is true).
fn without_holes(
    positions: Vec<f32>,
    mut indices: Vec<u32>,
    size: usize,
    any: bool,
    hole: impl Fn(usize) -> bool,
) -> PolyMesh {
    if any {
        let mut kept = 0usize;
        for f in 0..indices.len() / size {
            if !hole(f) {
                indices.copy_within(f * size..(f + 1) * size, kept * size);
                kept += 1;
            }
        }
        indices.truncate(kept * size);
    }
    let face_sizes = vec![size as u32; indices.len() / size];
    PolyMesh { positions, indices, face_sizes }
}
