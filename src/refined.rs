//! The result of a call, whose arrays can be copied out piece by piece.

use crate::attributes::Attribute;
use crate::mesh::{chunked, HalfEdgeMesh, PolyMesh};
use crate::refine::pqq;
use std::borrow::Cow;

/// A subdivision result. After an untagged quad split (Catmull-Clark, bilinear) its face list is
/// implicit: it keeps the last level's parent mesh, from which the faces follow by index
/// arithmetic ([`pqq`]), so that a caller can copy indices, face sizes and triangles out in
/// cache-sized pieces without the arrays ever being stored whole (the wasm bindings do). The
/// pieces, joined, are the arrays of [`Refined::into_poly`].
///
/// The lifetime is the base mesh's when [`crate::scheme::subdivide_mesh_borrowed`] made the result with a single
/// quad split (the base is then the parent its faces follow from); `'static` otherwise.
pub struct Refined<'a> {
    form: Form<'a>,
    attributes: Vec<Attribute>,
    /// The limit tangents and normals, when the limit was asked for
    /// ([`crate::scheme::subdivide_limit`]); the positions are then the limit positions.
    limit: Option<Box<[Vec<f32>; 3]>>,
}

enum Form<'a> {
    Poly(PolyMesh),
    /// The last level's positions and the mesh it refined.
    Quads {
        positions: Vec<f32>,
        parent: Box<Cow<'a, HalfEdgeMesh>>,
    },
}

impl<'a> Refined<'a> {
    /// A result whose faces are listed.
    pub(crate) fn poly(poly: PolyMesh, attributes: Vec<Attribute>) -> Self {
        Refined { form: Form::Poly(poly), attributes, limit: None }
    }

    /// A result whose faces are the implicit quads of one split of `parent`.
    pub(crate) fn quads(
        positions: Vec<f32>,
        parent: Cow<'a, HalfEdgeMesh>,
        attributes: Vec<Attribute>,
    ) -> Self {
        Refined {
            form: Form::Quads { positions, parent: Box::new(parent) },
            attributes,
            limit: None,
        }
    }

    /// A result at the limit: `poly`'s positions are limit positions, with the two limit
    /// tangents and the unit normal of each vertex (three floats each).
    pub(crate) fn limit(
        poly: PolyMesh,
        attributes: Vec<Attribute>,
        [first, second]: [Vec<f32>; 2],
        normals: Vec<f32>,
    ) -> Self {
        Refined {
            form: Form::Poly(poly),
            attributes,
            limit: Some(Box::new([first, second, normals])),
        }
    }

    /// The limit tangents (OpenSubdiv's `tan1` and `tan2`, three floats per vertex) when the
    /// result is at the limit ([`crate::scheme::subdivide_limit`]).
    pub fn tangents(&self) -> Option<[&[f32]; 2]> {
        self.limit.as_deref().map(|[a, b, _]| [&a[..], &b[..]])
    }

    /// The unit limit normals (three floats per vertex; zero where the tangents are degenerate)
    /// when the result is at the limit: `tangents[0] × tangents[1]`, normalised, which points
    /// to the side from which the faces are wound counter-clockwise (outward on a closed mesh
    /// wound so, as the OBJ convention has it).
    pub fn normals(&self) -> Option<&[f32]> {
        self.limit.as_deref().map(|[_, _, n]| &n[..])
    }

    /// The refined attribute channels, in the order they were given.
    pub fn attributes(&self) -> &[Attribute] {
        &self.attributes
    }

    /// The flat arrays and the attribute channels.
    pub fn into_parts(self) -> (PolyMesh, Vec<Attribute>) {
        let Refined { form, attributes, .. } = self;
        (Refined { form, attributes: Vec::new(), limit: None }.into_poly(), attributes)
    }

    pub fn positions(&self) -> &[f32] {
        match &self.form {
            Form::Poly(poly) => &poly.positions,
            Form::Quads { positions, .. } => positions,
        }
    }

    pub fn num_faces(&self) -> usize {
        match &self.form {
            Form::Poly(poly) => poly.num_faces(),
            Form::Quads { parent, .. } => parent.num_half_edges(),
        }
    }

    /// Length of the face index list.
    pub fn num_indices(&self) -> usize {
        match &self.form {
            Form::Poly(poly) => poly.indices.len(),
            Form::Quads { parent, .. } => 4 * parent.num_half_edges(),
        }
    }

    /// Length of the fan triangulation ([`PolyMesh::triangles`]).
    pub fn num_triangle_indices(&self) -> usize {
        match &self.form {
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
        match &self.form {
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
        match &self.form {
            Form::Poly(_) => None,
            Form::Quads { .. } => Some(4),
        }
    }

    /// The face sizes, in consecutive pieces.
    pub fn face_size_chunks(&self, mut sink: impl FnMut(&[u32])) {
        match &self.form {
            Form::Poly(poly) => sink(&poly.face_sizes),
            Form::Quads { parent, .. } => chunked(parent.num_half_edges(), |_| [4], sink),
        }
    }

    /// The flat arrays.
    pub fn into_poly(self) -> PolyMesh {
        match self.form {
            Form::Poly(poly) => poly,
            Form::Quads { positions, parent } => PolyMesh {
                positions,
                indices: pqq::child_face_indices(&parent),
                face_sizes: vec![4; parent.num_half_edges()],
            },
        }
    }
}
