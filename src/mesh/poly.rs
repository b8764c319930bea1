//! The flat polygon mesh that goes in and comes out: the typed-array form of the JS API.

/// The largest piece of an index array handed over in pieces ([`PolyMesh::triangle_chunks`],
/// [`chunked`]): 192 KiB, so that the buffer stays in cache while it is copied out. A multiple
/// of 3, 4 and 6, so that pieces hold whole triangles, quads and quad fans.
pub(crate) const CHUNK_LEN: usize = 6 * 8192;

/// Hands `item(0)`, `item(1)`, ..., `item(count - 1)` to `sink`, flattened, in consecutive pieces
/// of at most [`CHUNK_LEN`] indices written into one reused buffer: for index arrays that are
/// copied out as they are made and never stored whole.
pub(crate) fn chunked<const N: usize>(
    count: usize,
    item: impl Fn(usize) -> [u32; N],
    mut sink: impl FnMut(&[u32]),
) {
    let mut buffer = vec![[0u32; N]; CHUNK_LEN / N];
    let mut start = 0;
    while start < count {
        let n = buffer.len().min(count - start);
        for (i, slot) in buffer[..n].iter_mut().enumerate() {
            *slot = item(start + i);
        }
        sink(buffer[..n].as_flattened());
        start += n;
    }
}

/// Hands the quads of `group(0)`, ..., `group(count - 1)` (`K` quads each) to `quads` and their
/// fans ([`quad_fan`]) to `fans`, in matching pieces (at most [`CHUNK_LEN`] indices of fans
/// each): one pass makes both arrays of a quad mesh's result, each quad made once. A group is
/// what one step makes best: the `K` child quads of a parent with `K` corners gather that
/// parent's corners and edges once, in a loop the compiler can vectorise.
pub(crate) fn quad_and_fan_chunks<const K: usize>(
    count: usize,
    group: impl Fn(usize) -> [[u32; 4]; K],
    mut quads: impl FnMut(&[u32]),
    mut fans: impl FnMut(&[u32]),
) {
    let groups = (CHUNK_LEN / 6 / K).max(1);
    let mut quad_buffer = vec![[[0u32; 4]; K]; groups];
    let mut fan_buffer = vec![[[0u32; 6]; K]; groups];
    let mut start = 0;
    while start < count {
        let n = groups.min(count - start);
        for (i, slot) in quad_buffer[..n].iter_mut().enumerate() {
            *slot = group(start + i);
        }
        for (fan, q) in fan_buffer[..n].iter_mut().zip(&quad_buffer[..n]) {
            *fan = q.map(quad_fan);
        }
        quads(quad_buffer[..n].as_flattened().as_flattened());
        fans(fan_buffer[..n].as_flattened().as_flattened());
        start += n;
    }
}

/// The two triangles of quad `q`'s fan: (0, 1, 2) and (0, 2, 3).
#[inline]
pub(crate) fn quad_fan(q: [u32; 4]) -> [u32; 6] {
    [q[0], q[1], q[2], q[0], q[2], q[3]]
}

/// The area vector of polygon `face` over `positions` (x, y, z per vertex), in f64: Newell's
/// normal, twice the area along the normal; exact for planar faces, the best plane's for others.
pub fn area_vector(positions: &[f32], face: &[u32]) -> glam::DVec3 {
    let point = |v: u32| {
        let i = 3 * v as usize;
        glam::DVec3::new(positions[i].into(), positions[i + 1].into(), positions[i + 2].into())
    };
    let mut area = glam::DVec3::ZERO;
    for (i, &a) in face.iter().enumerate() {
        area += point(a).cross(point(face[(i + 1) % face.len()]));
    }
    area
}

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
    /// Checks that the arrays fit together (whole vertices, face sizes summing to the index
    /// count, every index naming a vertex) without building the half-edge mesh: one pass over
    /// the faces, for helpers that only walk them (normals, edges, drawable meshes).
    pub fn check_arrays(&self) -> crate::Result<()> {
        if !self.positions.len().is_multiple_of(3) {
            return Err(crate::Error::InvalidMesh(format!(
                "positions has {} entries, which is not a multiple of 3 (x, y, z per vertex)",
                self.positions.len()
            )));
        }
        let total: u64 = self.face_sizes.iter().map(|&n| n as u64).sum();
        if total != self.indices.len() as u64 {
            return Err(crate::Error::InvalidMesh(format!(
                "faceSizes add up to {total} but indices has {} entries; they must be equal",
                self.indices.len()
            )));
        }
        let vertices = self.num_vertices();
        if let Some(k) = self.indices.iter().position(|&i| i as usize >= vertices) {
            return Err(crate::Error::InvalidMesh(format!(
                "indices[{k}] refers to vertex {}, but there are only {vertices} vertices",
                self.indices[k]
            )));
        }
        Ok(())
    }

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
            let quads = self.indices.as_chunks::<4>().0;
            chunked(quads.len(), |f| quad_fan(quads[f]), sink);
            return;
        }
        let mut buffer = Vec::with_capacity(CHUNK_LEN);
        let mut start = 0usize;
        for &n in &self.face_sizes {
            let n = n as usize;
            let Some(face) = self.indices.get(start..start + n) else {
                break;
            };
            for k in 1..n.saturating_sub(1) {
                if buffer.len() + 3 > CHUNK_LEN {
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
    use super::{chunked, PolyMesh, CHUNK_LEN};

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
        let quads = 3 * CHUNK_LEN / 6 + 5;
        let pentagons = CHUNK_LEN / 9 + 7;
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
                assert!(chunk.len() <= CHUNK_LEN && chunk.len() % 3 == 0);
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
            assert_eq!(pieces, fan.len().div_ceil(CHUNK_LEN).max(1));
        }
    }

    /// `chunked` hands over every item once, in order, in full pieces but the last; none for
    /// no items.
    #[test]
    fn chunked_hands_over_every_item_in_order() {
        for count in [0, 1, CHUNK_LEN / 4, CHUNK_LEN / 4 + 1, 3 * CHUNK_LEN / 4 + 17] {
            let mut joined = Vec::new();
            let mut sizes = Vec::new();
            chunked(
                count,
                |i| [4 * i as u32, 4 * i as u32 + 1, 4 * i as u32 + 2, 4 * i as u32 + 3],
                |c| {
                    sizes.push(c.len());
                    joined.extend_from_slice(c);
                },
            );
            assert_eq!(joined, (0..4 * count as u32).collect::<Vec<_>>(), "{count} items");
            assert_eq!(sizes.len(), count.div_ceil(CHUNK_LEN / 4), "{count} items");
            assert!(sizes.iter().rev().skip(1).all(|&n| n == CHUNK_LEN), "{count} items");
        }
    }
}
