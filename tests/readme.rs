//! The Rust examples of README.md, compiled and run. Each `example!` holds one README block's
//! code; the test fails when the README's text and this file's differ (comments and spacing
//! aside), so the examples users copy are the ones that compile. What a block leaves to the
//! reader is defined before it, and what it claims is checked after it, against closed forms
//! (face and vertex counts) or the same result reached through another call.

use std::error::Error;

/// Runs the tokens as statements here and records their text.
macro_rules! example {
    ($seen:ident, $($code:tt)*) => {
        $seen.push(stringify!($($code)*).to_string());
        $($code)*
    };
}

/// Code without `//` comments and whitespace, the form in which a README block and its
/// `stringify!`-ed copy here compare equal.
fn normalized(code: &str) -> String {
    code.lines()
        .map(|line| line.split_once("//").map_or(line, |(code, _)| code))
        .flat_map(|line| line.chars().filter(|c| !c.is_whitespace()))
        .collect()
}

/// The ```rust blocks of README.md.
fn readme_blocks() -> Vec<String> {
    let readme = include_str!("../README.md");
    let mut blocks = Vec::new();
    let mut rest = readme;
    while let Some(start) = rest.find("```rust\n") {
        let body = &rest[start + "```rust\n".len()..];
        let end = body.find("```").unwrap_or(body.len());
        blocks.push(body[..end].to_string());
        rest = &body[end..];
    }
    blocks
}

fn max_diff(a: &[f32], b: &[f32]) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f32::max)
}

#[test]
fn the_readmes_rust_examples_compile_and_do_what_they_say() -> Result<(), Box<dyn Error>> {
    let mut seen: Vec<String> = Vec::new();
    {
        example!(seen,
            use subsurf::{subdivide, Boundary, Options, PolyMesh, Scheme};
            let mesh = PolyMesh {
                positions: vec![1.0, 1.0, 1.0, 1.0, -1.0, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, 1.0],
                indices: vec![0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2],
                face_sizes: vec![3; 4],
            };
            let refined = subdivide(&mesh, &Options::new(Scheme::Loop, 2).with_boundary(Boundary::EdgeOnly))?;
        );
        // Loop on a closed triangle mesh: F' = 4F and V' = V + E, E' = 2E + 3F per level.
        assert_eq!(refined.face_sizes, vec![3; 64]);
        assert_eq!(refined.positions.len(), 3 * 34);
        assert_eq!(refined.indices.len(), 3 * 64);

        // The second example in the same scope: its `mesh` and `Options` are the first's, as
        // the README reads them.
        use subsurf::Tags;
        let options = Options::new(Scheme::Loop, 2);
        // An affine function of the positions, which stays that function of the refined ones.
        let affine = |positions: &[f32]| -> Vec<f32> {
            positions.iter().enumerate().map(|(i, p)| 0.25 * p + 0.1 * (i % 3) as f32).collect()
        };
        let colors = affine(&mesh.positions);
        example!(seen,
            use subsurf::attributes::Attribute;
            use subsurf::scheme::subdivide_with_attributes;
            let color = Attribute::vertex("color", 3, colors);
            let (refined, channels) = subdivide_with_attributes(&mesh, &[color], &options, &Tags::default())?;
        );
        assert!(max_diff(&channels[0].values, &affine(&refined.positions)) < 1e-6);
    }
    {
        let cage = subsurf::PolyMesh {
            positions: vec![
                -1.0, -1.0, -1.0, -1.0, -1.0, 1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0, -1.0,
                -1.0, 1.0, -1.0, 1.0, 1.0, 1.0, -1.0, 1.0, 1.0, 1.0,
            ],
            indices: vec![0, 4, 5, 1, 4, 6, 7, 5, 6, 2, 3, 7, 2, 0, 1, 3, 1, 5, 7, 3, 0, 2, 6, 4],
            face_sizes: vec![4; 6],
        };
        let moved_cage_positions: Vec<f32> = cage
            .positions
            .iter()
            .enumerate()
            .map(|(i, p)| p * (1.0 + 0.2 * (i % 3) as f32))
            .collect();
        let colors: Vec<f32> =
            cage.positions.chunks(3).flat_map(|p| [p[0], p[1], p[2], 1.0]).collect();
        // Catmull-Clark level 2 on a cube: 96 quads, so 98 points (Euler: V = F + 2).
        let mut refined_colors = vec![0.0f32; 4 * 98];
        example!(seen,
            use subsurf::{stencil_table, Options, Scheme, Tags};
            let (table, mut refined) = stencil_table(&cage, &Options::new(Scheme::CatmullClark, 2), &Tags::default())?;
            table.evaluate(&moved_cage_positions, 3, &mut refined.positions)?;
            table.evaluate(&colors, 4, &mut refined_colors)?;
        );
        let options = Options::new(Scheme::CatmullClark, 2);
        let moved = subsurf::PolyMesh { positions: moved_cage_positions.clone(), ..cage.clone() };
        let expected = subsurf::subdivide(&moved, &options)?;
        assert_eq!(refined.indices, expected.indices);
        assert!(max_diff(&refined.positions, &expected.positions) < 1e-5);
        // The rows' weights sum to one: (x, y, z, 1) of the cage gives (x, y, z, 1) refined.
        let still = subsurf::subdivide(&cage, &options)?;
        let expected_colors: Vec<f32> =
            still.positions.chunks(3).flat_map(|p| [p[0], p[1], p[2], 1.0]).collect();
        assert!(max_diff(&refined_colors, &expected_colors) < 1e-5);
    }

    let blocks = readme_blocks();
    for block in &blocks {
        assert!(
            seen.iter().any(|code| normalized(code) == normalized(block)),
            "this README block is not the code tests/readme.rs runs; update one of them:\n{block}"
        );
    }
    assert_eq!(blocks.len(), seen.len(), "every example here is a README block");
    Ok(())
}
