//! Applying the rules' weights to data (OpenSubdiv's `Far::PrimvarRefiner`): the sinks that turn
//! a new point's [`Weights`] into a value, for positions and for rows of any width.

use crate::rules::Weights;
use glam::Vec3;

/// Sums weighted positions (or any three floats per vertex): the parent level's `points` by
/// vertex, corners through `he_from`, and the child level's `face_points` by cell.
pub struct PointSum<'a> {
    pub points: &'a [[f32; 3]],
    pub he_from: &'a [u32],
    pub face_points: &'a [[f32; 3]],
    pub sum: Vec3,
}

impl<'a> PointSum<'a> {
    #[inline(always)]
    pub fn new(points: &'a [[f32; 3]], he_from: &'a [u32], face_points: &'a [[f32; 3]]) -> Self {
        PointSum { points, he_from, face_points, sum: Vec3::ZERO }
    }

    /// The point whose weights `rule` gives.
    #[inline(always)]
    pub fn eval(&mut self, rule: impl FnOnce(&mut Self)) -> [f32; 3] {
        self.sum = Vec3::ZERO;
        rule(self);
        self.sum.to_array()
    }
}

impl Weights for PointSum<'_> {
    #[inline(always)]
    fn vertex(&mut self, v: u32, weight: f32) {
        self.sum += Vec3::from_array(self.points[v as usize]) * weight;
    }

    #[inline(always)]
    fn corner(&mut self, h: u32, weight: f32) {
        self.vertex(self.he_from[h as usize], weight);
    }

    #[inline(always)]
    fn face_point(&mut self, c: u32, weight: f32) {
        self.sum += Vec3::from_array(self.face_points[c as usize]) * weight;
    }
}

/// Sums weighted rows of `width` floats per vertex (every vertex-varying channel side by side):
/// the parent level's `rows` by vertex, corners through `he_from`, and the child level's
/// `face_rows` by cell, into `sum`.
pub struct RowSum<'a> {
    pub rows: &'a [f32],
    pub width: usize,
    pub he_from: &'a [u32],
    pub face_rows: &'a [f32],
    pub sum: Vec<f32>,
}

impl<'a> RowSum<'a> {
    pub fn new(rows: &'a [f32], width: usize, he_from: &'a [u32], face_rows: &'a [f32]) -> Self {
        RowSum { rows, width, he_from, face_rows, sum: vec![0.0; width] }
    }

    /// Appends to `out` the row whose weights `rule` gives.
    #[inline]
    pub fn eval_into(&mut self, out: &mut Vec<f32>, rule: impl FnOnce(&mut Self)) {
        self.sum.fill(0.0);
        rule(self);
        out.extend_from_slice(&self.sum);
    }

    #[inline(always)]
    fn add(sum: &mut [f32], row: &[f32], weight: f32) {
        for (s, &x) in sum.iter_mut().zip(row) {
            *s += x * weight;
        }
    }
}

impl Weights for RowSum<'_> {
    #[inline]
    fn vertex(&mut self, v: u32, weight: f32) {
        let start = v as usize * self.width;
        Self::add(&mut self.sum, &self.rows[start..start + self.width], weight);
    }

    #[inline]
    fn corner(&mut self, h: u32, weight: f32) {
        self.vertex(self.he_from[h as usize], weight);
    }

    #[inline]
    fn face_point(&mut self, c: u32, weight: f32) {
        let start = c as usize * self.width;
        Self::add(&mut self.sum, &self.face_rows[start..start + self.width], weight);
    }
}
