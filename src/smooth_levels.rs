//! Refined frames of a closed cage in closed form: each frame makes every level's points by the
//! scheme's smooth rules, the step Catmull-Clark's limit takes on triangle cages
//! ([`crate::quad_rings`]) and the one Loop's takes ([`crate::regular_rings`]), and the last
//! level goes straight to the output.
//!
//! Why: a refined row of the horse at Catmull-Clark level 2 holds some 11 control points (8
//! bytes each) and gathers them from anywhere in the cage; a step reads about 5 points of the
//! level before, mostly near each other, and a face point 4. The levels before the last are a
//! quarter of the frame's points and less, so a frame costs little more than its last level.
//! No frame reads the table: the evaluator makes it only when asked for it (`stencils()`, the
//! GPU; see `Evaluator::table`).

use crate::mesh::{HalfEdgeMesh, PolyMesh};
use crate::quad_rings::QuadStep;
use crate::regular_rings::{fan_masks, FanMasks, Step};
use crate::stencil::{ClosedForms, StencilTable, Written};
use std::borrow::Cow;
use std::ops::ControlFlow;

/// Every level of a closed cage by one scheme's smooth rules.
#[derive(Clone, Debug)]
pub(crate) enum SmoothLevels {
    /// Catmull-Clark: vertex points, face points, edge points (as `refine::pqq` numbers them).
    Quads(Vec<QuadStep>),
    /// Loop: vertex children, edge children (as `refine::ptq` numbers them), with each
    /// valence's weights.
    Triangles(Vec<Step>, Vec<FanMasks>),
}

impl SmoothLevels {
    /// Catmull-Clark's `levels` levels of `base`, with the output faces (quads, as
    /// `refine::pqq` lists them; no positions); `None` unless every level before the last is a
    /// closed cage whose every vertex has a closed fan of 3 to `MAX_VALENCE` faces.
    pub(crate) fn catmull_clark(
        base: &HalfEdgeMesh,
        levels: usize,
        told: &mut Told<'_>,
    ) -> Option<(Self, PolyMesh)> {
        let (steps, last) = catmull_clark_steps(base, levels, told)?;
        Some((SmoothLevels::Quads(steps), quad_faces(&last)))
    }

    /// Loop's `levels` levels of `base`, with the output faces (triangles, as `refine::ptq`
    /// lists them); `None` unless every level before the last is a closed triangle mesh with a
    /// closed fan at every vertex.
    pub(crate) fn loop_(
        base: &HalfEdgeMesh,
        levels: usize,
        told: &mut Told<'_>,
    ) -> Option<(Self, PolyMesh)> {
        let (steps, last) = loop_steps(base, levels, told)?;
        Some((SmoothLevels::Triangles(steps, fan_masks()), triangle_faces(&last)))
    }

    /// Number of output points.
    pub(crate) fn outputs(&self) -> usize {
        match self {
            SmoothLevels::Quads(steps) => steps.last().map_or(0, QuadStep::outputs),
            SmoothLevels::Triangles(steps, _) => steps.last().map_or(0, Step::outputs),
        }
    }

    /// The levels as stencil tables, one per level, each on the level before's vertices (see
    /// `Evaluator::level_tables`), written from the steps: no rule walk, no composition.
    pub(crate) fn tables(&self) -> Vec<StencilTable> {
        match self {
            SmoothLevels::Quads(steps) => steps.iter().map(QuadStep::table).collect(),
            SmoothLevels::Triangles(steps, masks) => steps.iter().map(|s| s.table(masks)).collect(),
        }
    }

    /// What a frame reads besides its input: the steps' topology.
    pub(crate) fn bytes(&self) -> u64 {
        match self {
            SmoothLevels::Quads(steps) => steps.iter().map(QuadStep::bytes).sum(),
            SmoothLevels::Triangles(steps, _) => steps.iter().map(Step::bytes).sum(),
        }
    }
}

/// Catmull-Clark's steps of `levels` levels from `base`, with the mesh of the level before the
/// last (see [`SmoothLevels::catmull_clark`]; [`quad_faces`] of it are the output faces).
pub(crate) fn catmull_clark_steps<'b>(
    base: &'b HalfEdgeMesh,
    levels: usize,
    told: &mut Told<'_>,
) -> Option<(Vec<QuadStep>, Cow<'b, HalfEdgeMesh>)> {
    levels_of(base, levels, QuadStep::new, quad_child, told)
}

/// Loop's steps of `levels` levels from `base`, with the mesh of the level before the last
/// (see [`SmoothLevels::loop_`]).
pub(crate) fn loop_steps<'b>(
    base: &'b HalfEdgeMesh,
    levels: usize,
    told: &mut Told<'_>,
) -> Option<(Vec<Step>, Cow<'b, HalfEdgeMesh>)> {
    levels_of(base, levels, Step::new, triangle_child, told)
}

/// Catmull-Clark's output faces after `levels` levels of `base` and the number of output
/// vertices, from the levels' topology alone.
pub(crate) fn catmull_clark_faces(
    base: &HalfEdgeMesh,
    levels: usize,
    told: &mut Told<'_>,
) -> Option<(PolyMesh, usize)> {
    let (_, last) = levels_of(base, levels, |_| Some(()), quad_child, told)?;
    Some((quad_faces(&last), crate::refine::pqq::num_child_vertices(&last)))
}

/// The child mesh of `mesh` by the quad split, topology only (its positions left at zero).
fn quad_child(mesh: &HalfEdgeMesh) -> HalfEdgeMesh {
    let zeros = vec![[0.0; 3]; crate::refine::pqq::num_child_vertices(mesh)];
    crate::refine::pqq::child_mesh(mesh, zeros)
}

/// The child mesh of `mesh` by the triangle split, topology only (its positions left at zero).
pub(crate) fn triangle_child(mesh: &HalfEdgeMesh) -> HalfEdgeMesh {
    let zeros = vec![[0.0; 3]; crate::refine::ptq::num_child_vertices(mesh)];
    crate::refine::ptq::child_mesh(mesh, zeros)
}

/// The quads of `mesh`'s quad split, without positions.
pub(crate) fn quad_faces(mesh: &HalfEdgeMesh) -> PolyMesh {
    faces_of(crate::refine::pqq::child_face_indices(mesh), 4)
}

/// The triangles of `mesh`'s triangle split, without positions.
pub(crate) fn triangle_faces(mesh: &HalfEdgeMesh) -> PolyMesh {
    faces_of(crate::refine::ptq::child_face_indices(mesh), 3)
}

/// Faces of `n` corners each, without positions.
fn faces_of(indices: Vec<u32>, n: u32) -> PolyMesh {
    let face_sizes = vec![n; indices.len() / n as usize];
    PolyMesh { positions: Vec::new(), indices, face_sizes }
}

/// The steps of `levels` levels from `base` and the mesh of the level before the last: `step`
/// of each level's mesh, `child` making the next (the last level's mesh is not made: its
/// points are the output).
fn levels_of<'b, S>(
    base: &'b HalfEdgeMesh,
    levels: usize,
    step: impl Fn(&HalfEdgeMesh) -> Option<S>,
    child: impl Fn(&HalfEdgeMesh) -> HalfEdgeMesh,
    told: &mut Told<'_>,
) -> Option<(Vec<S>, Cow<'b, HalfEdgeMesh>)> {
    let mut steps = Vec::with_capacity(levels);
    let mut mesh = Cow::Borrowed(base);
    for level in 0..levels {
        steps.push(step(&mesh)?);
        if level + 1 < levels {
            mesh = Cow::Owned(child(&mesh));
            if told(level + 1, &mesh).is_break() {
                return None;
            }
        }
    }
    (levels > 0).then_some((steps, mesh))
}

/// Told the mesh of each level made before the last (its number, from 1), so that a call can
/// tell its progress as it goes; `Break` stops the making (the maker then gives `None`).
pub(crate) type Told<'t> = dyn FnMut(usize, &HalfEdgeMesh) -> ControlFlow<()> + 't;

/// A [`Told`] for makers with no one to tell.
pub(crate) fn untold(_: usize, _: &HalfEdgeMesh) -> ControlFlow<()> {
    ControlFlow::Continue(())
}

/// The levels before the last, from the padded control points, then the last into `out`.
fn run<S>(
    steps: &[S],
    control: &[[f32; 4]],
    out: &mut [[f32; 3]],
    padded: impl Fn(&S, &[[f32; 4]]) -> Vec<[f32; 4]>,
    last: impl Fn(&S, &[[f32; 4]], &mut Written<'_>),
) {
    let Some((final_step, before)) = steps.split_last() else { return };
    let mut points = Cow::Borrowed(control);
    for step in before {
        points = padded(step, &points).into();
    }
    last(final_step, &points, &mut Written::new(out));
}

impl ClosedForms for SmoothLevels {
    fn rest(&self) -> &[u32] {
        &[]
    }

    fn points(&self, control: &[[f32; 4]], positions: &mut [[f32; 3]]) {
        match self {
            SmoothLevels::Quads(steps) => {
                run(steps, control, positions, QuadStep::padded, |s, p, out| s.apply(p, out))
            }
            SmoothLevels::Triangles(steps, masks) => run(
                steps,
                control,
                positions,
                |s, p| s.padded(p, masks),
                |s, p, out| s.apply(p, masks, out),
            ),
        }
    }

    /// The points only: the levels serve evaluators without normals (with them, the last
    /// level's points come with the limit's normals from `crate::quad_rings` and
    /// `crate::regular_rings`).
    fn points_and_normals(
        &self,
        control: &[[f32; 4]],
        positions: &mut [[f32; 3]],
        _normals: &mut [[f32; 3]],
    ) {
        self.points(control, positions);
    }
}
