//! Axis-aligned bounding boxes.

use glam::Vec2;

/// An axis-aligned box from `min` to `max`, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Aabb {
    /// Lower-left corner.
    pub min: Vec2,
    /// Upper-right corner.
    pub max: Vec2,
}

impl Aabb {
    /// The box centred on `centre` with the given half extents.
    pub fn from_centre(centre: Vec2, half_extents: Vec2) -> Self {
        Self {
            min: centre - half_extents,
            max: centre + half_extents,
        }
    }

    /// Whether the boxes overlap or touch.
    ///
    /// The four comparisons are all made and combined with `&`, not `&&`:
    /// one branch instead of four, which the broad phase's search (where
    /// about half the candidates touch) measured faster.
    #[inline]
    pub fn overlaps(&self, other: &Self) -> bool {
        (self.min.x <= other.max.x)
            & (other.min.x <= self.max.x)
            & (self.min.y <= other.max.y)
            & (other.min.y <= self.max.y)
    }

    /// Whether `p` is inside or on the boundary.
    #[inline]
    pub fn contains_point(&self, p: Vec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// The smallest box containing both.
    #[inline]
    pub fn union(&self, other: &Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The box grown by `margin` on every side.
    #[inline]
    pub fn grown(&self, margin: f32) -> Self {
        Self {
            min: self.min - Vec2::splat(margin),
            max: self.max + Vec2::splat(margin),
        }
    }

    /// Centre point.
    pub fn centre(&self) -> Vec2 {
        (self.min + self.max) * 0.5
    }

    /// Width and height.
    pub fn size(&self) -> Vec2 {
        self.max - self.min
    }
}
