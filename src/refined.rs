//! The result of a call, whose arrays can be copied out piece by piece.

use crate::attributes::{Attribute, Channels};
use crate::fvar::SeamCorners;
use crate::mesh::{chunked, HalfEdgeMesh, PolyMesh};
use crate::refine::pqq;
use std::borrow::Cow;
use std::sync::OnceLock;

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
    /// The face-varying attributes whose indices are the faces' own but near seams (their
    /// `indices` are empty): each one's place in `attributes` and its corners near seams. Like
    /// the implicit faces, they are made piece by piece ([`Refined::index_and_triangle_chunks`]).
    seam_corners: Vec<(usize, SeamCorners)>,
    /// `attributes` with every index list whole, made when [`Refined::attributes`] is first
    /// called on a result with `seam_corners`.
    listed: OnceLock<Vec<Attribute>>,
    /// The limit tangents of the last level's vertices, when its scheme has limit masks and
    /// the limit or normals were asked for.
    tangents: Option<Box<[Vec<f32>; 2]>>,
    /// Unit vertex normals, when asked for ([`crate::options::Options::normals`]).
    normals: Option<Vec<f32>>,
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
    fn new(form: Form<'a>, channels: Channels) -> Self {
        let Channels { attributes, seam_corners } = channels;
        Refined {
            form,
            attributes,
            seam_corners,
            listed: OnceLock::new(),
            tangents: None,
            normals: None,
        }
    }

    /// A result whose faces are listed.
    pub(crate) fn poly(poly: PolyMesh, channels: Channels) -> Self {
        Refined::new(Form::Poly(poly), channels)
    }

    /// A result whose faces are the implicit quads of one split of `parent`.
    pub(crate) fn quads(
        positions: Vec<f32>,
        parent: Cow<'a, HalfEdgeMesh>,
        channels: Channels,
    ) -> Self {
        Refined::new(Form::Quads { positions, parent: Box::new(parent) }, channels)
    }

    /// A result with the limit tangents, and the unit normal of each vertex when asked for
    /// (three floats each); `poly`'s positions are the limit positions or the level's, as the
    /// call asked.
    pub(crate) fn with_tangents(
        poly: PolyMesh,
        channels: Channels,
        tangents: [Vec<f32>; 2],
        normals: Option<Vec<f32>>,
    ) -> Self {
        Refined {
            tangents: Some(Box::new(tangents)),
            normals,
            ..Refined::new(Form::Poly(poly), channels)
        }
    }

    /// This result with `normals` (unit, three floats per vertex, or none) in place of any it
    /// had.
    pub(crate) fn with_given_normals(self, normals: Option<Vec<f32>>) -> Self {
        Refined { normals, ..self }
    }

    /// This result with vertex normals from its faces ([`crate::limit::face_normals`]) when it
    /// has none yet (the faces become listed ones).
    pub(crate) fn with_face_normals(self) -> Self {
        if self.normals.is_some() {
            return self;
        }
        let (poly, attributes) = self.into_parts();
        let normals = crate::limit::face_normals(&poly);
        let channels = Channels { attributes, seam_corners: Vec::new() };
        Refined { normals: Some(normals), ..Refined::poly(poly, channels) }
    }

    /// The limit tangents (OpenSubdiv's `tan1` and `tan2`, three floats per vertex) when the
    /// last level's scheme has limit masks and the limit or normals were asked for.
    pub fn tangents(&self) -> Option<[&[f32]; 2]> {
        self.tangents.as_deref().map(|[a, b]| [&a[..], &b[..]])
    }

    /// Unit vertex normals (three floats per vertex; zero where there is none), when asked
    /// for. After Catmull-Clark or Loop, the limit normal `tangents[0] × tangents[1]`;
    /// otherwise the normalised sum of the faces' area vectors around the vertex. Either points
    /// to the side from which the faces are wound counter-clockwise (outward on a closed mesh
    /// wound so, as the OBJ convention has it).
    pub fn normals(&self) -> Option<&[f32]> {
        self.normals.as_deref()
    }

    /// Takes the normals out of the result.
    pub fn take_normals(&mut self) -> Option<Vec<f32>> {
        self.normals.take()
    }

    /// The refined attribute channels, in the order they were given.
    pub fn attributes(&self) -> &[Attribute] {
        if self.seam_corners.is_empty() {
            return &self.attributes;
        }
        self.listed.get_or_init(|| {
            let mut attributes = self.attributes.clone();
            let faces = match &self.form {
                Form::Poly(poly) => Cow::Borrowed(&poly.indices[..]),
                Form::Quads { parent, .. } => Cow::Owned(pqq::child_face_indices(parent)),
            };
            list_indices(&self.seam_corners, &mut attributes, faces);
            attributes
        })
    }

    /// The attributes as the result keeps them, and the face-varying ones among them whose
    /// indices are left to be made piece by piece with the faces' (their `indices` here are
    /// empty): each one's place and corners near seams. Such an attribute's index list is the
    /// face index list ([`Refined::index_and_triangle_chunks`]) with each piece patched by
    /// [`SeamCorners::patch`] at its place, as [`Refined::attributes`] lists it whole.
    pub fn attributes_in_pieces(&self) -> (&[Attribute], &[(usize, SeamCorners)]) {
        (&self.attributes, &self.seam_corners)
    }

    /// The flat arrays and the attribute channels.
    pub fn into_parts(self) -> (PolyMesh, Vec<Attribute>) {
        let Refined { form, mut attributes, seam_corners, .. } = self;
        let poly = Refined::new(form, Channels::default()).into_poly();
        // Copied: made in the same pass as the faces (two fresh lists written at once), the
        // user time it saved went to the kernel's page faults, and more (1M quads, natively).
        list_indices(&seam_corners, &mut attributes, Cow::Borrowed(&poly.indices));
        (poly, attributes)
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

/// Gives the attributes of `seam_corners` their index lists: `faces` patched near seams (the
/// last one takes `faces` itself when it is owned).
fn list_indices(
    seam_corners: &[(usize, SeamCorners)],
    attributes: &mut [Attribute],
    mut faces: Cow<'_, [u32]>,
) {
    for (k, (i, seams)) in seam_corners.iter().enumerate() {
        let mut indices = if k + 1 == seam_corners.len() {
            std::mem::take(&mut faces).into_owned()
        } else {
            faces.to_vec()
        };
        seams.patch(0, &mut indices);
        if let Some(a) = attributes.get_mut(*i) {
            a.indices = Some(indices);
        }
    }
}
