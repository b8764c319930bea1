//! Doo-Sabin corner points, with the weights of CGAL's `DooSabin_mask_3`: for an `n`-gon with
//! vertices `v_0 .. v_{n-1}` starting at the corner, `Σ α_k v_k` with `α_0 = 1/4 + 5/(4n)` and
//! `α_k = (3 + 2 cos(2πk/n)) / (4n)`; for quads this is `(9, 3, 1, 3) / 16`.

use super::{vec3, CornerRules};
use crate::mesh::HalfEdgeMesh;
use glam::Vec3;
use std::sync::OnceLock;

/// Doo-Sabin subdivision rules.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DooSabin;

/// The Doo-Sabin weight of the vertex `k` steps after the corner in an `n`-gon.
pub fn doo_sabin_weight(n: usize, k: usize) -> f32 {
    let nf = n as f64;
    let w = if k == 0 {
        0.25 + 1.25 / nf
    } else {
        (3.0 + 2.0 * (std::f64::consts::TAU * k as f64 / nf).cos()) / (4.0 * nf)
    };
    w as f32
}

/// Faces up to this many corners take their weights from a table made once: computing the
/// cosines for every corner cost about a third of a Doo-Sabin level on meshes of triangles and
/// hexagons.
const TABLE_SIZES: usize = 16;

/// The weights of [`doo_sabin_weight`] for `n < TABLE_SIZES` corners, `n` in row `n`; the same
/// `f32` values, so results do not change.
fn weight_table() -> &'static [[f32; TABLE_SIZES]; TABLE_SIZES] {
    static TABLE: OnceLock<[[f32; TABLE_SIZES]; TABLE_SIZES]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut table = [[0.0; TABLE_SIZES]; TABLE_SIZES];
        for (n, row) in table.iter_mut().enumerate() {
            for (k, w) in row.iter_mut().enumerate().take(n) {
                *w = doo_sabin_weight(n, k);
            }
        }
        table
    })
}

impl CornerRules for DooSabin {
    #[inline]
    fn corner_point(&self, mesh: &HalfEdgeMesh, half_edge: u32) -> Vec3 {
        let c = mesh.cell_of(half_edge) as usize;
        let range = mesh.cell_range(c);
        let start = range.start;
        let corners = &mesh.he_from[range];
        let n = corners.len();
        let first = half_edge as usize - start;
        if n == 4 {
            let p = |k: usize| vec3(mesh.positions[corners[(first + k) % 4] as usize]);
            return (p(0) * 9.0 + (p(1) + p(3)) * 3.0 + p(2)) / 16.0;
        }
        // From the corner round the face: the corners after it, then those before it.
        let around = corners[first..].iter().chain(&corners[..first]);
        let p = |v: &u32| vec3(mesh.positions[*v as usize]);
        match weight_table().get(n) {
            Some(weights) => around.zip(weights).fold(Vec3::ZERO, |sum, (v, &w)| sum + p(v) * w),
            None => around
                .enumerate()
                .fold(Vec3::ZERO, |sum, (k, v)| sum + p(v) * doo_sabin_weight(n, k)),
        }
    }
}
