//! # subsurf: subdivision surfaces for the web
//!
//! Flat arrays in, flat arrays out. Build a [`PolyMesh`] (positions, face indices, face sizes),
//! call [`subdivide`], get the refined [`PolyMesh`] back.
//!
//! ```
//! use subsurf::{subdivide, Options, PolyMesh, Scheme};
//! // A unit square, one quad.
//! let square = PolyMesh {
//!     positions: vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.],
//!     indices: vec![0, 1, 2, 3],
//!     face_sizes: vec![4],
//! };
//! let refined = subdivide(&square, &Options::new(Scheme::CatmullClark, 2)).unwrap();
//! assert_eq!(refined.num_faces(), 16);
//! ```
//!
//! Layers, bottom up: [`mesh`] (the half-edge mesh), [`options`] (the vocabulary), [`rules`]
//! (rules as weights), [`primvar`] (applying weights to data), [`refine`] (topology hosts),
//! [`fvar`] (face-varying topology and values), [`attributes`] (data besides positions),
//! [`stencil`] (stencil tables) and [`evaluator`] (refine once, evaluate every frame), [`scheme`] (the driver), [`drawable`] (one index buffer for meshes with seams), [`triangles`] (triangle soups
//! from renderers welded and joined into faces), [`io`] (OBJ),
//! and the wasm bindings.

pub mod attributes;
pub mod drawable;
pub mod error;
pub mod evaluator;
pub mod fvar;
pub mod io;
pub mod limit;
pub mod mesh;
pub mod options;
mod patches;
pub mod predict;
pub mod primvar;
mod quad_rings;
pub mod refine;
pub mod refined;
mod regular_rings;
pub mod rules;
pub mod scheme;
pub mod shapes;
mod shared_weights;
mod smooth_levels;
pub mod stencil;
pub mod tags;
pub mod triangles;

#[cfg(target_arch = "wasm32")]
pub mod wasm;

pub use error::{Error, Result};
pub use evaluator::Evaluator;
pub use mesh::{HalfEdgeMesh, PolyMesh};
pub use options::{Boundary, CreaseMethod, FVarLinear};
pub use scheme::{stencil_table, subdivide, subdivide_with_tags, Options, Scheme};
pub use stencil::StencilTable;
pub use tags::{Corner, Crease, Tags};
