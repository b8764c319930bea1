//! Data a mesh carries besides positions: named channels of floats (colours, skin weights, morph
//! targets, UVs), refined with the same weights as the positions (OpenSubdiv's primvars).
//!
//! A channel is vertex-varying (one value per vertex) or face-varying (one value index per face
//! corner, so a vertex may have several values: UVs split at a seam). Vertex-varying channels
//! travel side by side as [`Rows`] through the levels.
//!
//! ```
//! use subsurf::attributes::Attribute;
//! use subsurf::scheme::subdivide_with_attributes;
//! use subsurf::{shapes, Options, Scheme, Tags};
//!
//! let cube = shapes::cube();
//! // A channel that is the x coordinate: it stays the x coordinate of every refined vertex.
//! let x: Vec<f32> = cube.positions.chunks(3).map(|p| p[0]).collect();
//! let options = Options::new(Scheme::CatmullClark, 2);
//! let (refined, channels) =
//!     subdivide_with_attributes(&cube, &[Attribute::vertex("x", 1, x)], &options, &Tags::default())
//!         .unwrap();
//! for (p, x) in refined.positions.chunks(3).zip(&channels[0].values) {
//!     assert!((p[0] - x).abs() < 1e-6);
//! }
//! ```

use crate::error::{Error, Result};
use crate::primvar::Rows;

/// The most floats one value of a channel may have.
pub const MAX_ITEM_SIZE: usize = 16;

/// One named channel of `item_size` floats per value.
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    pub name: String,
    /// Floats per value, 1 to [`MAX_ITEM_SIZE`].
    pub item_size: usize,
    /// The values, `item_size` floats each.
    pub values: Vec<f32>,
    /// `None` for a vertex-varying channel (one value per vertex, in vertex order). For a
    /// face-varying one, the value of each face corner, parallel to the mesh's `indices`.
    pub indices: Option<Vec<u32>>,
}

impl Attribute {
    /// A vertex-varying channel.
    pub fn vertex(name: impl Into<String>, item_size: usize, values: Vec<f32>) -> Self {
        Attribute { name: name.into(), item_size, values, indices: None }
    }

    /// A face-varying channel: `indices[k]` is the value of face corner `k`.
    pub fn face_varying(
        name: impl Into<String>,
        item_size: usize,
        values: Vec<f32>,
        indices: Vec<u32>,
    ) -> Self {
        Attribute { name: name.into(), item_size, values, indices: Some(indices) }
    }

    pub fn is_face_varying(&self) -> bool {
        self.indices.is_some()
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        self.values.len().checked_div(self.item_size).unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

fn invalid(name: &str, message: String) -> Error {
    Error::InvalidAttribute(format!("attribute '{name}': {message}"))
}

/// Checks every channel against a mesh of `vertices` vertices and `corners` face corners.
pub fn validate(attributes: &[Attribute], vertices: usize, corners: usize) -> Result<()> {
    for (i, a) in attributes.iter().enumerate() {
        let name = &a.name;
        if attributes[..i].iter().any(|b| b.name == a.name) {
            return Err(invalid(
                name,
                "the name is given twice; give each channel its own name".into(),
            ));
        }
        if a.item_size == 0 || a.item_size > MAX_ITEM_SIZE {
            return Err(invalid(
                name,
                format!("itemSize is {}; it must be 1 to {MAX_ITEM_SIZE}", a.item_size),
            ));
        }
        if !a.values.len().is_multiple_of(a.item_size) {
            return Err(invalid(
                name,
                format!("{} values is not a multiple of itemSize {}", a.values.len(), a.item_size),
            ));
        }
        if let Some(k) = a.values.iter().position(|x| !x.is_finite()) {
            return Err(invalid(
                name,
                format!(
                    "value {} has component {} = {}; every value must be a finite number",
                    k / a.item_size,
                    k % a.item_size,
                    a.values[k]
                ),
            ));
        }
        match &a.indices {
            None if a.len() != vertices => {
                return Err(invalid(
                    name,
                    format!(
                        "has {} values of itemSize {} but the mesh has {vertices} vertices; a vertex-varying channel has one value per vertex (give indices for one value per face corner)",
                        a.len(),
                        a.item_size
                    ),
                ));
            }
            None => {}
            Some(indices) => {
                if indices.len() != corners {
                    return Err(invalid(
                        name,
                        format!(
                            "has {} indices but the mesh has {corners} face corners; a face-varying channel has one index per entry of the mesh's indices",
                            indices.len()
                        ),
                    ));
                }
                if let Some(k) = indices.iter().position(|&x| x as usize >= a.len()) {
                    return Err(invalid(
                        name,
                        format!(
                            "index {k} is {}, but the channel has {} values (0..{})",
                            indices[k],
                            a.len(),
                            a.len().saturating_sub(1)
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Where each vertex-varying channel sits in [`Rows`]: its attribute's position in the list and
/// its first column.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RowLayout {
    /// `(attribute index, name, item size, first column)` of each vertex-varying channel.
    pub channels: Vec<(usize, String, usize, usize)>,
    pub width: usize,
}

/// The vertex-varying channels of `attributes` side by side, one row per vertex.
pub fn pack(attributes: &[Attribute], vertices: usize) -> (Rows, RowLayout) {
    let mut layout = RowLayout::default();
    for (i, a) in attributes.iter().enumerate().filter(|(_, a)| !a.is_face_varying()) {
        layout.channels.push((i, a.name.clone(), a.item_size, layout.width));
        layout.width += a.item_size;
    }
    let width = layout.width;
    if width == 0 {
        return (Rows::default(), layout);
    }
    let mut values = vec![0.0f32; vertices * width];
    for (i, _, size, column) in &layout.channels {
        let source = &attributes[*i].values;
        for (row, value) in values.chunks_exact_mut(width).zip(source.chunks_exact(*size)) {
            row[*column..column + size].copy_from_slice(value);
        }
    }
    (Rows { width, values }, layout)
}

/// The channels of `layout` taken back out of `rows`. A lone channel takes the rows' values as
/// they are (no copy: a level-1 result of 1M quads has 4M rows).
pub fn unpack(rows: Rows, layout: &RowLayout) -> Vec<Attribute> {
    if let [(_, name, size, 0)] = &layout.channels[..] {
        if *size == rows.width {
            return vec![Attribute::vertex(name.clone(), *size, rows.values)];
        }
    }
    layout
        .channels
        .iter()
        .map(|(_, name, size, column)| {
            let mut values = Vec::with_capacity(rows.len() * size);
            for row in rows.values.chunks_exact(rows.width.max(1)) {
                values.extend_from_slice(&row[*column..column + size]);
            }
            Attribute::vertex(name.clone(), *size, values)
        })
        .collect()
}
