//! Refine once, evaluate every frame: an [`Evaluator`] holds a call's output topology and its
//! stencil table ([`crate::stencil`]), so that new control positions (a skinned or morphed
//! cage) give the call's positions and normals with one sparse product and no topology work.
//! OpenSubdiv's `Far::StencilTableFactory` / `LimitStencilTableFactory` with
//! `Osd::CpuEvaluator::EvalStencils`, behind one type.

use crate::attributes::{Attribute, Channels};
use crate::error::{Error, Result};
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::options::{Options, Scheme};
use crate::patches::{RegularPatches, NO_PATCH};
use crate::quad_rings::QuadRings;
use crate::refined::Refined;
use crate::regular_rings::{Previous, RegularRings, Step};
use crate::scheme::{
    build_level_stencils, build_stencils, check_call, level_tables_within, report, report_result,
    subdivide_mesh_borrowed_with, table_too_large, MadeElsewhere, OnProgress, Progress,
    StencilBuild,
};
use crate::shared_weights::SharedWeights;
use crate::smooth_levels::{
    catmull_clark_faces, catmull_clark_steps, loop_steps, quad_faces, triangle_child,
    triangle_faces, untold, SmoothLevels, Told,
};
use crate::stencil::{pad, AllRows, ClosedForms, StencilTable};
use crate::tags::Tags;
use std::ops::ControlFlow;
use std::sync::{Arc, OnceLock};

/// Where an evaluator's normals come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum NormalSource {
    /// Not asked for.
    None,
    /// The table's tangent weights (the last level has limit masks).
    Tangents,
    /// The output faces, recomputed per frame (bilinear, midpoint, Doo-Sabin, √3).
    Faces,
}

/// A subdivision call prepared for many control positions of the same mesh: its output faces
/// and face-varying channels (fixed), its stencil table, and how its normals are made. Equal,
/// frame by frame, to [`crate::scheme::subdivide_with_attributes`] with the same options,
/// `limit` and `normals` included, to f32 rounding.
///
/// The positions and normals at build time are made from the table when first asked for
/// ([`Evaluator::positions`]): an evaluator used frame by frame never needs them.
#[derive(Clone, Debug)]
pub struct Evaluator {
    table: Table,
    /// What the evaluator was made from: its table on first use, its level stencils, and
    /// (the base mesh's positions, which no one changes behind an `Arc`) its frame at build
    /// time.
    recipe: Box<Recipe>,
    outputs: usize,
    /// The output faces; the positions are left empty (see `at_build`).
    faces: PolyMesh,
    attributes: Vec<Attribute>,
    /// The output positions and normals of the base mesh's positions, on first use.
    at_build: OnceLock<(Vec<f32>, Option<Vec<f32>>)>,
    source: NormalSource,
    /// The points made in closed form rather than from their stencil rows, if any; the
    /// table's rows give the others (see [`Closed`]).
    closed: Option<Closed>,
    /// The weights of the rows a frame reads, each distinct list once, when the table has
    /// tangents (see `crate::shared_weights`).
    shared: Option<SharedWeights>,
}

/// An evaluator's stencil table: made with it, or on first use ([`Evaluator::table`]) when a
/// closed form gives every point, so that no frame reads it.
#[derive(Clone, Debug)]
enum Table {
    Built(StencilTable),
    /// The table once made.
    Later(OnceLock<StencilTable>),
}

/// The base mesh, options and tags of an evaluator. The base mesh is shared with its owner
/// where it has one in an `Arc` ([`Evaluator::new_shared`]: the JS `BaseMesh`), not copied: it
/// is about as large as the refinement's first level.
#[derive(Clone, Debug)]
struct Recipe {
    base: Arc<HalfEdgeMesh>,
    options: Options,
    tags: Tags,
}

impl Recipe {
    fn new(base: &Arc<HalfEdgeMesh>, options: &Options, tags: &Tags) -> Box<Self> {
        Box::new(Recipe { base: Arc::clone(base), options: options.clone(), tags: tags.clone() })
    }
}

/// The closed form an evaluator runs for the points it gives, the table's rows giving the
/// others (`ClosedForms::rest`); when it gives every point, the evaluator may leave its table
/// out (see `Evaluator::from_levels`).
#[derive(Clone, Debug)]
enum Closed {
    /// Catmull-Clark limit points on regular faces, evaluated as bicubic patches rather than
    /// from their (much larger) stencil rows, with their normals (see `crate::patches`).
    Patches(RegularPatches),
    /// Loop limit points whose level before is regular, in closed form from that level's
    /// points (see `crate::regular_rings`).
    Rings(RegularRings),
    /// Catmull-Clark limit points (or refined points with limit normals) on a closed cage,
    /// from the last level's points by the masks (see `crate::quad_rings`): every point.
    Quads(QuadRings),
    /// Refined points (no limit, no normals) of a closed cage untagged, every level by the
    /// smooth rules each frame (see `crate::smooth_levels`): every point.
    Levels(SmoothLevels),
}

impl Closed {
    fn form(&self) -> &dyn ClosedForms {
        match self {
            Closed::Patches(patches) => patches,
            Closed::Rings(rings) => rings,
            Closed::Quads(quads) => quads,
            Closed::Levels(levels) => levels,
        }
    }

    /// Number of output vertices it gives.
    fn num_points(&self) -> usize {
        match self {
            Closed::Patches(patches) => patches.num_points(),
            Closed::Rings(rings) => rings.num_points(),
            Closed::Quads(quads) => quads.num_points(),
            Closed::Levels(levels) => levels.outputs(),
        }
    }

    /// What a frame reads for it besides its input.
    fn bytes(&self) -> u64 {
        match self {
            Closed::Patches(patches) => patches.bytes(),
            Closed::Rings(rings) => rings.bytes(),
            Closed::Quads(quads) => quads.bytes(),
            Closed::Levels(levels) => levels.bytes(),
        }
    }
}

impl Evaluator {
    /// Refines `base` once as `options` and `tags` say, recording the stencils. `attributes`
    /// are the base mesh's channels: face-varying ones are refined now (their values are fixed
    /// from then on), vertex-varying ones through the table. Errors as the subdivision would
    /// give them, and [`Error::TooLarge`] when the table passes `options.max_bytes`.
    pub fn new(
        base: &HalfEdgeMesh,
        attributes: &[Attribute],
        options: &Options,
        tags: &Tags,
    ) -> Result<Self> {
        Self::new_shared(&Arc::new(base.clone()), attributes, options, tags)
    }

    /// [`Evaluator::new`] on a base mesh the caller keeps in an `Arc`: the evaluator holds
    /// it (for its table on first use and its level stencils) without a copy of its own.
    pub fn new_shared(
        held: &Arc<HalfEdgeMesh>,
        attributes: &[Attribute],
        options: &Options,
        tags: &Tags,
    ) -> Result<Self> {
        let base = &**held;
        if tags.is_trivial() && !tags.smooth_triangles {
            if let Some(evaluator) = Self::from_levels(held, attributes, options, tags)? {
                return Ok(evaluator);
            }
        }
        let (build, patches) = build_table(base, attributes, options, tags)?;
        debug_assert_eq!(build.table.num_control_vertices(), base.num_vertices());
        let patchable = patchable(options, tags);
        let rings = if patchable || !options.limit || !tags.is_trivial() {
            None
        } else {
            regular_rings(
                base,
                options,
                tags,
                &build.mesh,
                build.table.num_stencils(),
                build.table.bytes(),
            )
        };
        // A closed cage without regular faces (a triangle cage: the horse, most glTF models):
        // the last level by Catmull and Clark's rules, and its limit masks. (OpenSubdiv's
        // smooth-triangle rule weights a triangle's edge points otherwise.)
        let quads = match (&patches, options.max_bytes.checked_sub(build.table.bytes())) {
            (None, Some(budget)) if patchable && !tags.smooth_triangles => {
                let outputs = build.table.num_stencils();
                let steps = catmull_clark_steps(base, options.levels(), &mut untold);
                let steps = steps.map(|(steps, _)| steps);
                steps
                    .and_then(|steps| QuadRings::new(steps, &build.mesh, true))
                    .filter(|quads| quads.num_points() == outputs && quads.bytes() <= budget)
            }
            _ => None,
        };
        let closed = (patches.map(Closed::Patches))
            .or(rings.map(Closed::Rings))
            .or(quads.map(Closed::Quads));
        let source = match (options.normals, build.table.tangent_weights().is_some()) {
            (false, _) => NormalSource::None,
            (true, true) => NormalSource::Tangents,
            (true, false) => NormalSource::Faces,
        };
        let mut face_varying = build.face_varying.into_iter();
        let mut channels = Vec::with_capacity(attributes.len());
        for a in attributes {
            if a.is_face_varying() {
                channels.extend(face_varying.next());
                continue;
            }
            let mut values = vec![0.0; build.table.num_stencils() * a.item_size];
            build.table.evaluate(&a.values, a.item_size, &mut values)?;
            channels.push(Attribute::vertex(a.name.clone(), a.item_size, values));
        }
        let shared = match (source, build.table.tangent_weights()) {
            (NormalSource::Tangents, Some([first, second])) => {
                let rows: Vec<usize> = match closed.as_ref().map(|c| c.form().rest()) {
                    Some(rest) => rest.iter().map(|&r| r as usize).collect(),
                    None => (0..build.table.num_stencils()).collect(),
                };
                let weights = [build.table.weights(), first, second];
                SharedWeights::new(build.table.offsets(), weights, &rows)
            }
            _ => None,
        };
        Ok(Evaluator {
            outputs: build.table.num_stencils(),
            table: Table::Built(build.table),
            recipe: Recipe::new(held, options, tags),
            faces: build.mesh,
            attributes: channels,
            at_build: OnceLock::new(),
            source,
            closed,
            shared,
        })
    }

    /// An evaluator whose closed form gives every point from the levels' smooth rules, on a
    /// closed cage: refined points (`crate::smooth_levels`); Catmull-Clark's limit where no
    /// base face is a regular patch, or its refined points with the limit's normals
    /// (`crate::quad_rings`); Loop's limit, or its refined points with the limit's normals
    /// (`crate::regular_rings`). It holds the output faces and the
    /// levels' topology, and makes its table only when asked for it (the stencil arrays, the
    /// GPU, a vertex-varying channel): no frame reads it. `None` when no closed form applies.
    ///
    /// The channels of `attributes` at build time come from one `subdivide` of the base mesh
    /// with them (the levels' topology does not carry them): face-varying ones are fixed from
    /// then on, and a vertex-varying one's frames (`evaluate_attribute`) read the table, made
    /// on their first call.
    fn from_levels(
        held: &Arc<HalfEdgeMesh>,
        attributes: &[Attribute],
        options: &Options,
        tags: &Tags,
    ) -> Result<Option<Self>> {
        let base = &**held;
        crate::predict::check_guards(base, options)?;
        let Some((closed, faces)) = closed_forms(base, options, &mut untold) else {
            return Ok(None);
        };
        let channels = if attributes.is_empty() {
            Vec::new()
        } else {
            let refined = subdivide_mesh_borrowed_with(base, attributes, options, tags)?;
            let (poly, channels) = refined.into_parts();
            if poly.indices != faces.indices {
                // The levels' faces are the call's; were they ever not, the table's path keeps
                // its own.
                return Ok(None);
            }
            channels
        };
        Ok(Some(Evaluator {
            table: Table::Later(OnceLock::new()),
            recipe: Recipe::new(held, options, tags),
            outputs: closed.num_points(),
            faces,
            attributes: channels,
            at_build: OnceLock::new(),
            source: if options.normals { NormalSource::Tangents } else { NormalSource::None },
            closed: Some(closed),
            shared: None,
        }))
    }

    /// The stencil table (positions, and the tangents' weights when normals come from it),
    /// made on first use when the evaluator left it out (see [`Evaluator::step_vertices`]):
    /// then [`Error::TooLarge`] when it passes the options' `max_bytes`.
    pub fn table(&self) -> Result<&StencilTable> {
        let made = match &self.table {
            Table::Built(table) => return Ok(table),
            Table::Later(made) => made,
        };
        if let Some(table) = made.get() {
            return Ok(table);
        }
        let Recipe { base, options, tags } = &*self.recipe;
        let (build, _) = build_table(base, &[], options, tags)?;
        Ok(made.get_or_init(|| build.table))
    }

    /// Whether the stencil table is made: with the evaluator, or since it was first asked for
    /// ([`Evaluator::table`]).
    pub fn has_table(&self) -> bool {
        match &self.table {
            Table::Built(_) => true,
            Table::Later(made) => made.get().is_some(),
        }
    }

    /// The stencils level by level, made on each call: table `k` gives level `k + 1`'s
    /// vertices from level `k`'s (the first from the control vertices). Where the limit's
    /// masks apply (`limit`, or `normals` of Catmull-Clark, Loop and Quad/Triangle), one table
    /// more gives the output vertices from the last level's: its limit points (or its own
    /// points) with the tangents' weights when the evaluator has normals from them. Run in turn, each on the one before's output, they give the frames of
    /// [`Evaluator::evaluate`] to f32 rounding (OpenSubdiv's `StencilTableFactory` with
    /// `factorizeIntermediateLevels` off). Their rows are not composed, so they cost a
    /// fraction of [`Evaluator::table`]'s build and bytes: what a GPU runs, one pass per
    /// level. [`Error::TooLarge`] when together they pass the options' `max_bytes`.
    ///
    /// Normals made from the output faces (bilinear, midpoint, Doo-Sabin, √3) are not in the
    /// tables, as they are not in [`Evaluator::table`].
    pub fn level_tables(&self) -> Result<Vec<StencilTable>> {
        let Recipe { base, options, tags } = &*self.recipe;
        match &self.closed {
            // The steps the frames run, written as tables.
            Some(Closed::Levels(levels)) => level_tables_within(levels.tables(), options),
            _ => build_level_stencils(base, options, tags),
        }
    }

    /// The output faces: vertex indices, listed face after face.
    pub fn indices(&self) -> &[u32] {
        &self.faces.indices
    }

    /// The number of corners of each output face.
    pub fn face_sizes(&self) -> &[u32] {
        &self.faces.face_sizes
    }

    /// The output faces as triangles (see [`PolyMesh::triangles`]).
    pub fn triangles(&self) -> Vec<u32> {
        self.faces.triangles()
    }

    /// The output positions at build time (3 floats per output vertex), made on first use.
    pub fn positions(&self) -> &[f32] {
        &self.at_build().0
    }

    /// The positions and normals at build time: [`Evaluator::evaluate`] of the control
    /// positions it was built with (which cannot fail: the table and those positions come
    /// from one build).
    fn at_build(&self) -> &(Vec<f32>, Option<Vec<f32>>) {
        self.at_build.get_or_init(|| {
            let n = 3 * self.num_vertices();
            let mut positions = vec![0.0; n];
            let mut normals = self.has_normals().then(|| vec![0.0; n]);
            let control = self.recipe.base.positions.as_flattened();
            match self.evaluate(control, &mut positions, normals.as_deref_mut()) {
                Ok(()) => (positions, normals),
                Err(_) => Default::default(),
            }
        })
    }

    /// The output channels at build time, in the order given: face-varying ones refined,
    /// vertex-varying ones evaluated from the values given to [`Evaluator::new`].
    pub fn attributes(&self) -> &[Attribute] {
        &self.attributes
    }

    /// The normals at build time, when asked for; made on first use.
    pub fn normals(&self) -> Option<&[f32]> {
        self.at_build().1.as_deref()
    }

    /// True when [`Evaluator::evaluate`] writes normals.
    pub fn has_normals(&self) -> bool {
        self.source != NormalSource::None
    }

    /// Number of control (base) vertices the evaluator reads.
    pub fn num_control_vertices(&self) -> usize {
        self.recipe.base.num_vertices()
    }

    /// How many output vertices [`Evaluator::evaluate`] computes as bicubic patches rather than
    /// from their stencil rows: Catmull-Clark at the limit without tags, on the base faces
    /// whose four corners are smooth interior vertices with four quads each (the limit surface
    /// there is a uniform bicubic B-spline patch). Same positions and normals to f32 rounding,
    /// about 2.7 times faster per point without normals and 1.8 with them (torus, wasm).
    pub fn patch_vertices(&self) -> usize {
        match &self.closed {
            Some(Closed::Patches(patches)) => patches.num_points(),
            _ => 0,
        }
    }

    /// How many output vertices [`Evaluator::evaluate`] computes in closed form rather than
    /// from their stencil rows: Loop at the limit without tags, from the level before the last,
    /// the children of regular vertices (valence 6, interior) and of edges between two (see
    /// `crate::regular_rings`); Catmull-Clark at the limit without tags on a closed cage that
    /// no patch covers (a triangle cage), every vertex, from the last level made by the rules
    /// (see `crate::quad_rings`); refined points with the limit's normals on a closed cage, by
    /// either scheme. Same positions and normals to f32 rounding.
    pub fn ring_vertices(&self) -> usize {
        match &self.closed {
            Some(Closed::Rings(rings)) => rings.num_points(),
            Some(Closed::Quads(quads)) => quads.num_points(),
            _ => 0,
        }
    }

    /// How many output vertices [`Evaluator::evaluate`] makes by the levels' smooth rules
    /// rather than from their stencil rows: without the limit, Catmull-Clark or Loop at every
    /// level and no tags, on a closed cage (every edge between two faces, every vertex with a
    /// closed fan of 3 to 64 faces): then every vertex, each frame making each level from the
    /// one before (see `crate::smooth_levels`). Same positions to f32 rounding.
    pub fn step_vertices(&self) -> usize {
        match &self.closed {
            Some(Closed::Levels(levels)) => levels.outputs(),
            _ => 0,
        }
    }

    /// Bytes of what a frame reads besides its input: the table when frames read it, and for
    /// the closed forms ([`Evaluator::ring_vertices`], [`Evaluator::step_vertices`]) the
    /// levels' topology or the level before's own table and the cases (indices of the points
    /// each reads), which `options.max_bytes` bounds with the table. An evaluator whose closed
    /// forms give every point makes its table on first use ([`Evaluator::table`]) and counts
    /// none here.
    pub fn bytes(&self) -> u64 {
        let table = match &self.table {
            Table::Built(table) => table.bytes(),
            Table::Later(_) => 0,
        };
        table + self.closed.as_ref().map_or(0, Closed::bytes)
    }

    /// Number of output vertices.
    pub fn num_vertices(&self) -> usize {
        self.outputs
    }

    /// The output positions (and, when asked for at build time, unit normals) for new
    /// `control` positions: 3 finite floats per control vertex in, 3 per output vertex out.
    /// Errors name what is wrong and leave the outputs untouched.
    pub fn evaluate(
        &self,
        control: &[f32],
        positions: &mut [f32],
        normals: Option<&mut [f32]>,
    ) -> Result<()> {
        let expected = 3 * self.num_control_vertices();
        if control.len() != expected {
            return Err(Error::InvalidAttribute(format!(
                "evaluate: positions has {} floats; expected {expected} (x, y, z for each of the {} vertices of the mesh the evaluator was built from)",
                control.len(),
                self.num_control_vertices()
            )));
        }
        if let Some(i) = crate::mesh::first_unusable(control) {
            return Err(Error::InvalidAttribute(format!(
                "evaluate: positions[{i}] (vertex {}, {}) is {}; {}",
                i / 3,
                ["x", "y", "z"][i % 3],
                control[i],
                crate::mesh::unusable_because(control[i], "coordinate")
            )));
        }
        let outputs = 3 * self.num_vertices();
        if positions.len() != outputs {
            return Err(Error::InvalidAttribute(format!(
                "evaluate: the output positions have {} floats; expected {outputs}",
                positions.len()
            )));
        }
        let normals = match (self.source, normals) {
            (NormalSource::None, _) => None,
            (_, None) => {
                return Err(Error::InvalidAttribute(
                    "evaluate: this evaluator gives normals; pass an output for them".into(),
                ))
            }
            (_, Some(normals)) if normals.len() != outputs => {
                return Err(Error::InvalidAttribute(format!(
                    "evaluate: the output normals have {} floats; expected {outputs}",
                    normals.len()
                )))
            }
            (_, Some(normals)) => Some(normals),
        };
        if let Some(closed) = self.closed.as_ref().map(Closed::form) {
            // The rows of the points no closed form gives, then the closed forms.
            let control = pad(control);
            let (positions, _) = positions.as_chunks_mut::<3>();
            match (self.source, normals) {
                (NormalSource::Tangents, Some(normals)) => {
                    let (normals, _) = normals.as_chunks_mut::<3>();
                    let (rest, shared) = (closed.rest(), self.shared.as_ref());
                    if !rest.is_empty() {
                        self.table()?
                            .points_and_normals(&control, rest, positions, normals, shared);
                    }
                    closed.points_and_normals(&control, positions, normals);
                }
                _ => {
                    if !closed.rest().is_empty() {
                        self.table()?.points(&control, closed.rest(), positions);
                    }
                    closed.points(&control, positions);
                }
            }
            return Ok(());
        }
        match (self.source, normals) {
            (NormalSource::Tangents, Some(normals)) => match &self.shared {
                Some(shared) => {
                    let control = pad(control);
                    let (positions, _) = positions.as_chunks_mut::<3>();
                    let (normals, _) = normals.as_chunks_mut::<3>();
                    let rows = AllRows(self.num_vertices());
                    self.table()?.points_and_normals(
                        &control,
                        rows,
                        positions,
                        normals,
                        Some(shared),
                    );
                    Ok(())
                }
                None => self.table()?.evaluate_with_normals(control, positions, normals),
            },
            (NormalSource::Faces, Some(normals)) => {
                self.table()?.evaluate(control, 3, positions)?;
                let mesh = &self.faces;
                crate::limit::face_normals_into(
                    positions,
                    &mesh.indices,
                    &mesh.face_sizes,
                    normals,
                );
                Ok(())
            }
            _ => self.table()?.evaluate(control, 3, positions),
        }
    }

    /// Any vertex-varying data (colours, skin weights, a morph target's deltas) through the
    /// positions' stencils: `width` floats per control vertex in, per output vertex out. Errors
    /// on a wrong length, and on a value that is not finite or beyond ±1e30
    /// ([`crate::mesh::MAX_COORDINATE`]).
    pub fn evaluate_attribute(&self, values: &[f32], width: usize, out: &mut [f32]) -> Result<()> {
        let vertices = self.num_control_vertices();
        if Some(values.len()) != vertices.checked_mul(width) {
            return Err(Error::InvalidAttribute(format!(
                "evaluateAttribute: values has {} floats; expected {width} (itemSize) for each of the {vertices} vertices of the mesh the evaluator was built from",
                values.len()
            )));
        }
        if let Some(i) = crate::mesh::first_unusable(values) {
            return Err(Error::InvalidAttribute(format!(
                "evaluateAttribute: values[{i}] (vertex {}, component {}) is {}; {}",
                i / width,
                i % width,
                values[i],
                crate::mesh::unusable_because(values[i], "value")
            )));
        }
        self.table()?.evaluate(values, width, out)
    }
}

/// Untagged Catmull-Clark at the limit only: tags can make any face irregular, and other
/// schemes' regular pieces are not these patches.
fn patchable(options: &Options, tags: &Tags) -> bool {
    options.limit && tags.is_trivial() && options.schemes.iter().all(|&s| s == Scheme::CatmullClark)
}

/// The stencil build of an evaluator, with its regular patches when `patchable` allows them.
/// With normals, the patches' and the rows' tangents are both summed on differences (see
/// `crate::patches`), so that they agree with the GPU evaluator's, which runs the rows. The
/// patches' points get their rows from the patches too, not through the levels. An evaluator
/// that leaves its table out makes it here on first use, so the two are the same.
fn build_table(
    base: &HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<(StencilBuild, Option<RegularPatches>)> {
    let levels = u32::try_from(options.levels()).unwrap_or(u32::MAX);
    let (mut patches, mut owners) = (None, Vec::new());
    let mut find_patches = |faces: &PolyMesh| {
        let outputs = faces.positions.len() / 3;
        patches = RegularPatches::new(base, faces, levels, outputs);
        owners = patches.as_ref().map_or_else(Vec::new, |p| p.owners(outputs));
        owners.iter().map(|&(p, _)| p != NO_PATCH).collect()
    };
    let made_elsewhere: Option<MadeElsewhere<'_>> =
        patchable(options, tags).then_some(&mut find_patches);
    let mut build = build_stencils(base, attributes, options, tags, made_elsewhere)?;
    if let Some(patches) = &patches {
        let tangents = build.table.tangent_weights().is_some();
        let bytes = build.table.bytes() + patches.row_bytes(tangents);
        if bytes > options.max_bytes {
            return Err(Error::TooLarge(table_too_large(levels, bytes, options.max_bytes)));
        }
        build.table = patches.rows_into(build.table, &owners);
    }
    Ok((build, patches))
}

/// Loop's closed forms for the last level (`crate::regular_rings`), when every level is Loop's
/// and the table, with them, stays within `options.max_bytes`: they are an evaluation path,
/// never a reason to refuse a build. The level before is the control mesh at level 1, else a
/// refined table of its own, built here.
fn regular_rings(
    base: &HalfEdgeMesh,
    options: &Options,
    tags: &Tags,
    faces: &PolyMesh,
    outputs: usize,
    table_bytes: u64,
) -> Option<RegularRings> {
    // On a mesh that is not a 2-manifold, a vertex whose triangles close one fan can still
    // have a sharpened edge (a marked half of a non-manifold edge), which its triangles alone
    // do not show: those keep their rows.
    let levels = options.levels();
    let manifold = base.has_simple_edges() && !base.is_non_manifold();
    if levels == 0 || !manifold || options.schemes.iter().any(|&s| s != Scheme::Loop) {
        return None;
    }
    let budget = options.max_bytes.checked_sub(table_bytes)?;
    if faces.face_sizes.iter().any(|&n| n != 3) {
        return None;
    }
    let children = &faces.indices;
    // A mesh's cells are its half-edges in order, so their corners are `he_from`.
    let rings = if levels == 1 {
        RegularRings::new(
            &base.he_from,
            base.num_vertices(),
            children,
            outputs,
            Previous::Control,
            None,
        )?
    } else if let Some((previous, last)) = closed_previous(base, levels, &mut untold) {
        RegularRings::new(&last.he_from, last.num_vertices(), children, outputs, previous, None)?
    } else {
        let previous = Options {
            schemes: options.schemes[..levels - 1].to_vec(),
            limit: false,
            normals: false,
            max_bytes: budget,
            ..options.clone()
        };
        let build = build_stencils(base, &[], &previous, tags, None).ok()?;
        let vertices = build.table.num_stencils();
        let previous = Previous::Table(build.table);
        RegularRings::new(&build.mesh.indices, vertices, children, outputs, previous, None)?
    };
    (rings.bytes() <= budget).then_some(rings)
}

/// The level before the last of Loop's `levels` (2 or more) on a closed cage, by Loop's rules,
/// level by level, on the levels' topology alone (`refine::ptq`, which numbers them as the
/// refinement does), with that level's mesh; `None` unless every level is a closed mesh with a
/// closed fan at every vertex.
fn closed_previous<'b>(
    base: &'b HalfEdgeMesh,
    levels: usize,
    told: &mut Told<'_>,
) -> Option<(Previous, std::borrow::Cow<'b, HalfEdgeMesh>)> {
    let (mut steps, before) = loop_steps(base, levels.checked_sub(1)?, told)?;
    let last = triangle_child(&before);
    if told(levels - 1, &last).is_break() {
        return None;
    }
    let previous = if levels >= 3 {
        // From level 3 the vertex children come from the level before's own closed forms
        // (`Previous::Nested`); at level 2 that level is small enough to read as numbered.
        let step = steps.pop()?;
        let inner = RegularRings::new(
            &before.he_from,
            before.num_vertices(),
            &last.he_from,
            last.num_vertices(),
            if steps.is_empty() { Previous::Control } else { Previous::Steps(steps) },
            None,
        )?;
        Previous::Nested(Box::new(inner), step)
    } else {
        Previous::Steps(steps)
    };
    Some((previous, std::borrow::Cow::Owned(last)))
}

/// A `subdivide` of `base` with the limit or its normals ([`subdivide_mesh_borrowed_with`]'s
/// positions, normals, faces and channels, to f32 rounding, but no [`Refined::tangents`]), by
/// the closed forms an evaluator runs each frame, where they give every point: a closed cage
/// with no tags, Catmull-Clark or Loop at every level, and no attributes unless only the
/// normals are asked for (the points and channels then come from a `subdivide` without them).
/// The limit masks' walk on the last level, the mesh it needs and the two tangents' sums cost
/// a `subdivide` about twice what these take (the horse at level 2). `None` where they do not
/// apply: make that call.
///
/// [`Refined::tangents`]: crate::refined::Refined::tangents
pub fn subdivide_closed<'a>(
    base: &'a HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
) -> Result<Option<Refined<'a>>> {
    closed_call(base, attributes, options, tags, None)
}

/// [`subdivide_closed`] that tells `progress` after each level, as
/// [`crate::scheme::subdivide_mesh_borrowed_with_progress`] does, with the same counts: each
/// level before the last once its mesh is made, the last once the result is; a `Break` ends
/// the call with [`Error::Cancelled`]. Where the closed forms turn out not to apply after
/// levels were told (none of the shapes tried: a cage they cannot take shows at level 0), the
/// `None` leaves the call to the masks, which tell the levels again from the first.
pub fn subdivide_closed_with_progress<'a>(
    base: &'a HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    progress: &mut OnProgress<'_>,
) -> Result<Option<Refined<'a>>> {
    closed_call(base, attributes, options, tags, Some(progress))
}

/// [`subdivide_closed`], with `progress` told when given (the bindings pass theirs as an
/// `Option`).
pub(crate) fn closed_call<'a>(
    base: &'a HalfEdgeMesh,
    attributes: &[Attribute],
    options: &Options,
    tags: &Tags,
    mut progress: Option<&mut OnProgress<'_>>,
) -> Result<Option<Refined<'a>>> {
    let shaded = options.limit || options.normals;
    // The attributes' limit (face-varying values along seams included) is the masks' to give.
    let limited_channels = options.limit && !attributes.is_empty();
    let untagged = tags.is_trivial() && !tags.smooth_triangles;
    let levels = options.levels();
    if !shaded || limited_channels || levels == 0 || !untagged {
        return Ok(None);
    }
    // What the call would refuse, it refuses here, before any work.
    check_call(base, attributes, options)?;
    // Each level before the last is told as its mesh is made, as the levels of a `subdivide`
    // are, so that a stop comes before the rest of the work.
    let mut stopped = None;
    let mut told = |level, mesh: &HalfEdgeMesh| {
        let (faces, vertices) = (mesh.num_cells(), mesh.num_vertices());
        match report(progress.as_deref_mut(), Progress { level, levels, faces, vertices }) {
            Ok(()) => ControlFlow::Continue(()),
            Err(stop) => {
                stopped = Some(stop);
                ControlFlow::Break(())
            }
        }
    };
    let made = closed_forms(base, options, &mut told);
    if let Some(stop) = stopped {
        return Err(stop);
    }
    // Found out after levels were told (seldom: a fan that does not close shows at level 0),
    // the masks' call tells them again from the first.
    let Some((closed, faces)) = made else { return Ok(None) };
    let control = pad(base.positions.as_flattened());
    let mut positions = vec![[0.0; 3]; closed.num_points()];
    let mut normals = vec![[0.0; 3]; if options.normals { positions.len() } else { 0 }];
    match options.normals {
        true => closed.form().points_and_normals(&control, &mut positions, &mut normals),
        false => closed.form().points(&control, &mut positions),
    }
    let normals = options.normals.then(|| normals.into_flattened());
    let refined = if attributes.is_empty() {
        let poly = PolyMesh { positions: positions.into_flattened(), ..faces };
        Refined::poly(poly, Channels::default())
    } else {
        // The refined points, faces and channels of a call without normals, as the levels
        // number them: the closed forms' points and faces are the same, to f32 rounding.
        let plain = Options { normals: false, ..options.clone() };
        subdivide_mesh_borrowed_with(base, attributes, &plain, tags)?
    };
    report_result(progress, &refined, levels)?;
    Ok(Some(refined.with_given_normals(normals)))
}

/// The closed form that gives every output point of `options` on `base` from the levels'
/// smooth rules, with the output faces (see [`Evaluator::from_levels`]); `None` where none
/// applies or it would pass `options.max_bytes`. Tags and attributes are the caller's to rule
/// out.
fn closed_forms(
    base: &HalfEdgeMesh,
    options: &Options,
    told: &mut Told<'_>,
) -> Option<(Closed, PolyMesh)> {
    let levels = options.levels();
    let all = |scheme| !options.schemes.is_empty() && options.schemes.iter().all(|&s| s == scheme);
    let made = if options.limit && all(Scheme::CatmullClark) && crate::patches::all_regular(base) {
        // Every point on a patch (a closed all-quad cage of valence 4: a torus).
        catmull_clark_faces(base, levels, told).and_then(|(faces, outputs)| {
            let patches = RegularPatches::new(base, &faces, u32::try_from(levels).ok()?, outputs)?;
            patches.rest().is_empty().then_some((Closed::Patches(patches), faces))
        })
    } else if !options.limit && !options.normals && all(Scheme::CatmullClark) {
        SmoothLevels::catmull_clark(base, levels, told)
            .map(|(form, faces)| (Closed::Levels(form), faces))
    } else if !options.limit && !options.normals && all(Scheme::Loop) {
        SmoothLevels::loop_(base, levels, told).map(|(form, faces)| (Closed::Levels(form), faces))
    } else if all(Scheme::Loop) {
        // The limit, or refined points with the limit's normals.
        closed_loop_rings(base, levels, !options.limit, told)
            .map(|(form, faces)| (Closed::Rings(form), faces))
    } else if all(Scheme::CatmullClark) && (!options.limit || !crate::patches::any_regular(base)) {
        // The limit (where no patch is), or refined points with the limit's normals.
        catmull_clark_steps(base, levels, told).and_then(|(steps, last)| {
            let faces = quad_faces(&last);
            Some((Closed::Quads(QuadRings::new(steps, &faces, options.limit)?), faces))
        })
    } else {
        None
    };
    made.filter(|(closed, _)| closed.bytes() <= options.max_bytes)
}

/// Loop's limit on a closed cage when its closed forms give every point, with the output
/// faces (as `refine::ptq` lists them), for an evaluator that leaves its table out. With
/// `refined`, the last level's own points with the limit's normals.
fn closed_loop_rings(
    base: &HalfEdgeMesh,
    levels: usize,
    refined: bool,
    told: &mut Told<'_>,
) -> Option<(RegularRings, PolyMesh)> {
    if !base.has_simple_edges() || base.is_non_manifold() {
        return None;
    }
    let (previous, last) = match levels {
        0 => return None,
        1 => (Previous::Control, std::borrow::Cow::Borrowed(base)),
        _ => closed_previous(base, levels, told)?,
    };
    let faces = triangle_faces(&last);
    let outputs = crate::refine::ptq::num_child_vertices(&last);
    let (parents, vertices) = (&last.he_from, last.num_vertices());
    let refined = match refined {
        true => Some(Step::new(&last)?),
        false => None,
    };
    let rings = RegularRings::new(parents, vertices, &faces.indices, outputs, previous, refined)?;
    (rings.num_points() == outputs && rings.rest().is_empty()).then_some((rings, faces))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cage of few neighbourhoods (the icosahedron's twelve vertices are all alike) shares
    /// its limit rows' weights, and the frame from the shared weights is the table's own, bit
    /// for bit.
    #[test]
    fn shared_weights_give_the_tables_frame() {
        let mesh = crate::shapes::icosahedron();
        let base = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let options = Options { limit: true, normals: true, ..Options::new(Scheme::Loop, 3) };
        // A crease, so that every point comes from its row (untagged, Loop's closed forms
        // would give them all; `crate::regular_rings`).
        let crease =
            crate::tags::Crease { vertices: [mesh.indices[0], mesh.indices[1]], sharpness: 2.0 };
        let tags = Tags { creases: vec![crease], ..Tags::default() };
        let evaluator = Evaluator::new(&base, &[], &options, &tags).unwrap();
        assert!(evaluator.shared.is_some() && !matches!(evaluator.closed, Some(Closed::Rings(_))));
        let control: Vec<f32> =
            mesh.positions.iter().enumerate().map(|(i, x)| x * (1.0 + i as f32 / 100.0)).collect();
        let n = 3 * evaluator.num_vertices();
        let (mut positions, mut normals) = (vec![0.0; n], vec![0.0; n]);
        evaluator.evaluate(&control, &mut positions, Some(&mut normals)).unwrap();
        let (mut want, mut want_normals) = (vec![0.0; n], vec![0.0; n]);
        evaluator
            .table()
            .unwrap()
            .evaluate_with_normals(&control, &mut want, &mut want_normals)
            .unwrap();
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&positions), bits(&want));
        assert_eq!(bits(&normals), bits(&want_normals));
    }
}
