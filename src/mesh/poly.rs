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
