//! Lanes: the worlds a demo scene runs, each drawn at its own offset. A
//! scene file makes one lane; the integrator comparison makes one lane per
//! integrator, the same spring in each.

use super::controls::Knobs;
use glam::Vec2;
use passo_physics::{
    BodyDef, BodyId, BodyKind, ForceModels, Integrator, PhysicsError, Shape, Spring, World,
    WorldSettings,
};
use passo_scene::{Colour, SceneBody};

/// One world of the demo, drawn at `offset`.
#[derive(Debug)]
pub struct Lane {
    /// Shown under the lane when there are several.
    pub label: String,
    /// The world.
    pub world: World,
    /// Names and colours, sorted by id.
    pub bodies: Vec<SceneBody>,
    /// Where the lane is drawn, metres.
    pub offset: Vec2,
    /// Each dynamic body's drag area as the scene gave it, for the drag-area
    /// slider (a multiplier).
    base_drag: Vec<(BodyId, f32)>,
}

/// The colour a spawned body gets, by count.
const SPAWN_COLOURS: [[u8; 4]; 4] = [
    [0xf0, 0xc8, 0x50, 0xff],
    [0xf0, 0x78, 0x78, 0xff],
    [0x78, 0xd0, 0xf0, 0xff],
    [0xb0, 0xf0, 0x78, 0xff],
];

impl Lane {
    /// A lane of `world`, whose dynamic bodies' drag areas are the base of
    /// the drag-area slider.
    pub(crate) fn new(label: String, world: World, bodies: Vec<SceneBody>, offset: Vec2) -> Self {
        let base_drag = world
            .bodies()
            .filter(|b| b.kind == BodyKind::Dynamic)
            .map(|b| (b.id, b.drag_area))
            .collect();
        Self {
            label,
            world,
            bodies,
            offset,
            base_drag,
        }
    }

    /// A body's drag area as the scene gave it (dynamic bodies only).
    /// Forgets the bodies the world no longer has (spawned after the
    /// state a rewind went back to).
    pub(crate) fn forget_removed(&mut self) {
        let world = &self.world;
        self.bodies.retain(|b| world.contains(b.id));
        self.base_drag.retain(|&(id, _)| world.contains(id));
    }

    /// The drag-area multiplier the world's bodies show: a body's area
    /// against the scene's (not `skip`'s, whose area the glide changes).
    pub(crate) fn drag_scale_in_world(&self, skip: Option<BodyId>) -> Option<f32> {
        self.base_drag
            .iter()
            .filter(|&&(id, base)| Some(id) != skip && base > 0.0)
            .find_map(|&(id, base)| Some(self.world.body(id)?.drag_area / base))
    }

    pub(crate) fn base_drag(&self, id: BodyId) -> Option<f32> {
        self.base_drag
            .iter()
            .find(|(b, _)| *b == id)
            .map(|&(_, area)| area)
    }

    /// Sets the sliders' force models, limits and contact switches.
    pub(crate) fn apply_knobs(&mut self, knobs: &Knobs) {
        let s = knobs.applied_to(*self.world.settings());
        if let Err(e) = self.world.set_settings(s) {
            log::warn!("slider value refused: {e}");
        }
    }

    /// Calls `f` on every dynamic body, logging what it refuses.
    pub(crate) fn for_each_dynamic(
        &mut self,
        mut f: impl FnMut(&mut World, BodyId) -> Result<(), PhysicsError>,
    ) {
        let ids: Vec<BodyId> = self
            .world
            .bodies()
            .filter(|b| b.kind == BodyKind::Dynamic)
            .map(|b| b.id)
            .collect();
        for id in ids {
            if let Err(e) = f(&mut self.world, id) {
                log::warn!("slider value refused: {e}");
            }
        }
    }

    /// Sets every dynamic body's drag area to its scene value times `scale`.
    pub(crate) fn scale_drag(&mut self, scale: f32) {
        for &(id, base) in &self.base_drag {
            let _ = self.world.set_drag_area(id, base * scale);
        }
    }

    /// Changes the world's settings, keeping the rest.
    pub(crate) fn update_settings(&mut self, change: impl FnOnce(&mut WorldSettings)) {
        let mut s = *self.world.settings();
        change(&mut s);
        let _ = self.world.set_settings(s);
    }

    /// Adds a body at a world point: a circle or a box of 0.6 m with the
    /// sliders' friction and restitution, coloured by count.
    pub(crate) fn spawn(&mut self, at: Vec2, round: bool, knobs: &Knobs) -> Option<BodyId> {
        let shape = if round {
            Shape::circle(0.3)
        } else {
            Shape::rect(0.6, 0.6)
        };
        let def = BodyDef {
            position: at - self.offset,
            shape: Some(shape),
            mass: shape.area() * 2.0,
            friction: knobs.friction,
            restitution: knobs.restitution,
            ..Default::default()
        };
        let id = self.world.add_body(def).ok()?;
        let colour = Colour(SPAWN_COLOURS[self.bodies.len() % SPAWN_COLOURS.len()]);
        let at = self.bodies.partition_point(|b| b.id < id);
        self.bodies.insert(
            at,
            SceneBody {
                id,
                name: None,
                colour,
            },
        );
        self.base_drag.push((id, def.drag_area));
        Some(id)
    }
}

/// The bob's colour in each integrator's lane, in [`Integrator::ALL`] order.
const INTEGRATOR_COLOURS: [[u8; 4]; 4] = [
    [0xe4, 0x6c, 0x3a, 0xff],
    [0x5c, 0xb8, 0x5c, 0xff],
    [0x3a, 0x8e, 0xe4, 0xff],
    [0xa3, 0x5c, 0xd6, 0xff],
];

/// The same spring under each integrator, side by side, 3 m apart: a 1 kg
/// body on a spring of period 1 s, started 1.5 m from rest.
pub(crate) fn integrator_lanes() -> Vec<Lane> {
    Integrator::ALL
        .iter()
        .zip(INTEGRATOR_COLOURS)
        .enumerate()
        .map(|(i, (&integrator, colour))| {
            let mut world = World::new(WorldSettings {
                forces: ForceModels {
                    gravity: None,
                    spring: Some(Spring {
                        anchor: Vec2::ZERO,
                        stiffness: (2.0 * std::f32::consts::PI).powi(2),
                    }),
                    ..ForceModels::none()
                },
                integrator,
                min_speed: 0.0,
                interpolation: true,
                // The bob swings through its anchor: nothing collides.
                contacts: None,
                ..Default::default()
            })
            .expect("valid settings");
            let anchor = world
                .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(0.08)))
                .expect("valid anchor");
            let bob = world
                .add_body(BodyDef {
                    position: Vec2::new(0.0, 1.5),
                    shape: Some(Shape::circle(0.2)),
                    ..Default::default()
                })
                .expect("valid body");
            let bodies = vec![
                SceneBody {
                    id: anchor,
                    name: Some("anchor".into()),
                    colour: Colour([0x9a, 0x9e, 0xa8, 0xff]),
                },
                SceneBody {
                    id: bob,
                    name: Some(integrator.name().into()),
                    colour: Colour(colour),
                },
            ];
            Lane::new(
                integrator.name().to_owned(),
                world,
                bodies,
                Vec2::new(i as f32 * 3.0 - 4.5, 0.0),
            )
        })
        .collect()
}
