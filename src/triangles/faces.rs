//! The faces to subdivide, from welded triangles: sharp edges found, triangles joined into quads
//! and smoothing fans grouped, each when asked for, in one call.

use super::edges::{check_corners, triangle_normals, TriangleEdges};
use super::quads::{join_quads, triangle_polygons, JoinConstraints, Polygons, QuadLimits};
use super::sharp::{
    crease_angle_edges, normal_split_edges, splits_normals, tagged_edges, FOUND, SMOOTH,
};
use super::sides::smoothing_fans;
use crate::error::{Error, Result};

/// What [`triangle_faces`] does besides listing the triangles. Nothing, by default.
#[derive(Clone, Copy, Debug, Default)]
pub struct FaceOptions<'a> {
    /// Edges whose triangles' normals differ by more than this angle (radians) are sharp.
    pub crease_angle: Option<f64>,
    /// x, y, z per input vertex: edges where the input split its vertices with normals more
    /// than about 1° apart at both ends are sharp ([`normal_split_edges`]).
    pub split_normals: Option<&'a [f32]>,
    /// The caller's creases, as pairs of welded vertices, with [`Self::crease_sharpness`]: no
    /// quad joins across them, and from sharpness 10 on they split the smoothing fans.
    pub creases: &'a [u32],
    /// One sharpness per pair of [`Self::creases`].
    pub crease_sharpness: &'a [f32],
    /// Join pairs of triangles into quads ([`join_quads`]) within these limits.
    pub quads: Option<QuadLimits>,
    /// A group per triangle (a material); quads never join two groups.
    pub groups: Option<&'a [u32]>,
    /// A class per input vertex: a quad joins two triangles only where the input vertices of
    /// their corners at each end of the shared edge are of one class (one side of every seam).
    pub corner_classes: Option<&'a [u32]>,
    /// Triangles that are holes (ascending or not): they join nothing.
    pub holes: &'a [u32],
    /// Group the corners into smoothing fans when some edge is infinitely sharp.
    pub sides: bool,
}

/// The faces to subdivide, made of the triangles given to [`triangle_faces`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Faces {
    /// The faces: triangles, and quads where triangles were joined.
    pub polygons: Polygons,
    /// The edges found sharp (by angle or split normals), as pairs of welded vertices, in edge
    /// order: to be subdivided as infinitely sharp creases.
    pub creases: Vec<u32>,
    /// The faces that are holes: those made of a hole triangle.
    pub holes: Vec<u32>,
    /// When asked for and some edge splits the normals: per face corner, its smoothing fan (the
    /// lowest triangle corner of the fan, below `3 × triangles`).
    pub sides: Option<Vec<u32>>,
}

/// The faces of welded triangles: `positions` x, y, z per welded vertex, `corners` three
/// welded vertices per triangle, `input_corners` the input vertex of each corner (for the
/// per-input-vertex data of [`FaceOptions::split_normals`] and
/// [`FaceOptions::corner_classes`]), as [`super::weld_triangles`] gives them.
///
/// Edges are found only when an option needs them. Errors when the arrays do not fit each
/// other; nothing given is modified.
///
/// ```
/// use subsurf::triangles::{triangle_faces, FaceOptions, QuadLimits};
/// let square = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
/// let corners = [0, 1, 2, 0, 2, 3];
/// let options = FaceOptions { quads: Some(QuadLimits::default()), ..Default::default() };
/// let faces = triangle_faces(&square, &corners, &corners, &options).unwrap();
/// assert_eq!(faces.polygons.face_sizes, [4]);
/// ```
pub fn triangle_faces(
    positions: &[f32],
    corners: &[u32],
    input_corners: &[u32],
    options: &FaceOptions,
) -> Result<Faces> {
    let triangles = corners.len() / 3;
    check(positions, corners, input_corners, options)?;
    let mut hole = vec![false; triangles];
    for &t in options.holes {
        hole[t as usize] = true;
    }
    let needs_edges = options.quads.is_some()
        || options.crease_angle.is_some()
        || options.split_normals.is_some()
        || (!options.creases.is_empty() && options.sides);
    let mut faces = Faces::default();
    if !needs_edges {
        faces.polygons = triangle_polygons(triangles);
        faces.holes = (0..triangles as u32).filter(|&t| hole[t as usize]).collect();
        return Ok(faces);
    }

    let edges = TriangleEdges::new(corners)?;
    let mut marks = vec![SMOOTH; edges.len()];
    if let Some(angle) = options.crease_angle {
        crease_angle_edges(&edges, &triangle_normals(positions, corners)?, angle, &mut marks)?;
    }
    if let Some(split) = options.split_normals {
        normal_split_edges(&edges, input_corners, split, &mut marks)?;
    }
    faces.creases = (0..edges.len())
        .filter(|&e| marks[e] == FOUND)
        .flat_map(|e| [edges.a[e], edges.b[e]])
        .collect();
    tagged_edges(&edges, options.creases, options.crease_sharpness, &mut marks)?;

    faces.polygons = match options.quads {
        Some(limits) => {
            let classes: Option<Vec<u32>> = options
                .corner_classes
                .map(|c| input_corners.iter().map(|&v| c[v as usize]).collect());
            let constraints = JoinConstraints {
                groups: options.groups,
                corner_classes: classes.as_deref(),
                holes: Some(&hole),
            };
            join_quads(positions, corners, &edges, &marks, &constraints, limits)?
        }
        None => triangle_polygons(triangles),
    };
    faces.holes = (0..faces.polygons.first_triangles.len() as u32)
        .filter(|&f| hole[faces.polygons.first_triangles[f as usize] as usize])
        .collect();
    if options.sides && marks.iter().any(|&m| splits_normals(m)) {
        let fans = smoothing_fans(&edges, &marks)?;
        faces.sides = Some(faces.polygons.corners.iter().map(|&c| fans[c as usize]).collect());
    }
    Ok(faces)
}

fn check(
    positions: &[f32],
    corners: &[u32],
    input_corners: &[u32],
    options: &FaceOptions,
) -> Result<()> {
    let triangles = corners.len() / 3;
    let wrong = |what: String| Err(Error::mesh(format!("triangle faces: {what}")));
    check_corners(positions, corners, "triangle faces")?;
    if u32::try_from(corners.len()).is_err() {
        return Err(Error::TooLarge(format!(
            "{} triangle corners; faces number their corners with 32-bit indices",
            corners.len()
        )));
    }
    if input_corners.len() != corners.len() {
        return wrong(format!(
            "{} input corners for {} corners; give the input vertex of every corner",
            input_corners.len(),
            corners.len()
        ));
    }
    if let Some(groups) = options.groups.filter(|g| g.len() != triangles) {
        return wrong(format!(
            "{} triangle groups for {triangles} triangles; give one per triangle",
            groups.len()
        ));
    }
    if let Some(&t) = options.holes.iter().find(|&&t| t as usize >= triangles) {
        return Err(Error::InvalidTag(format!(
            "holes names triangle {t}, but there are {triangles} triangles"
        )));
    }
    if let Some(classes) = options.corner_classes {
        if let Some(k) = input_corners.iter().position(|&v| v as usize >= classes.len()) {
            return wrong(format!(
                "corner {k} is input vertex {}, but there are corner classes for {} vertices",
                input_corners[k],
                classes.len()
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangles::weld_triangles;

    /// A unit cube with its vertices split per face (a flat-shaded export): 24 vertices.
    fn split_cube() -> (Vec<f32>, Vec<u32>) {
        let corner = |i: u32| [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f32);
        let quads =
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let positions = quads.iter().flat_map(|q| q.map(corner)).flatten().collect();
        let corners = (0..6u32).flat_map(|f| [0, 1, 2, 0, 2, 3].map(|k| 4 * f + k)).collect();
        (positions, corners)
    }

    #[test]
    fn a_split_cube_becomes_six_quads_with_twelve_sharp_edges() {
        let (positions, input) = split_cube();
        let welded = weld_triangles(&positions, &input, 0.0).unwrap();
        let options = FaceOptions {
            crease_angle: Some(30f64.to_radians()),
            quads: Some(QuadLimits::default()),
            sides: true,
            ..Default::default()
        };
        let faces = triangle_faces(&welded.positions, &welded.corners, &input, &options).unwrap();
        assert_eq!(faces.polygons.face_sizes, [4; 6]);
        assert_eq!(faces.creases.len(), 2 * 12);
        // Every face is a fan of its own at each of its corners.
        let sides = faces.sides.unwrap();
        let mut distinct = sides.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(distinct.len(), 24);
    }

    #[test]
    fn random_soups_give_every_triangle_once_and_never_panic() {
        // Points on a coarse lattice (many welds, folds, non-manifold and flipped edges).
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut random = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        for round in 0..200 {
            let vertices = 3 + random(40) as usize;
            let positions: Vec<f32> = (0..3 * vertices).map(|_| random(4) as f32 * 0.5).collect();
            let input: Vec<u32> =
                (0..3 * (1 + random(60))).map(|_| random(vertices as u64) as u32).collect();
            let normals: Vec<f32> = (0..3 * vertices).map(|_| random(3) as f32 - 1.0).collect();
            let welded = weld_triangles(&positions, &input, [0.0, 0.3][round % 2]).unwrap();
            let triangles = welded.kept.len();
            let input_corners: Vec<u32> = welded
                .kept
                .iter()
                .flat_map(|&t| [0, 1, 2].map(|j| input[3 * t as usize + j]))
                .collect();
            let classes: Vec<u32> = (0..vertices as u32).map(|v| v % 3).collect();
            let groups: Vec<u32> = (0..triangles as u32).map(|t| t % 2).collect();
            let holes: Vec<u32> = (0..triangles as u32).filter(|t| t % 5 == 0).collect();
            let pairs = welded.corners.len().min(4) / 2;
            let options = FaceOptions {
                crease_angle: Some(0.6),
                split_normals: Some(&normals),
                creases: &welded.corners[..pairs * 2],
                crease_sharpness: &[10.0, 2.0][..pairs],
                quads: Some(QuadLimits::default()),
                groups: Some(&groups),
                corner_classes: Some(&classes),
                holes: &holes,
                sides: true,
            };
            let faces =
                triangle_faces(&welded.positions, &welded.corners, &input_corners, &options)
                    .unwrap();
            let p = &faces.polygons;
            let mut used = vec![0; 3 * triangles];
            for &c in &p.corners {
                used[c as usize] += 1;
            }
            // A quad takes its first triangle's corners and the far corner of its partner.
            assert!(used.iter().all(|&u| u <= 1), "round {round}: a corner used twice");
            assert!(used.chunks_exact(3).all(|t| t.contains(&1)), "round {round}: a triangle lost");
            let quads = p.face_sizes.iter().filter(|&&n| n == 4).count();
            assert_eq!(p.corners.len(), 3 * triangles - 2 * quads);
            assert_eq!(p.face_sizes.iter().sum::<u32>() as usize, p.corners.len());
            if let Some(sides) = &faces.sides {
                assert_eq!(sides.len(), p.corners.len());
            }
        }
    }

    #[test]
    fn nothing_asked_gives_the_triangles() {
        let (positions, input) = split_cube();
        let welded = weld_triangles(&positions, &input, 0.0).unwrap();
        let options = FaceOptions { holes: &[3, 1], ..Default::default() };
        let faces = triangle_faces(&welded.positions, &welded.corners, &input, &options).unwrap();
        assert_eq!(faces.polygons.face_sizes, [3; 12]);
        assert_eq!(faces.holes, [1, 3]);
        assert!(faces.creases.is_empty() && faces.sides.is_none());
        let bad = FaceOptions { holes: &[12], ..Default::default() };
        let message = triangle_faces(&welded.positions, &welded.corners, &input, &bad).unwrap_err();
        assert!(message.to_string().contains("holes names triangle 12, but there are 12"));
    }

    #[test]
    fn tagged_sharp_creases_split_the_fans_but_are_not_listed() {
        let square = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
        let corners = [0, 1, 2, 0, 2, 3];
        let options = FaceOptions {
            creases: &[2, 0],
            crease_sharpness: &[10.0],
            quads: Some(QuadLimits::default()),
            sides: true,
            ..Default::default()
        };
        let faces = triangle_faces(&square, &corners, &corners, &options).unwrap();
        assert_eq!(faces.polygons.face_sizes, [3, 3]);
        assert!(faces.creases.is_empty());
        assert_eq!(faces.sides.unwrap(), [0, 1, 2, 3, 4, 5]);
    }
}
