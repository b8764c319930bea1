//! The flat polygon mesh that goes in and comes out: the typed-array form of the JS API.

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

    /// A fan triangulation of every face, as a WebGL index buffer. Faces are assumed convex enough
    /// for a fan; refined faces always are.
    pub fn triangles(&self) -> Vec<u32> {
        let faces = self.face_sizes.len();
        // The refined meshes of the quad and triangle splits are uniform: one tight loop each.
        let uniform = |n: u32| {
            self.indices.len() == n as usize * faces && self.face_sizes.iter().all(|&s| s == n)
        };
        if uniform(3) {
            return self.indices.clone();
        }
        if uniform(4) {
            // Collected from an exact-size iterator: written in place, neither zeroed first
            // nor grown piece by piece (both cost a pass on wasm).
            let quads = self.indices.as_chunks::<4>().0.iter();
            let fans: Vec<[u32; 6]> = quads.map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect();
            return fans.into_flattened();
        }
        let count: usize = self.face_sizes.iter().map(|&n| (n as usize).saturating_sub(2)).sum();
        let mut out = Vec::with_capacity(3 * count);
        let mut start = 0usize;
        for &n in &self.face_sizes {
            let n = n as usize;
            let Some(face) = self.indices.get(start..start + n) else {
                break;
            };
            for k in 1..n.saturating_sub(1) {
                out.extend_from_slice(&[face[0], face[k], face[k + 1]]);
            }
            start += n;
        }
        out
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
    use super::PolyMesh;

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
}
