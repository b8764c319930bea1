//! Doo-Sabin corner points, with the weights of CGAL's `DooSabin_mask_3`: for an `n`-gon with
//! vertices `v_0 .. v_{n-1}` starting at the corner, `Σ α_k v_k` with `α_0 = 1/4 + 5/(4n)` and
//! `α_k = (3 + 2 cos(2πk/n)) / (4n)`; for quads this is `(9, 3, 1, 3) / 16`. A kept boundary
//! is cut as Chaikin's corner cutting does (CGAL's boundary rule): `3/4` of the near end and
//! `1/4` of the far end.

use super::{CornerRules, Weights};
use crate::mesh::HalfEdgeMesh;
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

thread_local! {
    /// The weights of the last face larger than the table, made once for all its corners: an
    /// `n`-gon's corners need `n` weights each, and computing them per corner cost `n²`
    /// cosines (a face of 100k corners, the child of a fan's hub, took minutes).
    static LARGE_FACE: std::cell::RefCell<(usize, Vec<f32>)> =
        const { std::cell::RefCell::new((0, Vec::new())) };
}

impl CornerRules for DooSabin {
    #[inline]
    fn corner_point(&self, mesh: &HalfEdgeMesh, half_edge: u32, w: &mut impl Weights) {
        let range = mesh.cell_range(mesh.cell_of(half_edge) as usize);
        let (start, n) = (range.start as u32, range.len());
        let first = (half_edge - start) as usize;
        // From the corner round the face: the corners after it, then those before it (a
        // subtraction, not `%`: a division per corner cost Doo-Sabin 20 % on triangles).
        let corner = |k: usize| {
            let at = first + k;
            start + if at >= n { at - n } else { at } as u32
        };
        if n == 4 {
            // (9, 3, 1, 3) / 16, summed whole and scaled once.
            let group = w.begin_group(1.0 / 16.0);
            w.corner(corner(1), 3.0);
            w.corner(corner(3), 3.0);
            w.corner(corner(2), 1.0);
            w.corner(corner(0), 9.0);
            w.end_group(group);
            return;
        }
        match weight_table().get(n) {
            Some(weights) => (0..n).for_each(|k| w.corner(corner(k), weights[k])),
            None => LARGE_FACE.with_borrow_mut(|(size, weights)| {
                if *size != n {
                    *size = n;
                    weights.clear();
                    weights.extend((0..n).map(|k| doo_sabin_weight(n, k)));
                }
                (0..n).for_each(|k| w.corner(corner(k), weights[k]))
            }),
        }
    }

    #[inline]
    fn boundary_point(
        &self,
        mesh: &HalfEdgeMesh,
        half_edge: u32,
        near: usize,
        w: &mut impl Weights,
    ) {
        let [near_weight, far_weight] = if near == 0 { [0.75, 0.25] } else { [0.25, 0.75] };
        w.corner(half_edge, near_weight);
        w.corner(mesh.next_in_cell(half_edge), far_weight);
    }
}
