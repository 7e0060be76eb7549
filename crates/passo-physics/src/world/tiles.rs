//! Tile maps as bodies: a map's merged rectangles added as static or
//! kinematic boxes.

use crate::{BodyDef, BodyId, BodyKind, PhysicsError, World};

impl World {
    /// Adds the solid cells of `map` as boxes of `kind` (static, or
    /// kinematic for a level part that moves: give every returned body the
    /// same velocity), merged into as few boxes as the map allows (see
    /// [`TileMap::rects`](crate::TileMap::rects)). Each box takes its
    /// kind's friction, restitution and one-way side. Returns the bodies in
    /// the order of the rectangles.
    ///
    /// ```
    /// use passo_physics::{BodyDef, BodyKind, Shape, TileMap, World, glam::Vec2};
    /// let mut world = World::default();
    /// let map = TileMap::from_ascii("
    ///     #........#
    ///     ##########", Vec2::ONE, Vec2::new(-5.0, 0.0)).unwrap();
    /// world.add_tile_map(&map, BodyKind::Static).unwrap();
    /// let ball = world.add_body(BodyDef::new_dynamic(Vec2::new(0.0, 3.0), Shape::circle(0.25))).unwrap();
    /// for _ in 0..120 {
    ///     world.step(1.0 / 60.0);
    /// }
    /// // Resting on the floor, whose top is at y = 1.
    /// assert!((world.body(ball).unwrap().position.y - 1.25).abs() < 0.01);
    /// ```
    ///
    /// # Errors
    /// A dynamic `kind` (a map is level geometry), or a box the world
    /// refuses; the boxes added before it stay.
    pub fn add_tile_map(
        &mut self,
        map: &crate::TileMap,
        kind: BodyKind,
    ) -> Result<Vec<BodyId>, PhysicsError> {
        let mut ids = self.add_tile_rects(map, &map.rects(), kind)?;
        ids.extend(self.add_tile_chains(map, &map.chains(), kind)?);
        Ok(ids)
    }

    /// Adds a map's chains ([`TileMap::chains`](crate::TileMap::chains):
    /// its slopes and the ground they touch) as closed chains of `kind`,
    /// each with its kind's friction and restitution. Returns their
    /// segments' bodies, chain after chain.
    ///
    /// # Errors
    /// As [`add_tile_map`](Self::add_tile_map).
    pub fn add_tile_chains(
        &mut self,
        map: &crate::TileMap,
        chains: &[crate::TileChain],
        kind: BodyKind,
    ) -> Result<Vec<BodyId>, PhysicsError> {
        level_kind(kind)?;
        let mut ids = Vec::new();
        for chain in chains {
            let tile = map.kinds()[usize::from(chain.kind)];
            let def = crate::ChainDef {
                closed: true,
                kind,
                friction: tile.friction,
                restitution: tile.restitution,
                ..crate::ChainDef::new(chain.points.clone())
            };
            ids.extend(self.add_chain(&def)?);
        }
        Ok(ids)
    }

    /// [`add_tile_map`](Self::add_tile_map) with the map's rectangles
    /// already merged ([`TileMap::rects`](crate::TileMap::rects)), for a
    /// caller that counts them first (a map can merge into millions).
    ///
    /// # Errors
    /// As [`add_tile_map`](Self::add_tile_map).
    pub fn add_tile_rects(
        &mut self,
        map: &crate::TileMap,
        rects: &[crate::TileRect],
        kind: BodyKind,
    ) -> Result<Vec<BodyId>, PhysicsError> {
        level_kind(kind)?;
        let mut ids = Vec::with_capacity(rects.len());
        for rect in rects {
            let aabb = map.rect_aabb(rect);
            let tile = map.kinds()[rect.kind as usize];
            let def = BodyDef {
                kind,
                position: aabb.centre(),
                shape: Some(crate::Shape::Box {
                    half_extents: aabb.size() * 0.5,
                }),
                friction: tile.friction,
                restitution: tile.restitution,
                one_way: tile.one_way,
                ..BodyDef::default()
            };
            ids.push(self.add_body(def)?);
        }
        Ok(ids)
    }
}

/// A tile map's kind of body: static or kinematic.
fn level_kind(kind: BodyKind) -> Result<(), PhysicsError> {
    if kind == BodyKind::Dynamic {
        return Err(PhysicsError::InvalidTileMap(
            "a tile map is Static or Kinematic, not Dynamic".into(),
        ));
    }
    Ok(())
}
