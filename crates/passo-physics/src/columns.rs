//! Vectors kept as two arrays, one of x and one of y: structure of arrays
//! down to the components. A loop over them loads whole vector registers
//! of x and of y, with no shuffles to pull interleaved `Vec2`s apart
//! (BENCHMARKS.md, "Why the code is shaped this way", has what the
//! interleaved layout cost). The dynamic bodies keep their
//! positions, velocities and forces this way.
//!
//! Serialised as a sequence of `Vec2`, as a `Vec<Vec2>` is: the layout in
//! memory does not show in a snapshot file.

use glam::Vec2;
use std::ops::Range;

/// Vectors as an array of x and an array of y, of the same length.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Columns {
    x: Vec<f32>,
    y: Vec<f32>,
}

impl Columns {
    pub(crate) fn len(&self) -> usize {
        self.x.len()
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Vector `i`.
    ///
    /// # Panics
    /// If `i` is out of range.
    #[inline(always)]
    pub(crate) fn at(&self, i: usize) -> Vec2 {
        Vec2::new(self.x[i], self.y[i])
    }

    /// Vector `i`, or `None` if `i` is out of range.
    pub(crate) fn get(&self, i: usize) -> Option<Vec2> {
        (i < self.len()).then(|| self.at(i))
    }

    #[inline(always)]
    pub(crate) fn set(&mut self, i: usize, v: Vec2) {
        self.x[i] = v.x;
        self.y[i] = v.y;
    }

    pub(crate) fn push(&mut self, v: Vec2) {
        self.x.push(v.x);
        self.y.push(v.y);
    }

    /// Removes vector `i`, moving the last one into its place.
    pub(crate) fn swap_remove(&mut self, i: usize) {
        self.x.swap_remove(i);
        self.y.swap_remove(i);
    }

    pub(crate) fn fill(&mut self, v: Vec2) {
        self.x.fill(v.x);
        self.y.fill(v.y);
    }

    /// Makes this a copy of `other`, reusing this one's buffers.
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.x.clone_from(&other.x);
        self.y.clone_from(&other.y);
    }

    /// Bytes the arrays hold on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.x.capacity() + self.y.capacity()) * std::mem::size_of::<f32>()
    }

    /// The vectors in order.
    pub(crate) fn iter(&self) -> impl ExactSizeIterator<Item = Vec2> + Clone + '_ {
        self.view().iter()
    }

    pub(crate) fn view(&self) -> ColumnsRef<'_> {
        ColumnsRef {
            x: &self.x,
            y: &self.y,
        }
    }

    pub(crate) fn view_mut(&mut self) -> ColumnsMut<'_> {
        ColumnsMut {
            x: &mut self.x,
            y: &mut self.y,
        }
    }
}

impl FromIterator<Vec2> for Columns {
    fn from_iter<I: IntoIterator<Item = Vec2>>(iter: I) -> Self {
        let (x, y) = iter.into_iter().map(|v| (v.x, v.y)).unzip();
        Self { x, y }
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Columns {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.iter())
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Columns {
    /// Read straight into the two arrays: no `Vec<Vec2>` in between, which
    /// would double what a large (or damaged) snapshot takes to decode.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Vectors;
        impl<'de> serde::de::Visitor<'de> for Vectors {
            type Value = Columns;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a sequence of vectors")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Columns, A::Error> {
                // A length from the file is a hint, not a promise: reserve
                // at most a few thousand up front, then grow as read.
                let n = seq.size_hint().unwrap_or(0).min(4096);
                let mut c = Columns {
                    x: Vec::with_capacity(n),
                    y: Vec::with_capacity(n),
                };
                while let Some(v) = seq.next_element::<Vec2>()? {
                    c.push(v);
                }
                Ok(c)
            }
        }
        d.deserialize_seq(Vectors)
    }
}

/// A run of [`Columns`] to read.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ColumnsRef<'a> {
    pub x: &'a [f32],
    pub y: &'a [f32],
}

impl<'a> ColumnsRef<'a> {
    pub(crate) fn len(&self) -> usize {
        self.x.len()
    }

    #[inline(always)]
    pub(crate) fn at(&self, i: usize) -> Vec2 {
        Vec2::new(self.x[i], self.y[i])
    }

    /// The vectors in `range`.
    pub(crate) fn slice(self, range: Range<usize>) -> Self {
        Self {
            x: &self.x[range.clone()],
            y: &self.y[range],
        }
    }

    pub(crate) fn split_at(self, mid: usize) -> (Self, Self) {
        let (xa, xb) = self.x.split_at(mid);
        let (ya, yb) = self.y.split_at(mid);
        (Self { x: xa, y: ya }, Self { x: xb, y: yb })
    }

    pub(crate) fn iter(self) -> impl ExactSizeIterator<Item = Vec2> + Clone + 'a {
        let y = &self.y[..self.x.len()];
        self.x.iter().zip(y).map(|(&x, &y)| Vec2::new(x, y))
    }
}

/// A run of [`Columns`] to write.
#[derive(Debug)]
pub(crate) struct ColumnsMut<'a> {
    pub x: &'a mut [f32],
    pub y: &'a mut [f32],
}

impl<'a> ColumnsMut<'a> {
    pub(crate) fn len(&self) -> usize {
        self.x.len()
    }

    /// The x and the y array, of the same length (so that a loop over
    /// `0..x.len()` indexes both with no bounds check).
    pub(crate) fn into_parts(self) -> (&'a mut [f32], &'a mut [f32]) {
        let n = self.x.len();
        (self.x, &mut self.y[..n])
    }

    /// The vectors in `range`, to write.
    pub(crate) fn slice(&mut self, range: Range<usize>) -> ColumnsMut<'_> {
        ColumnsMut {
            x: &mut self.x[range.clone()],
            y: &mut self.y[range],
        }
    }

    pub(crate) fn split_at(self, mid: usize) -> (Self, Self) {
        let (xa, xb) = self.x.split_at_mut(mid);
        let (ya, yb) = self.y.split_at_mut(mid);
        (Self { x: xa, y: ya }, Self { x: xb, y: yb })
    }

    pub(crate) fn as_ref(&self) -> ColumnsRef<'_> {
        ColumnsRef {
            x: self.x,
            y: self.y,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn columns() -> Columns {
        (0..5).map(|i| Vec2::new(i as f32, -(i as f32))).collect()
    }

    #[test]
    fn vectors_go_in_and_out_by_index_and_in_order() {
        let mut c = columns();
        assert_eq!(c.len(), 5);
        assert_eq!(c.at(3), Vec2::new(3.0, -3.0));
        assert_eq!(c.get(5), None);
        c.set(1, Vec2::new(9.0, 8.0));
        c.swap_remove(0);
        let expected = [(4.0, -4.0), (9.0, 8.0), (2.0, -2.0), (3.0, -3.0)];
        let got: Vec<_> = c.iter().map(|v| (v.x, v.y)).collect();
        assert_eq!(got, expected);
        let (left, right) = c.view_mut().split_at(1);
        let (x, y) = right.into_parts();
        (x[0], y[2]) = (10.0, 7.0);
        assert_eq!(left.len(), 1);
        assert_eq!(c.at(1), Vec2::new(10.0, 8.0));
        let (left, right) = c.view().split_at(3);
        assert_eq!((left.at(2), right.len()), (Vec2::new(2.0, -2.0), 1));
        assert_eq!(c.view().slice(2..4).at(1), Vec2::new(3.0, 7.0));
    }
}
