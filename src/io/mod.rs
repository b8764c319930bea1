//! Reading and writing mesh files.

pub mod obj;

pub use obj::{read_obj, write_obj};
