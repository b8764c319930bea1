//! Sizes before any work: the counts formulas of every level, and the guards that refuse a call
//! whose result would not fit.

use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::options::{Options, Scheme, MAX_LEVELS};
use crate::refine::{dqq, pqq, ptq, sqrt3};

/// The predicted size after all levels of `options`, from the counts formulas of each level.
pub fn predict(mesh: &HalfEdgeMesh, options: &Options) -> Prediction {
    let mut counts =
        [mesh.num_vertices(), mesh.num_edges(), mesh.num_half_edges(), mesh.num_cells()]
            .map(|n| n as u64);
    for (level, scheme) in options.schemes.iter().enumerate() {
        let [v, e, h, f] = counts;
        counts = match scheme {
            Scheme::CatmullClark | Scheme::Bilinear => pqq::child_counts(v, e, h, f),
            Scheme::Loop | Scheme::Midpoint => ptq::child_counts(v, e, h, f),
            Scheme::DooSabin => dqq::child_counts(v, e, h, f),
            Scheme::Sqrt3 => {
                sqrt3::child_counts(v, e, h, f, sqrt3_refines_boundary(&options.schemes, level))
            }
            Scheme::QuadTriangle => {
                // Upper bound: T triangles make 4T faces and the other faces H - 3T, so H + T
                // <= H + F faces, and a centroid for each non-triangle, at most F.
                [v + e + f, 2 * e + h, 4 * h, h + f]
            }
        };
        if counts.iter().any(|&c| c > u64::MAX / 64) {
            // Saturate: a level grows every count less than 64-fold, so nothing overflowed yet,
            // and no guard lets this through.
            return Prediction { vertices: u64::MAX, faces: u64::MAX, corners: u64::MAX };
        }
    }
    Prediction { vertices: counts[0], faces: counts[3], corners: counts[2] }
}

/// The predicted size of a result, before any work: exact for the primal schemes, an upper
/// bound for Doo-Sabin, √3 and Quad/Triangle; every count is `u64::MAX` when it would not fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Prediction {
    pub vertices: u64,
    pub faces: u64,
    /// Face corners: the length of the index array.
    pub corners: u64,
}

impl Prediction {
    /// Bytes of the result's arrays as the JS API returns them: 12 per vertex, 4 per index,
    /// 4 per face size and 12 per triangle of the fan triangulation (corners - 2 per face).
    pub fn bytes(&self) -> u64 {
        let triangles = self.corners.saturating_sub(2 * self.faces);
        12u64
            .saturating_mul(self.vertices)
            .saturating_add(4u64.saturating_mul(self.corners))
            .saturating_add(4u64.saturating_mul(self.faces))
            .saturating_add(12u64.saturating_mul(triangles))
    }

    /// Bytes of the refined attribute channels: 4 per float per vertex of the vertex-varying
    /// ones; for each face-varying one 4 per index (one per corner) and 4 per float of at most
    /// one value per corner and per vertex (an upper bound: a value is a vertex's, seen by some
    /// of its corners, or a vertex's no corner sees).
    pub fn attribute_bytes(&self, sizes: &AttributeSizes) -> u64 {
        let fvar_values = self.corners.saturating_add(self.vertices);
        sizes.face_varying.iter().fold(
            4u64.saturating_mul(sizes.vertex_width).saturating_mul(self.vertices),
            |bytes, &size| {
                bytes
                    .saturating_add(4u64.saturating_mul(self.corners))
                    .saturating_add(4u64.saturating_mul(size).saturating_mul(fvar_values))
            },
        )
    }
}

/// Refuses, before any allocation, a call whose result would break a guard of `options`.
pub fn check_guards(mesh: &HalfEdgeMesh, options: &Options) -> Result<()> {
    check_guards_with(mesh, options, &AttributeSizes::default())
}

/// The floats per value of a call's attribute channels, for the byte guard.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct AttributeSizes {
    /// Floats per vertex of every vertex-varying channel together.
    pub vertex_width: u64,
    /// Item size of each face-varying channel.
    pub face_varying: Vec<u64>,
}

/// [`check_guards`] counting the bytes of attribute channels too (see
/// [`Prediction::attribute_bytes`]).
pub fn check_guards_with(
    mesh: &HalfEdgeMesh,
    options: &Options,
    attributes: &AttributeSizes,
) -> Result<()> {
    let levels = options.levels();
    if levels > MAX_LEVELS {
        return Err(Error::InvalidOption(format!(
            "{levels} levels is more than the {MAX_LEVELS} subsurf accepts; every level multiplies the faces by about four"
        )));
    }
    let predicted = predict(mesh, options);
    if predicted.faces == u64::MAX {
        return Err(Error::TooLarge(format!(
            "{levels} level(s) would make more faces than a 64-bit count holds, beyond any maxFaces (CLI --max-faces); use fewer levels"
        )));
    }
    if predicted.faces > options.max_faces {
        return Err(Error::TooLarge(format!(
            "{levels} level(s) would make {} faces, more than the limit of {}; use fewer levels or raise maxFaces (CLI --max-faces)",
            predicted.faces, options.max_faces
        )));
    }
    let bytes = predicted.bytes().saturating_add(predicted.attribute_bytes(attributes));
    if bytes > options.max_bytes {
        let channels = if *attributes == AttributeSizes::default() { "" } else { ", attributes" };
        return Err(Error::TooLarge(format!(
            "{levels} level(s) would make a result of {bytes} bytes (positions, indices, face sizes, triangles{channels}), more than the limit of {} bytes; use fewer levels or raise maxBytes (CLI --max-bytes)",
            options.max_bytes
        )));
    }
    Ok(())
}

/// Predicted `(vertices, faces)` after all levels; see [`predict`].
pub fn predict_counts(mesh: &HalfEdgeMesh, options: &Options) -> (u64, u64) {
    let p = predict(mesh, options);
    (p.vertices, p.faces)
}

/// √3 splits boundary edges on every second level of a run of √3 levels, starting with the
/// second, as CGAL's `Sqrt3_subdivision` does on steps 2, 4, ... of one call. A splitting level
/// thus always follows a √3 level, which leaves at most one boundary edge per triangle.
pub(crate) fn sqrt3_refines_boundary(schemes: &[Scheme], level: usize) -> bool {
    let run = schemes.iter().take(level).rev();
    run.take_while(|&&s| s == Scheme::Sqrt3).count() % 2 == 1
}
