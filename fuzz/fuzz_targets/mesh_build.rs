//! `HalfEdgeMesh::from_faces` on arbitrary arrays: it accepts exactly the valid ones (an
//! independent validator decides; a face may repeat a vertex), refuses the others with an
//! `InvalidMesh` message, and an accepted mesh has consistent connectivity, knows whether a face
//! repeats a vertex, and gives its arrays back.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use subsurf::{Error, HalfEdgeMesh};
use subsurf_fuzz::{check_connectivity, check_error, is_valid, repeats_a_vertex, MAX_ELEMENTS};

#[derive(Arbitrary, Debug)]
enum Positions {
    /// Any bit patterns: NaN, infinities, subnormals.
    Raw(Vec<f32>),
    /// Small whole coordinates, always finite.
    Small(Vec<[i8; 3]>),
}

#[derive(Arbitrary, Debug)]
enum Indices {
    /// As given: mostly out of range.
    Raw(Vec<u32>),
    /// Reduced modulo the vertex count plus `extra` (0 keeps every index in range).
    Modulo { values: Vec<u16>, extra: u8 },
}

#[derive(Arbitrary, Debug)]
struct Input {
    positions: Positions,
    indices: Indices,
    face_sizes: Vec<u8>,
    /// Face sizes as given (any u32) instead of small ones.
    raw_sizes: Option<Vec<u32>>,
}

fuzz_target!(|input: Input| {
    let positions: Vec<f32> = match input.positions {
        Positions::Raw(mut p) => {
            p.truncate(3 * MAX_ELEMENTS + 2);
            p
        }
        Positions::Small(mut p) => {
            p.truncate(MAX_ELEMENTS);
            p.iter().flat_map(|c| c.map(|x| x as f32 / 8.0)).collect()
        }
    };
    let vertices = positions.len() / 3;
    let indices: Vec<u32> = match input.indices {
        Indices::Raw(mut i) => {
            i.truncate(4 * MAX_ELEMENTS);
            i
        }
        Indices::Modulo { values, extra } => {
            let modulus = vertices as u32 + (extra % 3) as u32;
            values.iter().take(4 * MAX_ELEMENTS).map(|&v| v as u32 % modulus.max(1)).collect()
        }
    };
    let face_sizes: Vec<u32> = match input.raw_sizes {
        Some(mut sizes) => {
            sizes.truncate(MAX_ELEMENTS);
            sizes
        }
        None => input.face_sizes.iter().take(MAX_ELEMENTS).map(|&n| (n % 9) as u32).collect(),
    };
    let valid = is_valid(&positions, &indices, &face_sizes);
    match HalfEdgeMesh::from_faces(&positions, &indices, &face_sizes) {
        Ok(mesh) => {
            assert!(valid, "from_faces accepted an invalid mesh");
            assert_eq!(mesh.num_vertices(), vertices);
            assert_eq!(mesh.num_half_edges(), indices.len());
            assert_eq!(mesh.num_cells(), face_sizes.len());
            let poly = mesh.to_poly();
            assert_eq!(poly.indices, indices);
            assert_eq!(poly.face_sizes, face_sizes);
            let same_bits =
                poly.positions.iter().zip(&positions).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same_bits && poly.positions.len() == positions.len(), "positions changed");
            let repeats = repeats_a_vertex(&poly);
            assert_eq!(mesh.has_repeated_corners(), repeats, "repeated corners");
            assert_eq!(mesh.first_repeated_corner().is_some(), repeats, "first repeated corner");
            check_connectivity(&mesh);
        }
        Err(e) => {
            assert!(!valid, "from_faces refused a valid mesh: {e}");
            assert!(matches!(e, Error::InvalidMesh(_)), "wrong kind of error: {e:?}");
            check_error(&e, "from_faces");
        }
    }
});
