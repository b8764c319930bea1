//! Topology hosts: how the child mesh is connected. A host asks a stencil policy from
//! [`crate::rules`] for every new point and never chooses a weight itself.
//!
//! - [`pqq`]: primal quad split (Catmull-Clark, bilinear);
//! - [`ptq`]: primal triangle split (Loop, midpoint);
//! - [`dqq`]: dual split (Doo-Sabin);
//! - [`quad_tri`]: triangles as PTQ, other faces as PQQ (Quad/Triangle);
//! - [`sqrt3`]: centroid split and edge flips (√3).

pub mod dqq;
pub mod pqq;
pub mod ptq;
pub mod quad_tri;
pub mod sqrt3;
