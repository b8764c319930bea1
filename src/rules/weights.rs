//! The vocabulary rules speak in: a new point is a weighted sum of parent values, named by
//! topology alone. OpenSubdiv's `Sdc` masks carry the same information as three weight lists
//! (vertex, edges, faces) over a neighbourhood the caller lays out; a sink that is told each
//! source as the rule finds it needs no such layout, and lets a rule say "the other end of this
//! half-edge" in a way that face-varying data can resolve per face.

/// Where a rule puts the weights of one new point: each call adds `weight` times one parent
/// value. The weights of a point sum to 1 (every rule here is affine).
pub trait Weights {
    /// The value at parent vertex `v`, which is either the vertex a vertex rule moves or an end
    /// of the edge an edge rule splits. Data with several values per vertex (face-varying
    /// seams) resolves it from that context.
    fn vertex(&mut self, v: u32, weight: f32);
    /// The value at the corner where parent half-edge `h` starts: its from-vertex, as `h`'s cell
    /// sees it.
    fn corner(&mut self, h: u32, weight: f32);
    /// The face point of parent cell `c`: a point of the child level, which the host computes
    /// before any point that weights it.
    fn face_point(&mut self, c: u32, weight: f32);
    /// True for a sink to which a face point costs more than its cell's corners: a stencil's
    /// face point is a composed row, longer than a parent's. A rule that can weight the corners
    /// instead (Catmull-Clark's vertex rule among quads) then does.
    const FACE_POINTS_COST_MORE: bool = false;
    /// What a sink keeps while a group is open (the sum so far, or the scale outside it).
    type Group;
    /// Opens a group: everything added until [`Weights::end_group`] counts `scale` times. A rule
    /// that weights many sources alike (the ring of a vertex, the corners of a face) adds them
    /// at weight 1 in a group, so that a sink that sums values scales the group's sum once, as a
    /// hand-written stencil would: cheaper, and with less rounding, than scaling each value.
    /// Groups nest.
    fn begin_group(&mut self, scale: f32) -> Self::Group;
    /// Closes the group `begin_group` opened.
    fn end_group(&mut self, group: Self::Group);
    /// Adds `scale` times everything `group` adds (a group around a closure).
    #[inline(always)]
    fn scaled(&mut self, scale: f32, group: impl FnOnce(&mut Self))
    where
        Self: Sized,
    {
        let open = self.begin_group(scale);
        group(self);
        self.end_group(open);
    }
}

/// A sink that scales every weight by `scale` before passing it on: a rule that blends two
/// rules (a crease in transition) runs each into its own `Scaled`.
pub struct Scaled<'a, W: Weights> {
    pub inner: &'a mut W,
    pub scale: f32,
}

impl<W: Weights> Weights for Scaled<'_, W> {
    const FACE_POINTS_COST_MORE: bool = W::FACE_POINTS_COST_MORE;

    #[inline(always)]
    fn vertex(&mut self, v: u32, weight: f32) {
        self.inner.vertex(v, weight * self.scale);
    }

    #[inline(always)]
    fn corner(&mut self, h: u32, weight: f32) {
        self.inner.corner(h, weight * self.scale);
    }

    #[inline(always)]
    fn face_point(&mut self, c: u32, weight: f32) {
        self.inner.face_point(c, weight * self.scale);
    }

    type Group = W::Group;

    #[inline(always)]
    fn begin_group(&mut self, scale: f32) -> W::Group {
        self.inner.begin_group(scale)
    }

    #[inline(always)]
    fn end_group(&mut self, group: W::Group) {
        self.inner.end_group(group);
    }
}

/// One source of a recorded stencil.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Source {
    Vertex(u32),
    Corner(u32),
    FacePoint(u32),
}

/// A sink that records the weights as given, in order: for applying one rule's weights to
/// several buffers, for tests, and for rule sets written outside the crate to inspect.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stencil {
    pub sources: Vec<(Source, f32)>,
}

impl Stencil {
    /// The sum of all weights (1 for an affine rule).
    pub fn total(&self) -> f32 {
        self.sources.iter().map(|&(_, w)| w).sum()
    }

    /// Gives the recorded weights to `w`, in order.
    pub fn replay(&self, w: &mut impl Weights) {
        for &(source, weight) in &self.sources {
            match source {
                Source::Vertex(v) => w.vertex(v, weight),
                Source::Corner(h) => w.corner(h, weight),
                Source::FacePoint(c) => w.face_point(c, weight),
            }
        }
    }
}

impl Weights for Stencil {
    fn vertex(&mut self, v: u32, weight: f32) {
        self.sources.push((Source::Vertex(v), weight));
    }

    fn corner(&mut self, h: u32, weight: f32) {
        self.sources.push((Source::Corner(h), weight));
    }

    fn face_point(&mut self, c: u32, weight: f32) {
        self.sources.push((Source::FacePoint(c), weight));
    }

    /// Where the group's sources start, and its scale.
    type Group = (usize, f32);

    fn begin_group(&mut self, scale: f32) -> (usize, f32) {
        (self.sources.len(), scale)
    }

    fn end_group(&mut self, (start, scale): (usize, f32)) {
        for (_, w) in &mut self.sources[start..] {
            *w *= scale;
        }
    }
}
