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
use crate::fvar::{FVarChannel, SeamCorners};
use crate::primvar::Rows;
use std::borrow::Cow;

/// The most floats one value of a channel may have.
pub const MAX_ITEM_SIZE: usize = 16;

// Face-varying channels are summed in rows of at most this width.
const _: () = assert!(MAX_ITEM_SIZE <= crate::primvar::FVAR_MAX_WIDTH);

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
        if let Some(k) = crate::mesh::first_unusable(&a.values) {
            return Err(invalid(
                name,
                format!(
                    "value {} has component {} = {}; {}",
                    k / a.item_size,
                    k % a.item_size,
                    a.values[k],
                    crate::mesh::unusable_because(a.values[k], "value")
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
                let largest = indices.iter().fold(0, |m, &x| m.max(x));
                let in_range = indices.is_empty() || (largest as usize) < a.len();
                let out_of_range = |&x: &u32| x as usize >= a.len();
                let first_bad = || indices.iter().position(out_of_range);
                if let Some(k) = (!in_range).then(first_bad).flatten() {
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
pub fn pack(attributes: &[Attribute], vertices: usize) -> (Rows<'_>, RowLayout) {
    let mut layout = RowLayout::default();
    for (i, a) in attributes.iter().enumerate().filter(|(_, a)| !a.is_face_varying()) {
        layout.channels.push((i, a.name.clone(), a.item_size, layout.width));
        layout.width += a.item_size;
    }
    let width = layout.width;
    if width == 0 {
        return (Rows::default(), layout);
    }
    let values = interleave(attributes, &layout.channels, vertices, width);
    (Rows { width, values }, layout)
}

/// `count` rows of `width` floats, with the values of each member `(attribute index, name,
/// item size, first column)` side by side. A lone member's values are borrowed as they are:
/// the first level only reads them (12 MB not copied for a colour on 1M vertices).
fn interleave<'a>(
    attributes: &'a [Attribute],
    members: &[(usize, String, usize, usize)],
    count: usize,
    width: usize,
) -> Cow<'a, [f32]> {
    if let [(i, _, size, _)] = *members {
        let source = &attributes[i].values;
        return Cow::Borrowed(&source[..(count * size).min(source.len())]);
    }
    let mut values = vec![0.0; count * width];
    for &(i, _, size, column) in members {
        let source = &attributes[i].values;
        for (row, value) in values.chunks_exact_mut(width).zip(source.chunks_exact(size)) {
            row[column..column + size].copy_from_slice(value);
        }
    }
    Cow::Owned(values)
}

/// The channels of `layout` taken back out of `rows`. A lone channel takes the rows' values as
/// they are (no copy: a level-1 result of 1M quads has 4M rows).
pub fn unpack(rows: Rows<'_>, layout: &RowLayout) -> Vec<Attribute> {
    if let [(_, name, size, 0)] = &layout.channels[..] {
        if *size == rows.width {
            return vec![Attribute::vertex(name.clone(), *size, rows.values.into_owned())];
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

/// Where each face-varying channel sits: channels with equal indices travel as one
/// [`FVarChannel`], side by side. Per group, `(attribute index, name, item size, first column)`
/// of each member.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FVarLayout {
    pub groups: Vec<Vec<(usize, String, usize, usize)>>,
}

/// The face-varying channels of `attributes`, those with equal indices side by side up to
/// [`MAX_ITEM_SIZE`] floats (their rows up to the shortest channel's count, which every index
/// is below).
pub fn pack_face_varying(attributes: &[Attribute]) -> (Vec<FVarChannel<'_>>, FVarLayout) {
    let mut layout = FVarLayout::default();
    let mut group_indices: Vec<&[u32]> = Vec::new();
    for (i, a) in attributes.iter().enumerate() {
        let Some(indices) = &a.indices else { continue };
        let width = |g: usize| layout.groups[g].iter().map(|m| m.2).sum::<usize>();
        let fits = |g: usize| width(g) + a.item_size <= MAX_ITEM_SIZE;
        match (0..group_indices.len()).find(|&g| group_indices[g] == &indices[..] && fits(g)) {
            Some(g) => {
                let column = layout.groups[g].iter().map(|m| m.2).sum();
                layout.groups[g].push((i, a.name.clone(), a.item_size, column));
            }
            None => {
                group_indices.push(indices);
                layout.groups.push(vec![(i, a.name.clone(), a.item_size, 0)]);
            }
        }
    }
    let channels = layout
        .groups
        .iter()
        .zip(&group_indices)
        .map(|(members, indices)| {
            let width: usize = members.iter().map(|m| m.2).sum();
            let count = members.iter().map(|m| attributes[m.0].len()).min().unwrap_or(0);
            // The indices are borrowed too: the first level only reads them.
            let values = interleave(attributes, members, count, width);
            FVarChannel::new(width, values, Cow::Borrowed(indices))
        })
        .collect();
    (channels, layout)
}

/// The channels of a result: every attribute, and for each face-varying one whose indices are
/// the result's implicit faces' own but near seams, its place among them and those corners
/// ([`SeamCorners`]; its `indices` are then empty).
#[derive(Debug, Default)]
pub struct Channels {
    pub attributes: Vec<Attribute>,
    pub seam_corners: Vec<(usize, SeamCorners)>,
}

/// Every channel back out, in the order of the `count` attributes given: the vertex-varying
/// ones from `rows` ([`unpack`]), the face-varying ones from `channels`, with the last level's
/// corner values as their indices.
pub fn unpack_all(
    rows: Rows<'_>,
    layout: &RowLayout,
    channels: Vec<FVarChannel<'_>>,
    fvar_layout: &FVarLayout,
    count: usize,
) -> Channels {
    let mut slots: Vec<Option<Attribute>> = vec![None; count];
    let mut seam_corners = Vec::new();
    for (a, (i, ..)) in unpack(rows, layout).into_iter().zip(&layout.channels) {
        slots[*i] = Some(a);
    }
    for (channel, members) in channels.into_iter().zip(&fvar_layout.groups) {
        let mut level = channel.into_level();
        let width = level.width;
        if let Some(seams) = level.seam_corners.take() {
            seam_corners.extend(members.iter().map(|m| (m.0, seams.clone())));
        }
        if let [(i, name, size, _)] = &members[..] {
            // A lone channel takes the level's arrays as they are.
            let (values, indices) = (level.values, level.corner_values);
            slots[*i] = Some(Attribute::face_varying(name.clone(), *size, values, indices));
            continue;
        }
        for (k, (i, name, size, column)) in members.iter().enumerate() {
            let values = if *size == width {
                level.values.clone()
            } else {
                let mut values = Vec::with_capacity(level.values.len() / width.max(1) * size);
                for row in level.values.chunks_exact(width.max(1)) {
                    values.extend_from_slice(&row[*column..column + size]);
                }
                values
            };
            let indices = if k + 1 == members.len() {
                std::mem::take(&mut level.corner_values)
            } else {
                level.corner_values.clone()
            };
            slots[*i] = Some(Attribute::face_varying(name.clone(), *size, values, indices));
        }
    }
    Channels { attributes: slots.into_iter().flatten().collect(), seam_corners }
}
