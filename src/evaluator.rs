//! Refine once, evaluate every frame: an [`Evaluator`] holds a call's output topology and its
//! stencil table ([`crate::stencil`]), so that new control positions (a skinned or morphed
//! cage) give the call's positions and normals with one sparse product and no topology work.
//! OpenSubdiv's `Far::StencilTableFactory` / `LimitStencilTableFactory` with
//! `Osd::CpuEvaluator::EvalStencils`, behind one type.

use crate::attributes::Attribute;
use crate::error::{Error, Result};
use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::options::{Options, Scheme};
use crate::patches::{RegularPatches, NO_PATCH};
use crate::scheme::{build_stencils, table_too_large, MadeElsewhere};
use crate::shared_weights::SharedWeights;
use crate::stencil::{pad, AllRows, Blocks, StencilTable};
use crate::tags::Tags;
use std::sync::OnceLock;

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
    table: StencilTable,
    /// The output faces; the positions are left empty (see `at_build`).
    faces: PolyMesh,
    attributes: Vec<Attribute>,
    /// The control positions the evaluator was built with.
    control: Vec<f32>,
    /// The output positions and normals of `control`, on first use.
    at_build: OnceLock<(Vec<f32>, Option<Vec<f32>>)>,
    source: NormalSource,
    /// Catmull-Clark limit points on regular faces, evaluated as bicubic patches rather than
    /// from their (much larger) stencil rows, with their normals; the table's rows give the
    /// others (see `Evaluator::new`).
    patches: Option<RegularPatches>,
    /// How a frame sums the table's rows with tangents, made on the first frame (see
    /// [`RowSums`]).
    row_sums: OnceLock<RowSums>,
    /// How many output faces each base face gives, for [`Blocks`].
    runs: Vec<u32>,
    /// The caller's memory limit, which the table and the blocks share.
    max_bytes: u64,
}

/// How a frame sums the rows of a table with tangents: grouped by base face four at a time
/// ([`Blocks`]), or where they do not fit in `max_bytes` beside the table, a row at a time with
/// each distinct weight list once ([`SharedWeights`]), or as the table has them. Made on the
/// first frame, not with the evaluator: they serve the CPU's frames only, and an evaluator
/// whose frames run on the GPU (`js/webgpu.js` reads the table) never needs their memory
/// (the horse's level-2 Catmull-Clark blocks: 174 MB) or the time to make them.
#[derive(Clone, Debug)]
enum RowSums {
    Blocks(Blocks),
    Shared(SharedWeights),
    Table,
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
        // Untagged Catmull-Clark at the limit only: tags can make any face irregular, and
        // other schemes' regular pieces are not these patches. With normals, the patches' and
        // the rows' tangents are both summed on differences (see `crate::patches`), so that
        // they agree with the GPU evaluator's, which runs the rows. The patches' points get
        // their rows from the patches too, not through the levels.
        let patchable = options.limit
            && tags.is_trivial()
            && options.schemes.iter().all(|&s| s == Scheme::CatmullClark);
        let levels = u32::try_from(options.levels()).unwrap_or(u32::MAX);
        let (mut patches, mut owners) = (None, Vec::new());
        let mut find_patches = |faces: &PolyMesh| {
            let outputs = faces.positions.len() / 3;
            patches = RegularPatches::new(base, faces, levels, outputs);
            owners = patches.as_ref().map_or_else(Vec::new, |p| p.owners(outputs));
            owners.iter().map(|&(p, _)| p != NO_PATCH).collect()
        };
        let made_elsewhere: Option<MadeElsewhere<'_>> = patchable.then_some(&mut find_patches);
        let mut build = build_stencils(base, attributes, options, tags, made_elsewhere)?;
        if let Some(patches) = &patches {
            let tangents = build.table.tangent_weights().is_some();
            let bytes = build.table.bytes() + patches.row_bytes(tangents);
            if bytes > options.max_bytes {
                return Err(Error::TooLarge(table_too_large(levels, bytes, options.max_bytes)));
            }
            build.table = patches.rows_into(build.table, &owners);
        }
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
        let faces = &build.mesh;
        let runs = match source {
            NormalSource::Tangents => base_face_runs(base, options, tags, faces.face_sizes.len()),
            _ => Vec::new(),
        };
        Ok(Evaluator {
            table: build.table,
            faces: build.mesh,
            attributes: channels,
            control: base.positions.as_flattened().to_vec(),
            at_build: OnceLock::new(),
            source,
            patches,
            row_sums: OnceLock::new(),
            runs,
            max_bytes: options.max_bytes,
        })
    }

    /// How a frame sums the rows (see [`RowSums`]), made on first use.
    fn row_sums(&self) -> &RowSums {
        self.row_sums.get_or_init(|| {
            let table = &self.table;
            let Some([first, second]) = table.tangent_weights() else {
                return RowSums::Table;
            };
            let rest = self.patches.as_ref().map(|p| p.rest());
            let mut covered = Vec::new();
            if let Some(rest) = rest {
                covered = vec![false; table.num_stencils()];
                rest.iter().for_each(|&r| covered[r as usize] = true);
            }
            let room = self.max_bytes.saturating_sub(table.bytes());
            let faces = &self.faces;
            let (indices, sizes) = (&faces.indices, &faces.face_sizes);
            if let Some(blocks) = Blocks::new(table, indices, sizes, &self.runs, &covered, room) {
                return RowSums::Blocks(blocks);
            }
            let rows: Vec<usize> = match rest {
                Some(rest) => rest.iter().map(|&r| r as usize).collect(),
                None => (0..table.num_stencils()).collect(),
            };
            let weights = [table.weights(), first, second];
            match SharedWeights::new(table.offsets(), weights, &rows) {
                Some(shared) => RowSums::Shared(shared),
                None => RowSums::Table,
            }
        })
    }

    /// The stencil table (positions, and the tangents' weights when normals come from it).
    pub fn table(&self) -> &StencilTable {
        &self.table
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
            match self.evaluate(&self.control, &mut positions, normals.as_deref_mut()) {
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
        self.table.num_control_vertices()
    }

    /// How many output vertices [`Evaluator::evaluate`] computes as bicubic patches rather than
    /// from their stencil rows: Catmull-Clark at the limit without tags, on the base faces
    /// whose four corners are smooth interior vertices with four quads each (the limit surface
    /// there is a uniform bicubic B-spline patch). Same positions and normals to f32 rounding,
    /// about 2.7 times faster per point without normals and 1.8 with them (torus, wasm).
    pub fn patch_vertices(&self) -> usize {
        self.patches.as_ref().map_or(0, RegularPatches::num_points)
    }

    /// Number of output vertices.
    pub fn num_vertices(&self) -> usize {
        self.table.num_stencils()
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
        if let Some(i) = control.iter().position(|x| !x.is_finite()) {
            return Err(Error::InvalidAttribute(format!(
                "evaluate: positions[{i}] (vertex {}, {}) is {}; every coordinate must be finite",
                i / 3,
                ["x", "y", "z"][i % 3],
                control[i]
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
        if let Some(patches) = &self.patches {
            let control = pad(control);
            let (positions, _) = positions.as_chunks_mut::<3>();
            match (self.source, normals) {
                (NormalSource::Tangents, Some(normals)) => {
                    let (normals, _) = normals.as_chunks_mut::<3>();
                    let rest = patches.rest();
                    match self.row_sums() {
                        RowSums::Blocks(blocks) => blocks.evaluate(&control, positions, normals),
                        RowSums::Shared(shared) => {
                            let shared = Some(shared);
                            self.table
                                .points_and_normals(&control, rest, positions, normals, shared)
                        }
                        RowSums::Table => {
                            self.table.points_and_normals(&control, rest, positions, normals, None)
                        }
                    }
                    patches.evaluate_with_normals(&control, positions, normals);
                }
                _ => {
                    self.table.points(&control, patches.rest(), positions);
                    patches.evaluate(&control, positions);
                }
            }
            return Ok(());
        }
        match (self.source, normals) {
            (NormalSource::Tangents, Some(normals)) => match self.row_sums() {
                RowSums::Blocks(blocks) => {
                    let control = pad(control);
                    let (positions, _) = positions.as_chunks_mut::<3>();
                    let (normals, _) = normals.as_chunks_mut::<3>();
                    blocks.evaluate(&control, positions, normals);
                    Ok(())
                }
                RowSums::Shared(shared) => {
                    let control = pad(control);
                    let (positions, _) = positions.as_chunks_mut::<3>();
                    let (normals, _) = normals.as_chunks_mut::<3>();
                    let rows = AllRows(self.num_vertices());
                    self.table.points_and_normals(&control, rows, positions, normals, Some(shared));
                    Ok(())
                }
                RowSums::Table => self.table.evaluate_with_normals(control, positions, normals),
            },
            (NormalSource::Faces, Some(normals)) => {
                self.table.evaluate(control, 3, positions)?;
                let mesh = &self.faces;
                crate::limit::face_normals_into(
                    positions,
                    &mesh.indices,
                    &mesh.face_sizes,
                    normals,
                );
                Ok(())
            }
            _ => self.table.evaluate(control, 3, positions),
        }
    }

    /// Any vertex-varying data (colours, skin weights, a morph target's deltas) through the
    /// positions' stencils: `width` floats per control vertex in, per output vertex out.
    pub fn evaluate_attribute(&self, values: &[f32], width: usize, out: &mut [f32]) -> Result<()> {
        let vertices = self.num_control_vertices();
        if Some(values.len()) != vertices.checked_mul(width) {
            return Err(Error::InvalidAttribute(format!(
                "evaluateAttribute: values has {} floats; expected {width} (itemSize) for each of the {vertices} vertices of the mesh the evaluator was built from",
                values.len()
            )));
        }
        self.table.evaluate(values, width, out)
    }
}

/// How many output faces each base face gives, in base-face order, for grouping the rows by
/// base face ([`Blocks`]): each level of Catmull-Clark's and bilinear's split gives an n-gon n
/// children, Loop's, midpoint's and Quad/Triangle's a face four, and every split numbers a
/// parent's children together, in the parents' order; holes' faces are left out. Where the
/// counts do not add up to the output's faces (another scheme at some level), runs of the
/// average count instead: a worse grouping, not a wrong one.
fn base_face_runs(base: &HalfEdgeMesh, options: &Options, tags: &Tags, faces: usize) -> Vec<u32> {
    let cells = base.num_cells();
    let mut runs = vec![1u64; cells];
    for &hole in &tags.holes {
        if let Some(run) = runs.get_mut(hole as usize) {
            *run = 0;
        }
    }
    let mut known = true;
    for (level, scheme) in options.schemes.iter().enumerate() {
        match scheme {
            Scheme::CatmullClark | Scheme::Bilinear if level == 0 => {
                for (c, run) in runs.iter_mut().enumerate() {
                    let size = base.cell_offsets[c + 1] - base.cell_offsets[c];
                    *run *= u64::from(size);
                }
            }
            Scheme::CatmullClark
            | Scheme::Bilinear
            | Scheme::Loop
            | Scheme::Midpoint
            | Scheme::QuadTriangle => runs.iter_mut().for_each(|run| *run *= 4),
            _ => known = false,
        }
    }
    if known && runs.iter().sum::<u64>() == faces as u64 {
        return runs.into_iter().map(|n| u32::try_from(n).unwrap_or(u32::MAX)).collect();
    }
    let average = (faces / cells.max(1)).clamp(1, u32::MAX as usize) as u32;
    vec![average; faces.div_ceil(average as usize)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tags::Crease;

    /// A cage of few neighbourhoods (the icosahedron's twelve vertices are all alike) shares
    /// its limit rows' weights, and the frame from the shared weights is the table's own, bit
    /// for bit. (With room for blocks, as here, the evaluator itself uses those instead.)
    #[test]
    fn shared_weights_give_the_tables_frame() {
        let mesh = crate::shapes::icosahedron();
        let base = HalfEdgeMesh::from_poly(&mesh).unwrap();
        let options = Options { limit: true, normals: true, ..Options::new(Scheme::Loop, 3) };
        let evaluator = Evaluator::new(&base, &[], &options, &Tags::default()).unwrap();
        let table = evaluator.table();
        let [first, second] = table.tangent_weights().unwrap();
        let all: Vec<usize> = (0..table.num_stencils()).collect();
        let shared = SharedWeights::new(table.offsets(), [table.weights(), first, second], &all);
        let shared = shared.unwrap();
        let control: Vec<f32> =
            mesh.positions.iter().enumerate().map(|(i, x)| x * (1.0 + i as f32 / 100.0)).collect();
        let n = evaluator.num_vertices();
        let (mut positions, mut normals) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
        let rows = AllRows(n);
        table.points_and_normals(&pad(&control), rows, &mut positions, &mut normals, Some(&shared));
        let (mut want, mut want_normals) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        table.evaluate_with_normals(&control, &mut want, &mut want_normals).unwrap();
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(positions.as_flattened()), bits(&want));
        assert_eq!(bits(normals.as_flattened()), bits(&want_normals));
    }

    /// An evaluator with limit normals groups its rows into blocks by base face, and their
    /// frame is the rows' to f32 rounding, every row written: Loop and Catmull-Clark, with
    /// creases, holes, n-gons, regular patches beside the blocks, and with no room for the
    /// blocks (the shared rows then). Also a wasm test: there the blocks and normals run in
    /// lanes.
    #[cfg_attr(target_arch = "wasm32", wasm_bindgen_test::wasm_bindgen_test)]
    #[cfg_attr(not(target_arch = "wasm32"), test)]
    fn blocks_give_the_rows_frame() {
        let mut creased = crate::shapes::grid_with_hole(6, 5, 2..4, 1..3);
        creased.positions.iter_mut().skip(2).step_by(3).enumerate().for_each(|(i, z)| {
            *z = (i as f32 * 0.7).sin() * 0.3;
        });
        let crease = |a, b, sharpness| Crease { vertices: [a, b], sharpness };
        let creased_tags = Tags {
            creases: vec![crease(0, 1, 2.0), crease(1, 2, 2.0), crease(7, 8, 1.5)],
            holes: vec![0, 5],
            ..Tags::default()
        };
        let cases = [
            (crate::shapes::icosahedron(), Scheme::Loop, 3, Tags::default(), true),
            (
                crate::shapes::torus_triangles(9, 7, 1.0, 0.3),
                Scheme::Loop,
                2,
                Tags::default(),
                true,
            ),
            (crate::shapes::prism(5), Scheme::CatmullClark, 2, Tags::default(), true),
            (crate::shapes::dodecahedron(), Scheme::CatmullClark, 3, Tags::default(), true),
            (creased.clone(), Scheme::CatmullClark, 2, creased_tags.clone(), true),
            (creased, Scheme::CatmullClark, 2, creased_tags, false),
        ];
        for (mesh, scheme, levels, tags, room) in cases {
            let what = format!("{scheme:?} L{levels}, {} faces, room {room}", mesh.num_faces());
            let base = HalfEdgeMesh::from_poly(&mesh).unwrap();
            let mut options =
                Options { limit: true, normals: true, ..Options::new(scheme, levels) };
            if !room {
                let table = Evaluator::new(&base, &[], &options, &tags).unwrap().table.bytes();
                options.max_bytes = table + 64;
            }
            let evaluator = Evaluator::new(&base, &[], &options, &tags).unwrap();
            let blocks = matches!(evaluator.row_sums(), RowSums::Blocks(_));
            assert_eq!(blocks, room, "{what}");
            let control: Vec<f32> = mesh
                .positions
                .iter()
                .enumerate()
                .map(|(i, x)| x * (1.0 + (i % 7) as f32 / 50.0))
                .collect();
            let n = 3 * evaluator.num_vertices();
            let (mut positions, mut normals) = (vec![f32::NAN; n], vec![f32::NAN; n]);
            evaluator.evaluate(&control, &mut positions, Some(&mut normals)).unwrap();
            let (mut want, mut want_normals) = (vec![0.0; n], vec![0.0; n]);
            let table = evaluator.table();
            table.evaluate_with_normals(&control, &mut want, &mut want_normals).unwrap();
            for (v, (got, want)) in positions.chunks(3).zip(want.chunks(3)).enumerate() {
                let close = got.iter().zip(want).all(|(g, w)| (g - w).abs() <= 1e-5);
                assert!(close, "{what}: vertex {v}: {got:?} against {want:?}");
            }
            for (v, (got, want)) in normals.chunks(3).zip(want_normals.chunks(3)).enumerate() {
                // Zero where the tangents are (a vertex only holes use): zero in both.
                let dot: f32 = got.iter().zip(want).map(|(g, w)| g * w).sum();
                let zero = |n: &[f32]| n.iter().all(|&x| x == 0.0);
                let same = dot > 1.0 - 1e-6 || zero(got) && zero(want);
                assert!(same, "{what}: normal {v}: {got:?} against {want:?}");
            }
        }
    }
}
