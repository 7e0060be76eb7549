//! Turning a physics world into a draw list.

use glam::Vec2;
use passo_physics::{BodyId, BodyKind, Shape, World};
use passo_render::{DrawList, Renderer, TextureId};
use passo_scene::{BuiltScene, LevelArt, SceneBody, TileSprite};
use std::path::Path;

/// How wide a segment (sloped ground) is drawn, pixels.
pub const SEGMENT_WIDTH_PX: f32 = 3.0;

/// Background of every picture (sRGB).
pub const BACKGROUND: [u8; 4] = [24, 26, 32, 255];
/// Velocity arrows (sRGB).
pub const VELOCITY_COLOUR: [u8; 4] = [120, 220, 140, 255];
/// Force arrows (sRGB).
pub const FORCE_COLOUR: [u8; 4] = [240, 200, 80, 255];
/// Contact normals (sRGB).
pub const CONTACT_COLOUR: [u8; 4] = [240, 90, 200, 255];
/// Bodies the scene gave no colour (sRGB).
pub const DEFAULT_COLOUR: [u8; 4] = [200, 200, 210, 255];
/// Joints: a line between their anchors (sRGB).
pub const JOINT_COLOUR: [u8; 4] = [236, 226, 196, 255];
/// How wide a joint is drawn, pixels.
pub const JOINT_WIDTH_PX: f32 = 2.0;

/// What to draw besides the bodies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawOptions {
    /// Interpolation factor between the last two ticks, in `[0, 1]`; only
    /// has an effect if the world keeps previous positions.
    pub alpha: f32,
    /// Draw each body's velocity as an arrow showing where it will be in
    /// `velocity_scale` seconds.
    pub velocity_vectors: bool,
    /// Seconds of travel a velocity arrow shows. Default 0.25.
    pub velocity_scale: f32,
    /// Draw the force of the force models on each body (metres per newton
    /// per kilogram: an arrow of `force_scale * F / m` metres).
    pub force_vectors: bool,
    /// Metres of arrow per m/s² of acceleration. Default 0.1.
    pub force_scale: f32,
    /// Draw contact normals at contact points.
    pub contact_normals: bool,
    /// Radius of a body without a shape, metres.
    pub point_radius: f32,
    /// Draw sleeping bodies at 55 % brightness.
    pub dim_sleeping: bool,
    /// Added to every position: draws several worlds side by side.
    pub offset: Vec2,
}

impl Default for DrawOptions {
    fn default() -> Self {
        Self {
            alpha: 1.0,
            velocity_vectors: false,
            velocity_scale: 0.25,
            force_vectors: false,
            force_scale: 0.1,
            contact_normals: false,
            point_radius: 0.1,
            dim_sleeping: false,
            offset: Vec2::ZERO,
        }
    }
}

/// A level's tiles as textured quads: the scene's [`LevelArt`] with its
/// images loaded into a renderer.
///
/// [`LevelArt`]: passo_scene::LevelArt
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelTiles {
    /// The quads, each with the texture of its image.
    tiles: Vec<(TextureId, TileSprite)>,
    /// The bodies the quads stand for, sorted: not drawn as boxes.
    hidden: Vec<BodyId>,
}

impl LevelTiles {
    /// Loads the images of `built`'s level (PNG files) into `renderer`.
    /// When every image loads and every solid cell has a tile, the cells
    /// are drawn as their tiles instead of flat boxes; otherwise (no
    /// images, or one that does not load, which is logged) the level is
    /// drawn as boxes, as without tiles.
    pub fn load(renderer: &mut Renderer, built: &BuiltScene) -> Self {
        Self::from_art(&built.art, &built.cell_bodies, |path| {
            let image = crate::load_image(path)?;
            renderer.add_texture(&image).map_err(|e| e.to_string())
        })
    }

    /// The quads of `art`, with each image's texture from `texture` (which
    /// loads it, or finds it loaded before); `cell_bodies` are the bodies
    /// the quads stand for. Empty, so the level is drawn as boxes, when
    /// `art` is not complete or an image does not load (logged).
    pub fn from_art(
        art: &LevelArt,
        cell_bodies: &[BodyId],
        mut texture: impl FnMut(&Path) -> Result<TextureId, String>,
    ) -> Self {
        if !art.complete || art.tiles.is_empty() {
            return Self::default();
        }
        let mut textures = Vec::with_capacity(art.images.len());
        for path in &art.images {
            match texture(path) {
                Ok(id) => textures.push(id),
                Err(e) => {
                    log::warn!("the level's tiles are drawn as boxes: {e}");
                    return Self::default();
                }
            }
        }
        let mut hidden = cell_bodies.to_vec();
        hidden.sort();
        Self {
            tiles: art.tiles.iter().map(|t| (textures[t.image], *t)).collect(),
            hidden,
        }
    }

    /// Adds the quads to `list`, moved by `offset`.
    pub fn add_to(&self, list: &mut DrawList, offset: Vec2) {
        for (texture, tile) in &self.tiles {
            list.sprite(
                *texture,
                tile.centre + offset,
                tile.half_extents,
                tile.uv_min,
                tile.uv_max,
            );
        }
    }

    /// The bodies the quads stand for, sorted.
    pub fn hidden(&self) -> &[BodyId] {
        &self.hidden
    }

    /// The number of quads.
    pub fn len(&self) -> usize {
        self.tiles.len()
    }

    /// No quads: the level is drawn as boxes.
    pub fn is_empty(&self) -> bool {
        self.tiles.is_empty()
    }
}

/// Adds each joint as a line between its anchors (at the bodies'
/// interpolated positions), with a dot at each.
pub fn add_joints(list: &mut DrawList, world: &World, options: &DrawOptions) {
    let at = |id: BodyId| {
        world
            .interpolated_position(id, options.alpha)
            .or_else(|| world.body(id).map(|b| b.position))
            .unwrap_or(Vec2::ZERO)
    };
    for (_, joint) in world.joints() {
        let def = joint.def;
        let a = at(def.a) + def.anchor_a + options.offset;
        let b = def.b.map_or(Vec2::ZERO, at) + def.anchor_b + options.offset;
        list.line(a, b, JOINT_WIDTH_PX, JOINT_COLOUR);
        for p in [a, b] {
            list.circle(p, 0.05, JOINT_COLOUR);
        }
    }
}

/// Clears `list` (keeping its capacity), then draws the world into it.
pub fn draw_world(list: &mut DrawList, world: &World, bodies: &[SceneBody], options: &DrawOptions) {
    draw_world_with_tiles(list, world, bodies, &LevelTiles::default(), options);
}

/// Clears `list`, then draws the level's tiles and the world over them;
/// the bodies the tiles stand for are not drawn again.
pub fn draw_world_with_tiles(
    list: &mut DrawList,
    world: &World,
    bodies: &[SceneBody],
    tiles: &LevelTiles,
    options: &DrawOptions,
) {
    list.clear(BACKGROUND);
    tiles.add_to(list, options.offset);
    add_world_hiding(list, world, bodies, &tiles.hidden, options);
}

/// Adds the world's bodies (with their scene colours) and the chosen debug
/// vectors to `list`.
pub fn add_world(list: &mut DrawList, world: &World, bodies: &[SceneBody], options: &DrawOptions) {
    add_world_hiding(list, world, bodies, &[], options);
}

/// [`add_world`], leaving out the bodies in `hidden` (sorted): those a
/// level's tiles stand for.
pub fn add_world_hiding(
    list: &mut DrawList,
    world: &World,
    bodies: &[SceneBody],
    hidden: &[BodyId],
    options: &DrawOptions,
) {
    let colour_of = |body: &passo_physics::Body| {
        let fallback = match body.kind {
            BodyKind::Kinematic => passo_scene::KINEMATIC_COLOUR.0,
            _ => DEFAULT_COLOUR,
        };
        bodies
            .binary_search_by_key(&body.id, |b: &SceneBody| b.id)
            .map_or(fallback, |i| bodies[i].colour.0)
    };
    // Static bodies first, so moving ones are drawn over them.
    for pass in [true, false] {
        for body in world.bodies() {
            if (body.mass == f32::INFINITY) != pass || hidden.binary_search(&body.id).is_ok() {
                continue;
            }
            let p = world
                .interpolated_position(body.id, options.alpha)
                .unwrap_or(body.position)
                + options.offset;
            let mut colour = colour_of(&body);
            if options.dim_sleeping && body.asleep {
                for c in &mut colour[..3] {
                    *c = (f32::from(*c) * 0.55).round() as u8;
                }
            }
            match body.shape {
                Some(Shape::Circle { radius }) => list.circle(p, radius, colour),
                Some(Shape::Box { half_extents }) => list.rect(p, half_extents, colour),
                Some(shape @ Shape::Capsule { .. }) => {
                    list.capsule(p, shape.half_extents(), colour)
                }
                Some(Shape::Segment { half } | Shape::ChainSegment { half, .. }) => {
                    list.line(p - half, p + half, SEGMENT_WIDTH_PX, colour)
                }
                // Its outline.
                Some(Shape::Polygon(polygon)) => {
                    let v = polygon.vertices();
                    for (i, a) in v.iter().enumerate() {
                        let b = v[(i + 1) % v.len()];
                        list.line(p + *a, p + b, SEGMENT_WIDTH_PX, colour);
                    }
                }
                None => list.circle(p, options.point_radius, colour),
            }
        }
    }
    add_joints(list, world, options);
    for body in world.bodies() {
        let p = world
            .interpolated_position(body.id, options.alpha)
            .unwrap_or(body.position)
            + options.offset;
        if options.velocity_vectors && body.velocity != Vec2::ZERO {
            list.arrow(
                p,
                p + body.velocity * options.velocity_scale,
                2.0,
                VELOCITY_COLOUR,
            );
        }
        if options.force_vectors
            && body.mass.is_finite()
            && let Some(force) = world.model_force(body.id)
            && force != Vec2::ZERO
        {
            list.arrow(
                p,
                p + force / body.mass * options.force_scale,
                2.0,
                FORCE_COLOUR,
            );
        }
    }
    if options.contact_normals {
        for contact in world.contacts().filter(|c| c.touching) {
            for &point in &contact.points[..usize::from(contact.point_count)] {
                let point = point + options.offset;
                list.arrow(point, point + contact.normal * 0.4, 1.5, CONTACT_COLOUR);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use passo_physics::{BodyDef, WorldSettings};

    #[test]
    fn sleeping_bodies_are_dimmed_only_when_asked() {
        let mut world = World::new(WorldSettings::default()).unwrap();
        world
            .add_body(BodyDef::new_static(
                Vec2::new(0.0, -0.5),
                Shape::rect(10.0, 1.0),
            ))
            .unwrap();
        let ball = world
            .add_body(BodyDef {
                position: Vec2::new(0.0, 0.5),
                shape: Some(Shape::circle(0.5)),
                ..Default::default()
            })
            .unwrap();
        for _ in 0..120 {
            world.step(1.0 / 60.0);
        }
        assert!(world.is_asleep(ball).unwrap());
        let fill = |dim_sleeping| {
            let mut list = DrawList::new(BACKGROUND);
            let options = DrawOptions {
                dim_sleeping,
                ..Default::default()
            };
            add_world(&mut list, &world, &[], &options);
            // Static bodies are drawn first: the ball is the second shape.
            (list.shapes[0].fill, list.shapes[1].fill)
        };
        let (ground, bright) = fill(false);
        let (ground_dimmed, dim) = fill(true);
        assert_eq!(ground, ground_dimmed, "static bodies never sleep");
        let expected =
            passo_render::srgb_to_linear((f32::from(DEFAULT_COLOUR[0]) * 0.55).round() as u8);
        assert_eq!(dim[0], expected);
        assert!(dim[0] < 0.5 * bright[0]);
    }
}
