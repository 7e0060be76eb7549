//! How two bodies' friction coefficients combine into a contact's.

/// How a contact combines the friction coefficients `a` and `b` of its two
/// bodies. When the bodies name different rules, the later one in this
/// list wins (as Rapier's combine rules): an ice tile with `Min` makes
/// every body with the default rule (or `Average`) slide on it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum FrictionMix {
    /// `sqrt(a b)`: the default, as Box2D mixes friction.
    #[default]
    GeometricMean,
    /// `(a + b) / 2`.
    Average,
    /// `min(a, b)`: slippery surfaces (ice).
    Min,
    /// `a b`.
    Multiply,
    /// `max(a, b)`: grippy surfaces.
    Max,
}

impl FrictionMix {
    /// The contact's friction coefficient for bodies with coefficients `a`
    /// and `b` and rules `self` and `other`.
    #[inline]
    pub fn combine(self, other: Self, a: f32, b: f32) -> f32 {
        match self.max(other) {
            Self::GeometricMean => (a * b).sqrt(),
            Self::Average => 0.5 * (a + b),
            Self::Min => a.min(b),
            Self::Multiply => a * b,
            Self::Max => a.max(b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::FrictionMix::*;

    #[test]
    fn the_later_rule_wins_and_each_mixes_as_named() {
        assert_eq!(
            GeometricMean.combine(GeometricMean, 0.05, 0.6),
            (0.03f32).sqrt()
        );
        assert_eq!(Min.combine(GeometricMean, 0.05, 0.6), 0.05);
        assert_eq!(GeometricMean.combine(Min, 0.6, 0.05), 0.05);
        assert_eq!(Average.combine(Average, 0.2, 0.6), 0.4);
        assert_eq!(Max.combine(Min, 0.2, 0.6), 0.6);
        assert_eq!(Multiply.combine(Average, 0.5, 0.6), 0.3);
    }
}
