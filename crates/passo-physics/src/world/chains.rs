//! Chains: polylines of one-sided segments that meet smoothly, for sloped
//! ground and hills (see [`Shape::ChainSegment`]).

use crate::{BodyDef, BodyId, BodyKind, CollisionFilter, PhysicsError, Shape, World};
use glam::Vec2;

/// Most points in one chain.
pub const MAX_CHAIN_POINTS: usize = 1 << 20;

/// A chain of segments: ground that slopes. Each segment is a body with a
/// [`Shape::ChainSegment`], solid on the right of the way the points go:
/// ground drawn left to right is solid below, and a closed chain drawn
/// clockwise is solid inside.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainDef {
    /// The points, metres, in order; at least 2 (3 closed), no two in a
    /// row the same.
    pub points: Vec<Vec2>,
    /// Whether the last point joins the first.
    pub closed: bool,
    /// Static (the default) or kinematic (a sloped platform that moves:
    /// steer every segment alike).
    pub kind: BodyKind,
    /// Kinetic friction coefficient of every segment. Default 0.6.
    pub friction: f32,
    /// Restitution of every segment. Default 0.
    pub restitution: f32,
    /// Collision layers. Default: as [`BodyDef`]'s.
    pub filter: CollisionFilter,
    /// Game data for every segment.
    pub user_data: u64,
}

impl ChainDef {
    /// An open static chain through `points`.
    pub fn new(points: impl Into<Vec<Vec2>>) -> Self {
        let body = BodyDef::default();
        Self {
            points: points.into(),
            closed: false,
            kind: BodyKind::Static,
            friction: body.friction,
            restitution: body.restitution,
            filter: body.filter,
            user_data: 0,
        }
    }

    /// The same chain, closed (the last point joins the first).
    pub fn closed(self) -> Self {
        Self {
            closed: true,
            ..self
        }
    }

    /// The segments' bodies, in order: each at its segment's middle, with
    /// its neighbours' points.
    fn bodies(&self) -> Result<Vec<BodyDef>, PhysicsError> {
        let p = &self.points;
        let n = p.len();
        let least = if self.closed { 3 } else { 2 };
        if n < least || n > MAX_CHAIN_POINTS {
            return Err(PhysicsError::OutOfRange {
                what: "ChainDef::points",
                value: n as f32,
                allowed: "2 to 2^20 points (3 or more for a closed chain)",
            });
        }
        if self.kind == BodyKind::Dynamic {
            return Err(PhysicsError::OutOfRange {
                what: "ChainDef::kind",
                value: 0.0,
                allowed: "Static or Kinematic (a chain has no area, so no mass)",
            });
        }
        let segments = if self.closed { n } else { n - 1 };
        let at = |i: usize| p[i % n];
        let mut defs = Vec::with_capacity(segments);
        for i in 0..segments {
            let (a, b) = (at(i), at(i + 1));
            crate::error::position("ChainDef::points", a)?;
            crate::error::position("ChainDef::points", b)?;
            if a == b {
                return Err(PhysicsError::OutOfRange {
                    what: "ChainDef::points",
                    value: i as f32,
                    allowed: "no two points in a row the same (this is the index of the first)",
                });
            }
            let mid = 0.5 * (a + b);
            let before = (self.closed || i > 0).then(|| at(i + n - 1) - mid);
            let after = (self.closed || i + 2 < n).then(|| at(i + 2) - mid);
            defs.push(BodyDef {
                kind: self.kind,
                position: mid,
                shape: Some(Shape::ChainSegment {
                    half: 0.5 * (b - a),
                    before,
                    after,
                }),
                friction: self.friction,
                restitution: self.restitution,
                filter: self.filter,
                user_data: self.user_data,
                ..BodyDef::default()
            });
        }
        Ok(defs)
    }
}

impl World {
    /// Adds a chain: one body per segment, which meet smoothly (a body
    /// sliding along the chain never catches on a joint). Returns the
    /// segments' bodies in order.
    ///
    /// ```
    /// use passo_physics::{BodyDef, ChainDef, Shape, World, glam::Vec2};
    /// let mut world = World::default();
    /// // Flat, then a 30° slope up, then flat again: drawn left to right,
    /// // so solid below.
    /// let rise = 3.0 * 30f32.to_radians().tan();
    /// world.add_chain(&ChainDef::new([
    ///     Vec2::new(-10.0, 0.0), Vec2::new(0.0, 0.0), Vec2::new(3.0, rise), Vec2::new(10.0, rise),
    /// ])).unwrap();
    /// let ball = world.add_body(BodyDef::new_dynamic(Vec2::new(-5.0, 0.5), Shape::circle(0.25))).unwrap();
    /// for _ in 0..60 {
    ///     world.step(1.0 / 60.0);
    /// }
    /// // Resting on the flat part.
    /// assert!((world.body(ball).unwrap().position.y - 0.25).abs() < 0.01);
    /// ```
    ///
    /// # Errors
    /// Fewer than 2 points (3 closed) or more than [`MAX_CHAIN_POINTS`], a
    /// point that is not finite or lies beyond
    /// [`MAX_COORDINATE`](crate::constants::MAX_COORDINATE), two points
    /// in a row the same, a segment longer than
    /// [`MAX_SHAPE_SIZE`](crate::constants::MAX_SHAPE_SIZE), a dynamic
    /// kind, or a material the world refuses. Nothing is added then.
    pub fn add_chain(&mut self, chain: &ChainDef) -> Result<Vec<BodyId>, PhysicsError> {
        let defs = chain.bodies()?;
        for def in &defs {
            self.settings.check_body(def)?;
        }
        defs.into_iter().map(|def| self.add_body(def)).collect()
    }
}
