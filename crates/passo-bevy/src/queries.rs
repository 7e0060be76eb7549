//! Queries and casts against the physics world, as a system parameter
//! that answers with entities.

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use passo_physics as passo;

use crate::convert::{to_bevy, to_passo};
use crate::{BodyEntities, PassoWorld};

pub use passo::QueryFilter;

/// A ray's hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// The body hit.
    pub body: passo::BodyId,
    /// Its entity (`None` for a level's tile).
    pub entity: Option<Entity>,
    /// How far along the ray, metres.
    pub distance: f32,
    /// Where, metres.
    pub point: Vec2,
    /// The body's outward normal there.
    pub normal: Vec2,
}

/// A shape cast's first hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeHit {
    /// The body met.
    pub body: passo::BodyId,
    /// Its entity (`None` for a level's tile).
    pub entity: Option<Entity>,
    /// How much of the translation the shape moves before it touches,
    /// in `[0, 1]`.
    pub fraction: f32,
    /// Where they touch, metres.
    pub point: Vec2,
    /// The body's normal there.
    pub normal: Vec2,
}

/// Read-only questions to the world, answered with entities:
///
/// ```
/// use bevy::prelude::*;
/// use passo_bevy::prelude::*;
///
/// fn look_down(physics: SpatialQuery, players: Query<(Entity, &Position), With<Mover>>) {
///     for (player, at) in &players {
///         let below = QueryFilter::solid().excluding(physics.body(player).unwrap());
///         if let Some(hit) = physics.ray_cast(at.0, Vec2::NEG_Y, 10.0, &below) {
///             info!("ground {} m below", hit.distance);
///         }
///     }
/// }
/// # let mut app = App::new();
/// # app.add_systems(Update, look_down);
/// ```
#[derive(SystemParam)]
pub struct SpatialQuery<'w> {
    world: Res<'w, PassoWorld>,
    entities: Res<'w, BodyEntities>,
}

impl SpatialQuery<'_> {
    /// The physics world itself, for everything else it answers.
    pub fn world(&self) -> &passo::World {
        &self.world.0
    }

    /// The entity of a body (`None` for a level's tile, or a body gone).
    pub fn entity(&self, body: passo::BodyId) -> Option<Entity> {
        self.entities.entity(body)
    }

    /// The body of an entity (`None` if it has none).
    pub fn body(&self, entity: Entity) -> Option<passo::BodyId> {
        self.entities.body(entity)
    }

    /// The first body a ray from `origin` along `direction` meets within
    /// `max_distance` metres. `None` for a zero or non-finite direction,
    /// or an origin outside the world's limits.
    pub fn ray_cast(
        &self,
        origin: Vec2,
        direction: Vec2,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Option<RayHit> {
        let hit = self.world.ray_cast_with(
            to_passo(origin),
            to_passo(direction),
            max_distance,
            filter,
        )?;
        Some(RayHit {
            body: hit.body,
            entity: self.entity(hit.body),
            distance: hit.distance,
            point: to_bevy(hit.point),
            normal: to_bevy(hit.normal),
        })
    }

    /// The first body `shape`, moved from `start` by `translation`, meets.
    pub fn cast_shape(
        &self,
        shape: &crate::Collider,
        start: Vec2,
        translation: Vec2,
        filter: &QueryFilter,
    ) -> Option<ShapeHit> {
        let hit =
            self.world
                .cast_shape(&shape.0, to_passo(start), to_passo(translation), filter)?;
        Some(ShapeHit {
            body: hit.body,
            entity: self.entity(hit.body),
            fraction: hit.fraction,
            point: to_bevy(hit.point),
            normal: to_bevy(hit.normal),
        })
    }

    /// The entities whose shapes hold `point`, in body id order (tiles,
    /// which have no entity, are left out).
    pub fn point(&self, point: Vec2, filter: &QueryFilter) -> Vec<Entity> {
        let bodies = self.world.query_point_with(to_passo(point), filter);
        bodies.into_iter().filter_map(|b| self.entity(b)).collect()
    }

    /// The entities whose bounding boxes overlap the box from `min` to
    /// `max`, in body id order (tiles left out).
    pub fn aabb(&self, min: Vec2, max: Vec2, filter: &QueryFilter) -> Vec<Entity> {
        let aabb = passo::Aabb {
            min: to_passo(min),
            max: to_passo(max),
        };
        let bodies = self.world.query_aabb_with(aabb, filter);
        bodies.into_iter().filter_map(|b| self.entity(b)).collect()
    }

    /// Whether `entity` stands on something: a contact whose normal is
    /// within `max_slope` radians of straight up.
    pub fn is_standing(&self, entity: Entity, max_slope: f32) -> bool {
        self.body(entity)
            .is_some_and(|b| self.world.is_standing(b, max_slope))
    }
}
