//! Topology hosts: how the child mesh is connected. A host asks a stencil policy from
//! [`crate::rules`] for every new point and never chooses a weight itself.

pub mod pqq;
