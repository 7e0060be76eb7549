//! A typed reference to a collider in the world's packed arrays: a dynamic
//! body's index or a static body's index, told apart by one bit.
//!
//! The contact code keeps these in its hot arrays (contact rows, pair
//! lists), so the reference stays one `u32`: the top bit marks a static
//! body, the low 31 bits are the index in its array. Construct and read it
//! only through the methods below; nothing else decodes the bit.

/// A dynamic or static body, by its index in the world's arrays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(transparent))]
pub(crate) struct ColliderRef(u32);

/// The bit that marks a static body.
const STATIC: u32 = 1 << 31;

impl ColliderRef {
    /// Dynamic body `i` (or, in the broad phase's pair lists, proxy `i`).
    #[inline(always)]
    pub(crate) const fn dynamic(i: u32) -> Self {
        debug_assert!(i & STATIC == 0);
        Self(i)
    }

    /// Static body `i`.
    #[inline(always)]
    pub(crate) const fn fixed(i: u32) -> Self {
        debug_assert!(i & STATIC == 0);
        Self(i | STATIC)
    }

    /// Whether this is a static body.
    #[inline(always)]
    pub(crate) const fn is_static(self) -> bool {
        self.0 & STATIC != 0
    }

    /// The index in its array (dynamic or static).
    #[inline(always)]
    pub(crate) const fn index(self) -> usize {
        (self.0 & !STATIC) as usize
    }

    /// The dynamic index, or `None` for a static body.
    #[inline(always)]
    pub(crate) const fn dynamic_index(self) -> Option<usize> {
        if self.is_static() {
            None
        } else {
            Some(self.0 as usize)
        }
    }

    /// The same kind of reference with another index: a dynamic body that a
    /// removal moved, a proxy resolved to its body.
    #[inline(always)]
    pub(crate) const fn with_index(self, i: u32) -> Self {
        if self.is_static() {
            Self::fixed(i)
        } else {
            Self::dynamic(i)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::ColliderRef;

    #[test]
    fn a_reference_keeps_its_kind_and_index() {
        let d = ColliderRef::dynamic(7);
        let s = ColliderRef::fixed(7);
        assert!(!d.is_static() && s.is_static());
        assert_eq!((d.index(), s.index()), (7, 7));
        assert_eq!((d.dynamic_index(), s.dynamic_index()), (Some(7), None));
        assert_ne!(d, s);
        assert_eq!(s.with_index(3), ColliderRef::fixed(3));
        let top = (1 << 31) - 1;
        assert_eq!(ColliderRef::fixed(top).index(), top as usize);
    }
}
