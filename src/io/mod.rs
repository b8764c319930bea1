//! Reading and writing mesh files.

pub mod obj;
mod text;

pub use obj::{
    read_obj, read_obj_with, read_obj_with_tags, write_obj, write_obj_to, write_obj_with,
    write_obj_with_normals, ObjMesh, ObjReadOptions, UV,
};
