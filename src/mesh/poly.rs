//! The flat polygon mesh that goes in and comes out: the typed-array form of the JS API.

/// The largest piece [`PolyMesh::triangle_chunks`] hands over, in indices: 192 KiB, so that the
/// buffer stays in cache while it is copied out.
pub(crate) const TRIANGLE_CHUNK: usize = 6 * 8192;

/// A polygon mesh as three flat arrays, the form WebGL and OBJ files use.
///
/// `positions` holds x, y, z per vertex; face `f` uses the next `face_sizes[f]` entries of
/// `indices`, in counter-clockwise order seen from outside.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolyMesh {
    pub positions: Vec<f32>,
    pub indices: Vec<u32>,
    pub face_sizes: Vec<u32>,
}

impl PolyMesh {
    pub fn num_vertices(&self) -> usize {
        self.positions.len() / 3
    }

    pub fn num_faces(&self) -> usize {
        self.face_sizes.len()
    }

    /// Number of entries of [`PolyMesh::triangles`]: three per triangle of each face's fan.
    pub fn num_triangle_indices(&self) -> usize {
        3 * self.face_sizes.iter().map(|&n| (n as usize).saturating_sub(2)).sum::<usize>()
    }

    /// A fan triangulation of every face, as a WebGL index buffer. Faces are assumed convex enough
    /// for a fan; refined faces always are.
    pub fn triangles(&self) -> Vec<u32> {
        let mut out = Vec::with_capacity(self.num_triangle_indices());
        self.triangle_chunks(|chunk| out.extend_from_slice(chunk));
        out
    }

    /// [`PolyMesh::triangles`] in consecutive pieces of whole triangles, each at most
    /// 192 KiB of indices, except that an all-triangle mesh comes as one piece, its own
    /// index list. A caller can copy the fan out of a cache-sized buffer instead of writing the
    /// whole array and reading it back: the wasm bindings fill the JS array this way, which saves
    /// a pass over the largest result array.
    pub fn triangle_chunks(&self, mut sink: impl FnMut(&[u32])) {
        let faces = self.face_sizes.len();
        // The refined meshes of the quad and triangle splits are uniform: one tight loop each.
        let uniform = |n: u32| {
            self.indices.len() == n as usize * faces && self.face_sizes.iter().all(|&s| s == n)
        };
        if uniform(3) {
            sink(&self.indices);
            return;
        }
        if uniform(4) {
            let mut fans = vec![[0u32; 6]; TRIANGLE_CHUNK / 6];
            for quads in self.indices.as_chunks::<4>().0.chunks(fans.len()) {
                for (fan, q) in fans.iter_mut().zip(quads) {
                    *fan = [q[0], q[1], q[2], q[0], q[2], q[3]];
                }
                sink(fans[..quads.len()].as_flattened());
            }
            return;
        }
        let mut buffer = Vec::with_capacity(TRIANGLE_CHUNK);
        let mut start = 0usize;
        for &n in &self.face_sizes {
            let n = n as usize;
            let Some(face) = self.indices.get(start..start + n) else {
                break;
            };
            for k in 1..n.saturating_sub(1) {
                if buffer.len() + 3 > TRIANGLE_CHUNK {
                    sink(&buffer);
                    buffer.clear();
                }
                buffer.extend_from_slice(&[face[0], face[k], face[k + 1]]);
            }
            start += n;
        }
        if !buffer.is_empty() {
            sink(&buffer);
        }
    }

    /// Axis-aligned bounding box diagonal length; 0 for an empty mesh.
    pub fn bounding_diagonal(&self) -> f32 {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in self.positions.chunks_exact(3) {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if lo[0] > hi[0] {
            return 0.0;
        }
        ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::{PolyMesh, TRIANGLE_CHUNK};

    fn mesh(indices: &[u32], face_sizes: &[u32]) -> PolyMesh {
        PolyMesh {
            positions: vec![0.0; 3 * 8],
            indices: indices.to_vec(),
            face_sizes: face_sizes.to_vec(),
        }
    }

    /// The fan of each face, written out by hand: (0, k, k + 1) for k = 1..n - 1.
    #[test]
    fn triangles_are_the_fan_of_each_face() {
        let quads = mesh(&[0, 1, 2, 3, 4, 5, 6, 7], &[4, 4]);
        assert_eq!(quads.triangles(), [0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7]);
        let tris = mesh(&[0, 1, 2, 5, 6, 7], &[3, 3]);
        assert_eq!(tris.triangles(), [0, 1, 2, 5, 6, 7]);
        let mixed = mesh(&[0, 1, 2, 3, 4, 5, 6, 7, 0, 2, 4], &[5, 3, 3]);
        assert_eq!(mixed.triangles(), [0, 1, 2, 0, 2, 3, 0, 3, 4, 5, 6, 7, 0, 2, 4]);
        // Sizes that do not add up to the index count take the checked path and stop early.
        let short = mesh(&[0, 1, 2, 3, 4, 5, 6], &[4, 4]);
        assert_eq!(short.triangles(), [0, 1, 2, 0, 2, 3]);
    }

    /// The pieces join up to the whole fan, each holds whole triangles within the size limit,
    /// and the count matches: on quads (fast path), on mixed faces (general path) and on a mesh
    /// of pentagons whose fans straddle piece boundaries.
    #[test]
    fn triangle_chunks_join_up_to_the_fan() {
        let quads = 3 * TRIANGLE_CHUNK / 6 + 5;
        let pentagons = TRIANGLE_CHUNK / 9 + 7;
        let cases = [
            mesh(&(0..4 * quads as u32).map(|i| i % 8).collect::<Vec<_>>(), &vec![4; quads]),
            mesh(
                &(0..5 * pentagons as u32).map(|i| i % 8).collect::<Vec<_>>(),
                &vec![5; pentagons],
            ),
            mesh(&[0, 1, 2, 3, 4, 5, 6, 7, 0, 2, 4], &[5, 3, 3]),
        ];
        for poly in &cases {
            let mut joined = Vec::new();
            let mut pieces = 0;
            poly.triangle_chunks(|chunk| {
                assert!(chunk.len() <= TRIANGLE_CHUNK && chunk.len() % 3 == 0);
                joined.extend_from_slice(chunk);
                pieces += 1;
            });
            assert_eq!(joined.len(), poly.num_triangle_indices());
            // The fan written out face by face, independently of both code paths.
            let mut fan = Vec::new();
            let mut start = 0;
            for &n in &poly.face_sizes {
                let face = &poly.indices[start..start + n as usize];
                for k in 1..face.len() - 1 {
                    fan.extend_from_slice(&[face[0], face[k], face[k + 1]]);
                }
                start += n as usize;
            }
            assert_eq!(joined, fan);
            assert_eq!(pieces, fan.len().div_ceil(TRIANGLE_CHUNK).max(1));
        }
    }
}
