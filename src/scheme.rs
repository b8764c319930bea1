//! The driver: [`subdivide`] and its variants run the levels of a call, each scheme on its host
//! with its rules. The vocabulary lives in [`crate::options`], the sizes in [`crate::predict`],
//! the result in [`crate::refined`]; the names are re-exported here.

use crate::attributes::{self, Attribute, Channels};
use crate::error::{Error, Result};
use crate::fvar::{FVarChannel, LevelSharpness, MixedRules, PrimalRules, Split};
use crate::limit::FirstFaces;
use crate::mesh::{HalfEdgeMesh, PolyMesh};
pub use crate::options::{
    Boundary, FVarLinear, Options, Scheme, DEFAULT_MAX_BYTES, DEFAULT_MAX_FACES, MAX_LEVELS,
};
use crate::predict::sqrt3_refines_boundary;
pub use crate::predict::{
    check_guards, check_guards_with, predict, predict_counts, AttributeSizes, Prediction,
};
use crate::primvar::{pack_points, Channel, Primvar, Rows, Unpacking, MAX_PACKED};
use crate::refine::dqq::{self, DualBoundary};
use crate::refine::{check_distinct_corners, quad_tri, sqrt3, Pqq, PrimalSplit, Ptq};
pub use crate::refined::Refined;
use crate::rules::limit::LimitRules;
use crate::rules::Sqrt3;
use crate::rules::{
    Bilinear, CatmullClark, CreasedCatmullClark, CreasedLoop, DooSabin, LevelTags, Loop, Midpoint,
    QuadTriangle,
};
pub use crate::stencil::StencilTable;
use crate::stencil::Stencils;
use crate::tags::Tags;
use std::borrow::Cow;
use std::fmt::Display;
use std::ops::ControlFlow;

/// Where a call is, told to a progress callback after each level (the last one included, after
/// its limit evaluation if any; a call of 0 levels tells nothing). `faces` and `vertices` are
/// those of the mesh the level made (holes counted until the last level drops them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// Levels done, 1 to `levels`.
    pub level: usize,
    /// Levels of the call.
    pub levels: usize,
    pub faces: usize,
    pub vertices: usize,
}

/// A progress callback: `ControlFlow::Break` stops the call, which then returns
/// [`Error::Cancelled`] (a flag set by another thread, a deadline). A wasm call cannot be
/// interrupted from outside; this is the one place where the caller gets control back.
pub type OnProgress<'p> = dyn FnMut(Progress) -> ControlFlow<()> + 'p;

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
    let checked = match scheme {
        Scheme::DooSabin | Scheme::Sqrt3 => dqq::check(mesh, scheme.name()),
        Scheme::QuadTriangle => check_distinct_corners(mesh, scheme.name()),
        _ => Ok(()),
    };
    checked.map_err(|e| match e {
        Error::Unsupported(message) => at(message),
        other => other,
    })
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
    refine_with_attributes(Cow::Owned(base), &[], options, tags, None)
}

/// [`subdivide_mesh_refined`] that leaves `base` to the caller, to subdivide again with other
/// options or, after [`HalfEdgeMesh::set_positions`], other positions: the build from flat
/// arrays (OpenSubdiv's `TopologyRefinerFactory::Create`) is then paid once.
pub fn subdivide_mesh_borrowed<'a>(
    base: &'a HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'a>> {
    refine_with_attributes(Cow::Borrowed(base), &[], options, tags, None)
}

/// Subdivides `mesh` with its attribute channels (see [`Attribute`]): vertex-varying channels
/// take the same weights as the positions at every level. Returns the flat arrays and the
/// refined channels, in the order given.
pub fn subdivide_with_attributes(
    mesh: &PolyMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<(PolyMesh, Vec<Attribute>)> {
    subdivide_refined_with(mesh, attributes, options, tags).map(Refined::into_parts)
}

/// [`subdivide_with_attributes`], returning a [`Refined`].
pub fn subdivide_refined_with(
    mesh: &PolyMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'static>> {
    let base = HalfEdgeMesh::from_poly(mesh)?;
    refine_with_attributes(Cow::Owned(base), attributes, options, tags, None)
}

/// [`subdivide_mesh_refined`] with attribute channels.
pub fn subdivide_mesh_refined_with(
    base: HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'static>> {
    refine_with_attributes(Cow::Owned(base), attributes, options, tags, None)
}

/// [`subdivide_mesh_borrowed`] with attribute channels.
pub fn subdivide_mesh_borrowed_with<'a>(
    base: &'a HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'a>> {
    refine_with_attributes(Cow::Borrowed(base), attributes, options, tags, None)
}

/// [`subdivide_mesh_refined_with`] that tells `progress` after each level (see [`Progress`]);
/// a `Break` from it stops the call with [`Error::Cancelled`].
pub fn subdivide_mesh_refined_with_progress(
    base: HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    progress: &mut OnProgress<'_>,
) -> Result<Refined<'static>> {
    refine_with_attributes(Cow::Owned(base), attributes, options, tags, Some(progress))
}

/// [`subdivide_mesh_borrowed_with`] that tells `progress` after each level, as
/// [`subdivide_mesh_refined_with_progress`].
pub fn subdivide_mesh_borrowed_with_progress<'a>(
    base: &'a HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    progress: &mut OnProgress<'_>,
) -> Result<Refined<'a>> {
    refine_with_attributes(Cow::Borrowed(base), attributes, options, tags, Some(progress))
}

/// The stencil table of `mesh` under `options` and `tags` (see [`crate::stencil`]): for every
/// output vertex, the control vertices and weights whose weighted sum gives it, with the output
/// topology. The returned mesh is [`subdivide_with_tags`]'s result (its positions those of the
/// control positions at build time); for new control positions `p` (3 floats per vertex of
/// `mesh`), `table.evaluate(&p, 3, &mut refined.positions)` gives the positions `subdivide`
/// would, without refining again, and any vertex-varying channel evaluates the same way.
///
/// Guards as [`subdivide_with_tags`], and the table itself must fit in `options.max_bytes`
/// (4 bytes per output vertex and 8 per entry), else an [`Error::TooLarge`].
pub fn stencil_table(
    mesh: &PolyMesh,
    options: &Options,
    tags: &Tags,
) -> Result<(StencilTable, PolyMesh)> {
    let base = HalfEdgeMesh::from_poly(mesh)?;
    stencil_table_mesh(&base, options, tags)
}

/// [`stencil_table`] of an already built half-edge mesh.
pub fn stencil_table_mesh(
    base: &HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<(StencilTable, PolyMesh)> {
    let StencilBuild { table, mut mesh, .. } = build_stencils(base, &[], options, tags, None)?;
    mesh.positions = vec![0.0; 3 * table.num_stencils()];
    table.evaluate(base.positions.as_flattened(), 3, &mut mesh.positions)?;
    Ok((table, mesh))
}

/// What one stencil build gives: the table (with the tangent weights when `options.normals`
/// and the last level has limit masks), the output faces (`mesh`, its positions left empty: the
/// table gives them for any control positions), and the refined face-varying channels of
/// `attributes` (in their order; vertex-varying ones are left to the table).
pub(crate) struct StencilBuild {
    pub table: StencilTable,
    pub mesh: PolyMesh,
    pub face_varying: Vec<Attribute>,
}

/// The message of a stencil table of `levels` levels and `bytes` bytes past `max_bytes`.
pub(crate) fn table_too_large(levels: impl Display, bytes: impl Display, max_bytes: u64) -> String {
    format!(
        "{levels} level(s) would make a stencil table of {bytes} bytes, more than the limit of {max_bytes} bytes; use fewer levels or raise maxBytes (CLI --max-bytes)"
    )
}

/// Runs the levels of `options` once with stencils as the vertex-varying data (see
/// [`crate::stencil`]) and the face-varying channels of `attributes` alongside. With the limit,
/// the rows of the vertices that `made_elsewhere` marks (see [`StencilRequest`]) are left empty,
/// for the caller to fill.
pub(crate) fn build_stencils(
    base: &HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    made_elsewhere: Option<MadeElsewhere<'_>>,
) -> Result<StencilBuild> {
    if made_elsewhere.is_none() {
        if let Some(order) = VertexOrder::for_build(base, attributes, options, tags) {
            // An error is made again in the caller's numbering, so that it names their vertices.
            let build =
                build_stencils_in(&order.mesh, attributes, options, tags, None, Some(&order), None);
            if let Ok(build) = build {
                return Ok(build);
            }
        }
    }
    build_stencils_in(base, attributes, options, tags, made_elsewhere, None, None)
}

/// The stencils of `options` level by level (OpenSubdiv's `StencilTableFactory` with
/// `factorizeIntermediateLevels` off): table `k` gives level `k + 1`'s vertices from level
/// `k`'s (the first from the control vertices); where the limit's masks run (the limit or its
/// normals), one table more gives the output vertices from the last level's, with the
/// tangents' weights. Applied in turn they give what the composed table gives, to f32
/// rounding.
///
/// Why: no row is composed with the rows of the level before, which is most of a composed
/// table's build (a row of the horse at Catmull-Clark level 2 holds about 11 control points
/// composed from some 37 products; a level's own row holds 4 to 9), and the tables together
/// are a third or less of the composed one's bytes. A GPU runs them as one pass per level.
pub(crate) fn build_level_stencils(
    base: &HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Vec<StencilTable>> {
    let mut tables = Vec::with_capacity(options.levels());
    let build = build_stencils_in(base, &[], options, tags, None, None, Some(&mut tables))?;
    tables.push(build.table);
    level_tables_within(tables, options)
}

/// `tables`, the stencils of `options` level by level, unless together they pass
/// `options.max_bytes` ([`Error::TooLarge`]).
pub(crate) fn level_tables_within(
    tables: Vec<StencilTable>,
    options: &Options,
) -> Result<Vec<StencilTable>> {
    let bytes: u64 = tables.iter().map(StencilTable::bytes).sum();
    if bytes > options.max_bytes {
        return Err(Error::TooLarge(table_too_large(options.levels(), bytes, options.max_bytes)));
    }
    Ok(tables)
}

/// The base mesh of a stencil build with its vertices renamed in the order its faces first name
/// them, when the caller's order scatters them. The build reads the rows of a face's corners
/// together, in the faces' order; in the horse's order (a scan: 23 % of the steps from one face
/// corner to the next jump over more than 1024 vertices, 0.1 % in this order) the level-2
/// Catmull-Clark build took about 25 % longer, waiting on memory. Only for schemes whose hosts
/// number a level's vertex children first, in the parent's vertex order (the quad and triangle
/// splits), so that just the first rows of the result, the base vertices' descendants, come
/// out renamed; and only without face-varying channels and vertex tags, which name vertices.
struct VertexOrder {
    /// The base mesh with the caller's vertices under their new names.
    mesh: HalfEdgeMesh,
    /// The caller's vertex of each new name.
    controls: Vec<u32>,
}

impl VertexOrder {
    /// Steps between consecutive face corners longer than this many vertices count as jumps.
    const NEAR: u32 = 1024;

    fn for_build(
        base: &HalfEdgeMesh,
        attributes: &[Attribute],
        options: &Options,
        tags: &Tags,
    ) -> Option<Self> {
        let splits_only = options.schemes.iter().all(|s| {
            matches!(s, Scheme::CatmullClark | Scheme::Loop | Scheme::Bilinear | Scheme::Midpoint)
        });
        let vertex_tags = !tags.creases.is_empty() || !tags.corners.is_empty();
        if options.schemes.is_empty()
            || !splits_only
            || vertex_tags
            || attributes.iter().any(Attribute::is_face_varying)
            || base.num_vertices() <= Self::NEAR as usize
        {
            return None;
        }
        let n = base.num_vertices();
        let mut labels = vec![u32::MAX; n];
        let mut controls = Vec::with_capacity(n);
        for &v in &base.he_from {
            if let Some(label) = labels.get_mut(v as usize).filter(|l| **l == u32::MAX) {
                *label = controls.len() as u32;
                controls.push(v);
            }
        }
        for (v, label) in labels.iter_mut().enumerate() {
            if *label == u32::MAX {
                *label = controls.len() as u32;
                controls.push(v as u32);
            }
        }
        let (mut scattered, mut ordered) = (0, 0);
        let mut last = [0u32; 2];
        for &v in &base.he_from {
            let label = labels.get(v as usize).copied().unwrap_or(v);
            scattered += usize::from(v.abs_diff(last[0]) > Self::NEAR);
            ordered += usize::from(label.abs_diff(last[1]) > Self::NEAR);
            last = [v, label];
        }
        // Worth a second mesh only where the caller's order jumps often and this one rarely.
        if scattered <= 4 * ordered + base.num_half_edges() / 50 {
            return None;
        }
        Some(VertexOrder { mesh: base.relabelled(&labels, &controls), controls })
    }
}

/// [`build_stencils`] on `base`, which is the caller's mesh renamed by `order` when there is one.
fn build_stencils_in(
    base: &HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    made_elsewhere: Option<MadeElsewhere<'_>>,
    order: Option<&VertexOrder>,
    stages: Option<&mut Vec<StencilTable>>,
) -> Result<StencilBuild> {
    check_attributes(attributes, base)?;
    check_guards(base, options)?;
    let levels = options.levels();
    let num_control = base.num_vertices();
    // At least one entry (8 bytes) and one offset (4) per output vertex: refused before any
    // work when even that does not fit; otherwise the entries left are each level's limit.
    let vertices = predict(base, options).vertices;
    let offset_bytes = vertices.saturating_add(1).saturating_mul(4);
    let max_bytes = options.max_bytes;
    let too_large = |bytes: String| table_too_large(levels, bytes, max_bytes);
    let least = offset_bytes.saturating_add(vertices.saturating_mul(8));
    if least > max_bytes {
        return Err(Error::TooLarge(too_large(format!("at least {least}"))));
    }
    let limit = usize::try_from((max_bytes - offset_bytes) / 8).unwrap_or(usize::MAX);
    let (fvar, fvar_layout) = attributes::pack_face_varying(attributes);
    let count = attributes.len();
    let mut stencils = None;
    let mut request =
        StencilRequest { made_elsewhere, tangents: None, stages: stages.is_some().then(Vec::new) };
    let refined = refine_levels(
        Cow::Borrowed(base),
        options,
        tags,
        match order {
            // The rows name the caller's control vertices from the start.
            Some(order) => Stencils::named(&order.controls, limit),
            None => Stencils::identity(num_control, limit),
        },
        fvar,
        |last, fvar| {
            stencils = Some(last);
            attributes::unpack_all(Rows::default(), &Default::default(), fvar, &fvar_layout, count)
        },
        Some(&mut request),
        None,
    )?;
    let (mut mesh, face_varying) = refined.into_parts();
    let stencils = stencils.unwrap_or_default();
    let what = || too_large(format!("more than {max_bytes}"));
    if let (Some(out), Some(made)) = (stages, request.stages.take()) {
        for stage in made {
            out.push(stage.into_table(what)?);
        }
    }
    let mut table = stencils.into_table(what)?;
    if let Some(TangentRows { limit, tangents: [first, second] }) = request.tangents {
        let mismatch = || {
            Error::Unsupported(
                "the tangent stencils do not match the positions'; please report this mesh".into(),
            )
        };
        table = match (first.into_shared_weights(), second.into_shared_weights(), limit) {
            // Made with the table's own rows (the limit positions): the same entries.
            (Ok(a), Ok(b), None) => table.with_tangent_weights(a, b).ok_or_else(mismatch)?,
            // Refined points with limit normals: the entries of the limit positions' rows.
            (Ok(a), Ok(b), Some(limit)) => {
                let limit = limit.into_table(what)?;
                match limit.with_positions_of(&table) {
                    Ok(shared) => shared.with_tangent_weights(a, b).ok_or_else(mismatch)?,
                    Err(limit) => {
                        let first = limit.with_weights(a).ok_or_else(mismatch)?;
                        let second = limit.with_weights(b).ok_or_else(mismatch)?;
                        table.with_tangents(first, second)
                    }
                }
            }
            (Err(a), Err(b), _) => table.with_tangents(a.into_table(what)?, b.into_table(what)?),
            _ => return Err(mismatch()),
        };
    }
    if table.num_stencils() != mesh.num_vertices() {
        return Err(Error::Unsupported(format!(
            "the stencil table has {} rows for {} output vertices; please report this mesh",
            table.num_stencils(),
            mesh.num_vertices()
        )));
    }
    if let Some(order) = order {
        // The first rows, and the faces' corners among them, are the base vertices'
        // descendants in the order of their new names.
        table.reorder_first(&order.controls);
        let controls = &order.controls[..];
        for c in &mut mesh.indices {
            if (*c as usize) < controls.len() {
                *c = controls[*c as usize];
            }
        }
    }
    // The levels left no positions worth keeping (see `StencilBuild::mesh`).
    mesh.positions = Vec::new();
    Ok(StencilBuild { table, mesh, face_varying })
}

/// The `finish` of calls without attribute channels: one function item, so that every such
/// call shares one instance of the level loop.
fn no_attributes(_: Rows, _: Vec<FVarChannel<'_>>) -> Channels {
    Channels::default()
}

/// Checks `attributes` against `mesh` as the `*_with` functions do before any work.
pub fn check_attributes(attributes: &[Attribute], mesh: &HalfEdgeMesh) -> Result<()> {
    attributes::validate(attributes, mesh.num_vertices(), mesh.num_half_edges())
}

/// Checks `attributes` against `base` and the result's size, channels, tangents and normals
/// included, against the guards of `options`: what a call refuses before any work.
pub(crate) fn check_call(
    base: &HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
) -> Result<()> {
    check_attributes(attributes, base)?;
    // The two tangents and the normal add nine floats per vertex.
    let limit_width = if options.limit || options.normals { 9 } else { 0 };
    let sizes = AttributeSizes {
        vertex_width: attributes
            .iter()
            .filter(|a| !a.is_face_varying())
            .map(|a| a.item_size as u64)
            .sum::<u64>()
            + limit_width,
        face_varying: attributes
            .iter()
            .filter(|a| a.is_face_varying())
            .map(|a| a.item_size as u64)
            .collect(),
    };
    check_guards_with(base, options, &sizes)
}

fn refine_with_attributes<'a>(
    base: Cow<'a, HalfEdgeMesh>,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    progress: Option<&mut OnProgress<'_>>,
) -> Result<Refined<'a>> {
    check_call(&base, attributes, options)?;
    if attributes.is_empty() {
        // The positions-only instance of the level loop, as the plain calls use: in the one
        // that carries rows, the wasm build refined positions 27 % slower (other inlining).
        return refine_levels(
            base,
            options,
            tags,
            Rows::default(),
            Vec::new(),
            no_attributes,
            None,
            progress,
        );
    }
    let (rows, layout) = attributes::pack(attributes, base.num_vertices());
    let (fvar, fvar_layout) = attributes::pack_face_varying(attributes);
    let count = attributes.len();
    let finish = |rows, fvar| attributes::unpack_all(rows, &layout, fvar, &fvar_layout, count);
    refine_levels(base, options, tags, rows, fvar, finish, None, progress)
}

/// Subdivides `mesh` as `options` says and evaluates the last level at the limit (OpenSubdiv's
/// `PrimvarRefiner::Limit`): the result's positions are the limit positions of the last level's
/// vertices, [`Refined::tangents`] and [`Refined::normals`] their limit tangents and unit
/// normals (see [`crate::rules::limit`]). The faces are those of [`subdivide_with_tags`]. The
/// last level must be Catmull-Clark or Loop (Quad/Triangle on triangles is Loop), and the
/// boundary not `average`; otherwise an [`Error::Unsupported`] before any work.
pub fn subdivide_limit(
    mesh: &PolyMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'static>> {
    subdivide_limit_with(mesh, &[], options, tags)
}

/// [`subdivide_limit`] with attribute channels: vertex-varying channels take the limit position
/// masks too; face-varying channels are those of the last level.
pub fn subdivide_limit_with(
    mesh: &PolyMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'static>> {
    let base = HalfEdgeMesh::from_poly(mesh)?;
    let options = Options { limit: true, normals: true, ..options.clone() };
    refine_with_attributes(Cow::Owned(base), attributes, &options, tags, None)
}

/// [`subdivide_limit`] of an already built mesh, which is left to the caller.
pub fn subdivide_mesh_limit<'a>(
    base: &'a HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
) -> Result<Refined<'a>> {
    let options = Options { limit: true, normals: true, ..options.clone() };
    refine_with_attributes(Cow::Borrowed(base), &[], &options, tags, None)
}

/// Refuses a limit of `options` that is not defined, before any work.
fn check_limit(options: &Options) -> Result<()> {
    match options.schemes.last() {
        None => {
            return Err(Error::Unsupported(
                "limit: true needs at least one level; use levels >= 1, or normals: true alone for the base mesh's face normals".to_string(),
            ))
        }
        Some(
            Scheme::CatmullClark
            | Scheme::Loop
            | Scheme::QuadTriangle
            | Scheme::Bilinear
            | Scheme::Midpoint,
        ) => {}
        Some(&scheme) => {
            return Err(Error::Unsupported(format!(
                "limit: true is not available for a last level of {scheme} (subsurf has limit masks for catmull-clark, loop and quad-triangle, and bilinear and midpoint points are already on theirs); use normals: true without limit for normals from the faces, or end with a catmull-clark or loop level"
            )))
        }
    }
    if options.boundary == Boundary::Average {
        return Err(Error::Unsupported(
            "the limit is defined for boundary 'edge-and-corner', 'edge-only', 'none' and 'fixed', not 'average'"
                .to_string(),
        ));
    }
    Ok(())
}

/// Leaves out the faces of `poly` that `tags` makes holes, with their face-varying corners.
fn drop_holes(mut poly: PolyMesh, tags: &LevelTags, fvar: &mut [FVarChannel<'_>]) -> PolyMesh {
    let sizes = std::mem::take(&mut poly.face_sizes);
    let indices = std::mem::take(&mut poly.indices);
    let (mut start, mut kept) = (0usize, Vec::with_capacity(indices.len()));
    let mut kept_corners = vec![Vec::with_capacity(indices.len()); fvar.len()];
    for (f, &n) in sizes.iter().enumerate() {
        let corners = start..start + n as usize;
        if !tags.is_hole(f as u32) {
            kept.extend_from_slice(&indices[corners.clone()]);
            for (out, channel) in kept_corners.iter_mut().zip(fvar.iter_mut()) {
                out.extend_from_slice(&channel.level_mut().corner_values[corners.clone()]);
            }
            poly.face_sizes.push(n);
        }
        start = corners.end;
    }
    poly.indices = kept;
    for (channel, corners) in fvar.iter_mut().zip(kept_corners) {
        channel.level_mut().corner_values = corners;
    }
    poly
}

/// Runs every level of `options` on `base`, with the vertex-varying `rows` (or any other
/// [`Primvar`], such as the stencils of [`crate::stencil`]) and the face-varying channels `fvar`
/// alongside; `finish` turns the last level's rows and channels back into attribute channels.
/// With `limit`, the last level is evaluated at the limit (`rows` too, by the position masks).
/// `progress` is told after each level.
///
/// `stencil` is for a stencil build, where `rows` stand for the positions: the limit's
/// positions and normals are then left to the table (the result keeps the last level's
/// positions and has no normals), and with `normals` the tangents' rows are written there.
#[allow(clippy::too_many_arguments)]
fn refine_levels<'a, 'f, V: Primvar>(
    base: Cow<'a, HalfEdgeMesh>,
    options: &Options,
    tags: &Tags,
    rows: V,
    fvar: Vec<FVarChannel<'f>>,
    finish: impl FnOnce(V, Vec<FVarChannel<'f>>) -> Channels,
    stencil: Option<&mut StencilRequest<'_, V>>,
    mut progress: Option<&mut OnProgress<'_>>,
) -> Result<Refined<'a>> {
    if options.limit {
        check_limit(options)?;
    }
    let levels = options.levels();
    let stencil_build = stencil.is_some();
    let refined =
        run_levels(base, options, tags, rows, fvar, finish, stencil, progress.as_deref_mut())?;
    let face_normals = options.normals && !stencil_build;
    let refined = if face_normals { refined.with_face_normals() } else { refined };
    if levels > 0 {
        report_result(progress, &refined, levels)?;
    }
    Ok(refined)
}

/// Tells `progress`, if any, that the last of `levels` levels is done, with `refined`'s counts.
pub(crate) fn report_result(
    progress: Option<&mut OnProgress<'_>>,
    refined: &Refined<'_>,
    levels: usize,
) -> Result<()> {
    let (faces, vertices) = (refined.num_faces(), refined.positions().len() / 3);
    report(progress, Progress { level: levels, levels, faces, vertices })
}

/// Tells `progress`, if any, where the call is; a `Break` becomes [`Error::Cancelled`].
pub(crate) fn report(progress: Option<&mut OnProgress<'_>>, done: Progress) -> Result<()> {
    match progress.map(|tell| tell(done)) {
        Some(ControlFlow::Break(())) => Err(Error::Cancelled(format!(
            "the progress callback stopped the call after level {} of {}",
            done.level, done.levels
        ))),
        _ => Ok(()),
    }
}

/// The scheme whose limit masks apply after a level of `scheme` on `mesh` (Quad/Triangle is
/// Catmull-Clark on quads and Loop on triangles, and chooses per vertex on a mix), if any.
fn limit_scheme(scheme: Scheme, mesh: &HalfEdgeMesh) -> Option<Scheme> {
    match scheme {
        Scheme::CatmullClark | Scheme::Loop => Some(scheme),
        Scheme::QuadTriangle if mesh.cell_size == 4 => Some(Scheme::CatmullClark),
        Scheme::QuadTriangle if mesh.cell_size == 3 => Some(Scheme::Loop),
        // Quads and triangles: each vertex by its faces (see `LimitRules::scheme`).
        Scheme::QuadTriangle => Some(Scheme::QuadTriangle),
        _ => None,
    }
}

/// Given the last level's faces, true for each of its vertices whose limit rows the caller of a
/// stencil build makes itself (see [`StencilRequest`]).
pub(crate) type MadeElsewhere<'s> = &'s mut dyn FnMut(&PolyMesh) -> Vec<bool>;

/// What a stencil build asks of the levels besides its rows: which of the last level's vertices
/// get their limit rows elsewhere (`made_elsewhere`, given the last level's faces: true for each
/// such vertex, whose rows are then left empty), and, filled in, the tangents' rows.
pub(crate) struct StencilRequest<'s, V> {
    pub made_elsewhere: Option<MadeElsewhere<'s>>,
    pub tangents: Option<TangentRows<V>>,
    /// When asked for, each level's rows but the last on the level before's vertices (not
    /// composed down to the control vertices), filled in as the levels run: see
    /// [`build_level_stencils`].
    pub stages: Option<Vec<V>>,
}

/// The rows of the limit tangents at the last level's vertices, and the rows of their limit
/// positions when those are not the call's rows (normals without `limit`); rows made together
/// may share their entries ([`Primvar::limit_rows`]).
pub(crate) struct TangentRows<V> {
    pub limit: Option<V>,
    pub tangents: [V; 2],
}

/// [`refine_levels`] without the face normals, telling `progress` after each level but the
/// last (which the caller tells once the result is whole).
#[allow(clippy::too_many_arguments)]
fn run_levels<'a, 'f, V: Primvar>(
    base: Cow<'a, HalfEdgeMesh>,
    options: &Options,
    tags: &Tags,
    mut rows: V,
    mut fvar: Vec<FVarChannel<'f>>,
    finish: impl FnOnce(V, Vec<FVarChannel<'f>>) -> Channels,
    mut stencil: Option<&mut StencilRequest<'_, V>>,
    mut progress: Option<&mut OnProgress<'_>>,
) -> Result<Refined<'a>> {
    // The limit masks run on the last level's mesh, for the limit or for its normals.
    let masks_wanted = options.limit || options.normals;
    // A stencil build leaves the positions to its table (see `build_stencils`).
    let stencil_build = stencil.is_some();
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
    let fvar_mode = options.fvar_linear;
    let mut mesh = base;
    if options.schemes.is_empty() {
        if tags.holes.is_empty() {
            return Ok(Refined::poly(mesh.to_poly(), finish(rows, fvar)));
        }
        let level_tags = LevelTags::base_with_edges(&mesh, tags, &crease_edges, false);
        let poly = drop_holes(mesh.to_poly(), &level_tags, &mut fvar);
        return Ok(Refined::poly(poly, finish(rows, fvar)));
    }
    let mut level_tags: Option<LevelTags> = None;
    let levels = options.schemes.len();
    let mut last_scheme = Scheme::CatmullClark;
    // At the limit, OpenSubdiv's first face at each vertex, through runs of triangle splits
    // from the base mesh (see `crate::limit::FirstFaces`).
    let mut first_faces = masks_wanted.then(|| FirstFaces::base(&mesh));
    for (level, &scheme) in options.schemes.iter().enumerate() {
        check_scheme(&mesh, scheme, boundary, level)?;
        // Quad/Triangle is Loop on triangles (Stam & Loop's rules reduce to Loop's there; see
        // `rules::quad_triangle`), and the children of triangles are triangles: a mesh of
        // triangles takes Loop's host and rules from here, the tagged path included, so that
        // non-manifold edges and vertices follow the crease rules and child edges stay apart
        // as in Loop. (User tags are still refused for Quad/Triangle above.)
        let on_triangles = |s: Scheme| match s {
            Scheme::QuadTriangle if mesh.cell_size == 3 => Scheme::Loop,
            s => s,
        };
        let scheme = on_triangles(scheme);
        let masks = if masks_wanted { limit_scheme(scheme, &mesh) } else { None };
        last_scheme = masks.unwrap_or(scheme);
        let split_first = match (first_faces.take(), scheme) {
            (Some(f), Scheme::Loop | Scheme::Midpoint) if mesh.cell_size == 3 => {
                Some(f.triangle_split(mesh.num_cells()))
            }
            _ => None,
        };
        // The limit is taken on the last level's mesh, which is therefore built as any other.
        let last = level + 1 == levels && masks.is_none();
        if level_tags.is_none() && scheme.supports_tags() {
            // The tagged path: for the user's tags (base level), and for what only the crease
            // rules handle: boundary 'none', non-manifold input, smooth triangles. Decided for
            // the run of levels that carry tags from here on (bilinear and midpoint carry them
            // to a later Catmull-Clark or Loop level), on this level's mesh.
            let run = options.schemes[level..].iter().map(|&s| on_triangles(s));
            let run = run.take_while(|s| s.supports_tags());
            let (mut creased, mut catmull_clark) = (false, false);
            for s in run {
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
        let sharp = LevelSharpness {
            tags: level_tags.as_ref(),
            sharp_corners: boundary == Boundary::EdgeAndCorner,
        };
        // After the mixed split, the child mesh is built from its faces, which numbers edges
        // its own way: the face-varying edge tags follow (parent vertices, first edge point).
        let mut renumber = None;
        let mut primal = Primal {
            rows: &rows,
            fvar: &mut fvar,
            sharp,
            mode: fvar_mode,
            last,
            positions: !stencil_build,
        };
        let (child, next_tags) = match (scheme, &level_tags) {
            (Scheme::CatmullClark, Some(t)) => {
                let rules = CreasedCatmullClark { boundary, tags: t };
                primal.level::<Pqq, _>(mesh, &rules, false)
            }
            (Scheme::CatmullClark, None) => {
                primal.level::<Pqq, _>(mesh, &CatmullClark { boundary }, false)
            }
            (Scheme::Bilinear, _) => primal.level::<Pqq, _>(mesh, &Bilinear, true),
            (Scheme::Loop, Some(t)) => {
                let rules = CreasedLoop { boundary, tags: t };
                primal.level::<Ptq, _>(mesh, &rules, false)
            }
            (Scheme::Loop, None) => primal.level::<Ptq, _>(mesh, &Loop { boundary }, false),
            (Scheme::Midpoint, _) => primal.level::<Ptq, _>(mesh, &Midpoint, true),
            (Scheme::QuadTriangle, _) => {
                let rules = QuadTriangle { boundary };
                for channel in primal.fvar.iter_mut() {
                    let rules = MixedRules(&rules);
                    channel.refine(&mesh, Split::Mixed, &rules, false, &sharp, fvar_mode);
                }
                let (_, count) = Split::Mixed.face_points(&mesh);
                renumber = Some((mesh.num_vertices(), mesh.num_vertices() + count));
                let (poly, rows) = quad_tri::refine_with(&mesh, &rules, &rows);
                (Level::Poly(poly, rows), None)
            }
            (Scheme::DooSabin, _) => {
                let mode = if boundary == Boundary::None {
                    DualBoundary::Retract
                } else {
                    DualBoundary::Chaikin
                };
                if last || mesh.num_cells() == 0 {
                    let (poly, rows) = dqq::refine_with(&mesh, &DooSabin, mode, &rows);
                    for channel in fvar.iter_mut() {
                        channel.refine_doo_sabin(&mesh, &DooSabin, mode, &poly.indices);
                    }
                    (Level::Poly(poly, rows), None)
                } else {
                    let (child, rows) = dqq::child_mesh_with(&mesh, &DooSabin, mode, &rows)?;
                    for channel in fvar.iter_mut() {
                        channel.refine_doo_sabin(&mesh, &DooSabin, mode, &child.he_from);
                    }
                    (Level::Mesh(child, rows), None)
                }
            }
            (Scheme::Sqrt3, _) => {
                let refine_boundary = sqrt3_refines_boundary(&options.schemes, level);
                let rules = Sqrt3 { boundary };
                let fvar_level = |fvar: &mut Vec<FVarChannel<'_>>, corners: &[u32]| {
                    for channel in fvar.iter_mut() {
                        channel.refine_sqrt3(&mesh, &rules, refine_boundary, fvar_mode, corners);
                    }
                };
                if last {
                    let (poly, rows) = sqrt3::refine_with(&mesh, &rules, refine_boundary, &rows);
                    fvar_level(&mut fvar, &poly.indices);
                    (Level::Poly(poly, rows), None)
                } else {
                    let (child, rows) =
                        sqrt3::child_mesh_with(&mesh, &rules, refine_boundary, &rows)?;
                    fvar_level(&mut fvar, &child.he_from);
                    (Level::Mesh(child, rows), None)
                }
            }
        };
        level_tags = next_tags;
        mesh = match child {
            // A mesh without vertices (Doo-Sabin of a mesh without faces) stays empty.
            Level::Poly(poly, rows) if last || poly.positions.is_empty() || rows.overflowed() => {
                return Ok(Refined::poly(poly, finish(rows, fvar)));
            }
            Level::Mesh(_, rows) if rows.overflowed() => {
                return Ok(Refined::poly(PolyMesh::default(), finish(rows, fvar)));
            }
            Level::Poly(poly, child_rows) => {
                rows = child_rows;
                let child = HalfEdgeMesh::from_poly(&poly)?;
                if let Some((parent_vertices, edge_base)) = renumber {
                    for channel in fvar.iter_mut().filter(|c| c.analysed) {
                        channel.level_mut().renumber_edge_tags(&child, parent_vertices, edge_base);
                    }
                }
                Cow::Owned(child)
            }
            Level::Mesh(mesh, child_rows) => {
                rows = child_rows;
                first_faces = split_first.map(|split| FirstFaces::scatter(&mesh, split));
                Cow::Owned(mesh)
            }
            Level::Quads { positions, parent, rows } => {
                return Ok(Refined::quads(positions, parent, finish(rows, fvar)));
            }
        };
        // Level by level: this level's rows are a table of their own, and the next level's
        // start from this level's vertices.
        if let Some(stages) = stencil.as_deref_mut().and_then(|s| s.stages.as_mut()) {
            if let Some(restarted) = rows.restart(mesh.num_vertices()) {
                stages.push(std::mem::replace(&mut rows, restarted));
            }
        }
        if level + 1 < levels {
            let done = Progress {
                level: level + 1,
                levels,
                faces: mesh.num_cells(),
                vertices: mesh.num_vertices(),
            };
            report(progress.as_deref_mut(), done)?;
        }
    }
    if masks_wanted {
        let starts = first_faces.as_ref().map(|f| &f.vertices[..]);
        let rules = LimitRules { scheme: last_scheme, boundary, tags: level_tags.as_ref(), starts };
        // A stencil build's masks run once, for the rows.
        let want_tangent_rows = stencil_build && options.normals;
        let mut poly = mesh.to_poly();
        let elsewhere = match stencil.as_deref_mut().and_then(|s| s.made_elsewhere.as_mut()) {
            Some(made_elsewhere) => made_elsewhere(&poly),
            None => Vec::new(),
        };
        let (frame, limit_rows, tangents) = crate::limit::evaluate(
            &mesh,
            &rules,
            &rows,
            want_tangent_rows,
            !stencil_build,
            &elsewhere,
        );
        // The limit rows replace the level's under `limit`; otherwise the tangent rows may
        // share their entries.
        let limit_rows = if options.limit {
            rows = limit_rows;
            None
        } else {
            Some(limit_rows)
        };
        if options.limit {
            if !stencil_build {
                poly.positions = frame.positions;
            }
            let linear = fvar_mode == FVarLinear::All;
            for channel in fvar.iter_mut().filter(|c| c.analysed) {
                crate::limit::limit_face_varying(&mesh, &rules, channel.level_mut(), linear);
            }
        }
        if let Some(out) = stencil {
            out.tangents = tangents.map(|tangents| TangentRows { limit: limit_rows, tangents });
        }
        if let Some(tags) = level_tags.as_ref().filter(|t| t.has_holes()) {
            poly = drop_holes(poly, tags, &mut fvar);
        }
        if stencil_build {
            return Ok(Refined::poly(poly, finish(rows, fvar)));
        }
        let normals = options.normals.then_some(frame.normals);
        return Ok(Refined::with_tangents(poly, finish(rows, fvar), frame.tangents, normals));
    }
    Ok(Refined::poly(mesh.to_poly(), finish(rows, fvar)))
}

/// The new values of `rows` by the split `S` with `rules` (none when there are none).
fn refine_rows<S: PrimalSplit<R>, R, V: Primvar>(mesh: &HalfEdgeMesh, rules: &R, rows: &V) -> V {
    if rows.is_empty() {
        rows.with_capacity(0)
    } else {
        S::points(mesh, rules, rows)
    }
}

/// `mesh`'s positions and `channels` refined in one walk of the rules, packed (see
/// [`pack_points`]; every width up to [`MAX_PACKED`] takes the widest, one instance of the walk
/// per host: the lanes left over cost next to nothing); `None` when there is no channel or they
/// pass [`MAX_PACKED`] floats.
fn refine_packed<S: PrimalSplit<R>, R>(
    mesh: &HalfEdgeMesh,
    rules: &R,
    channels: &[Channel<'_>],
    room: &[usize],
) -> Option<Unpacking> {
    let widths: Vec<_> = channels.iter().map(|c| c.width).collect();
    if widths.is_empty() || 3 + widths.iter().sum::<usize>() > MAX_PACKED {
        return None;
    }
    let parent = pack_points::<MAX_PACKED>(&mesh.positions, channels);
    let mut child = Unpacking::new(S::num_points(mesh), &widths, room);
    S::points_into(mesh, rules, &parent, &mut child);
    Some(child)
}

/// One level's result, with its vertex-varying rows: flat arrays, or for the last quad split the
/// positions with the parent mesh (the faces are implicit, see [`Refined`]), or a mesh built by
/// index arithmetic where a host can do that.
enum Level<'a, V> {
    Poly(PolyMesh, V),
    Quads { positions: Vec<f32>, parent: Cow<'a, HalfEdgeMesh>, rows: V },
    Mesh(HalfEdgeMesh, V),
}

/// What one level of a primal split carries besides the mesh: the vertex-varying rows, the
/// face-varying channels (refined in place), the level's sharpness, and whether it is the last.
struct Primal<'r, 's, 'f, V> {
    rows: &'r V,
    fvar: &'r mut Vec<FVarChannel<'f>>,
    sharp: LevelSharpness<'s>,
    mode: crate::options::FVarLinear,
    last: bool,
    /// False in a stencil build, whose table gives the positions: the child positions are then
    /// left at zero (the other hosts still compute theirs).
    positions: bool,
}

impl<V: Primvar> Primal<'_, '_, '_, V> {
    /// One level of a primal split `S` with `rules` (`linear` for bilinear and midpoint, whose
    /// face-varying values are linear too), with the level's tags when it follows tags: the
    /// last level leaves out the children of holes (and keeps the faces implicit where it can);
    /// other levels return the child mesh and, with tags, the child level's tags.
    fn level<'a, S: PrimalSplit<R>, R>(
        &mut self,
        mesh: Cow<'a, HalfEdgeMesh>,
        rules: &R,
        linear: bool,
    ) -> (Level<'a, V>, Option<LevelTags>) {
        let split = if S::FACE_POINTS { Split::Quad } else { Split::Triangle };
        let (sharp, mode) = (&self.sharp, self.mode);
        let tags = self.sharp.tags;
        let holes = tags.filter(|t| t.has_holes());
        let implicit = self.last && S::IMPLICIT_FACES && holes.is_none();
        let steps: Vec<_> =
            self.fvar.iter_mut().map(|c| c.begin(&mesh, split, sharp, mode, implicit)).collect();
        // The vertex-varying rows and the face-varying values that follow the surface (their
        // values numbered as vertices) take the surface's weights: one walk of the rules refines
        // them with the positions, packed side by side with the sum in registers, when that fits
        // in `MAX_PACKED` floats; wider, each kind walks the rules on its own.
        let fvar_joint = FVarChannel::follows_surface(linear, mode) && !self.fvar.is_empty();
        let mut channels: Vec<_> = self.rows.as_channel().into_iter().collect();
        let has_rows = !channels.is_empty();
        // Each face-varying channel's values grow to its child's count after the walk.
        let mut room = vec![0; channels.len()];
        if fvar_joint {
            channels.extend(self.fvar.iter().map(|c| c.vertex_values(&mesh)));
            room.extend(steps.iter().map(|s| s.num_values()));
        }
        let (positions, rows, mut fvar_values) =
            match refine_packed::<S, R>(&mesh, rules, &channels, &room) {
                Some(child) => {
                    let (positions, refined) = child.into_parts();
                    let mut refined = refined.into_iter();
                    let rows = has_rows.then(|| refined.next()).flatten();
                    let rows = rows.and_then(|values| self.rows.with_channel(values));
                    let rows =
                        rows.unwrap_or_else(|| refine_rows::<S, R, V>(&mesh, rules, self.rows));
                    (positions, rows, refined.map(Some).collect())
                }
                None => {
                    let fvar_values: Vec<_> = channels[usize::from(has_rows)..]
                        .iter()
                        .map(|c| {
                            let values = Rows { width: c.width, values: Cow::Borrowed(&c.values) };
                            Some(
                                refine_rows::<S, R, Rows>(&mesh, rules, &values)
                                    .values
                                    .into_owned(),
                            )
                        })
                        .collect();
                    let rows = refine_rows::<S, R, V>(&mesh, rules, self.rows);
                    let positions = if self.positions {
                        S::points(&mesh, rules, &mesh.positions)
                    } else {
                        vec![[0.0; 3]; S::num_points(&mesh)]
                    };
                    (positions, rows, fvar_values)
                }
            };
        fvar_values.resize_with(steps.len(), || None);
        let value_rules = PrimalRules::<S, R>::new(rules);
        for ((channel, step), joint) in self.fvar.iter_mut().zip(steps).zip(fvar_values) {
            channel.finish(&mesh, split, &value_rules, step, linear, sharp, mode, joint);
        }
        if rows.overflowed() {
            // A stencil build past its limit is refused whatever follows: stop before the
            // child's topology, which would take as much memory again (in wasm, more than
            // there is).
            return (Level::Poly(PolyMesh::default(), rows), None);
        }
        if !self.last {
            let child = S::child_mesh(&mesh, positions);
            let child_tags = tags.map(|t| S::child_tags(&mesh, &child, t));
            return (Level::Mesh(child, rows), child_tags);
        }
        let positions = positions.into_flattened();
        if implicit {
            return (Level::Quads { positions, parent: mesh, rows }, None);
        }
        let mut indices = S::child_face_indices(&mesh);
        let size = S::FACE_SIZE;
        if let Some(tags) = holes {
            let keep = |f: usize| !tags.is_hole(S::parent_cell(&mesh, f));
            for channel in self.fvar.iter_mut() {
                channel.keep_faces(size, keep);
            }
            crate::mesh::retain_faces(&mut indices, size, keep);
        }
        let face_sizes = vec![size as u32; indices.len() / size];
        (Level::Poly(PolyMesh { positions, indices, face_sizes }, rows), None)
    }
}
