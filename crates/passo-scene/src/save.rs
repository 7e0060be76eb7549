//! Saving a running world as a scene file.

use crate::build::SceneBody;
use crate::format::{BodySpec, Camera, Forces, Material, SceneFile};
use passo_physics::{BodyKind, CollisionFilter, World};

/// The scene that recreates `world` in its current state: settings, and
/// every body listed one by one (in id order) with its current position and
/// velocity. Names and colours come from `bodies`; name, description, rate
/// and camera from `base`. Custom force models and contact warm-start data
/// are not part of a scene.
pub fn scene_from_world(world: &World, base: &SceneFile, bodies: &[SceneBody]) -> SceneFile {
    let s = world.settings();
    let f = &s.forces;
    let specs = world
        .bodies()
        .map(|b| {
            let record = bodies
                .binary_search_by_key(&b.id, |r| r.id)
                .ok()
                .map(|i| &bodies[i]);
            BodySpec {
                name: record.and_then(|r| r.name.clone()),
                kind: b.kind,
                shape: b.shape,
                mass: (b.kind == BodyKind::Dynamic).then_some(b.mass),
                density: None,
                position: b.position,
                velocity: b.velocity,
                material: Material {
                    restitution: b.restitution,
                    friction: b.friction,
                    friction_mix: b.friction_mix,
                    drag_area: b.drag_area,
                },
                colour: record.map(|r| r.colour),
                sensor: b.sensor,
                one_way: b.one_way,
                bullet: b.bullet,
                path: None,
                filter: (b.filter != CollisionFilter::default()).then_some(b.filter),
                min_speed: b.min_speed,
                max_speed: b.max_speed,
            }
        })
        .collect();
    SceneFile {
        name: base.name.clone(),
        description: base.description.clone(),
        rate_hz: base.rate_hz,
        integrator: s.integrator,
        force_form: s.force_form,
        forces: Forces {
            gravity: f.gravity,
            quadratic_drag: f.quadratic_drag,
            linear_drag: f.linear_drag,
            wind: f.air_velocity,
            surface_friction: f.surface_friction,
            force_field: f.force_field,
            spring: f.spring,
            central_gravity: f.central_gravity,
        },
        collisions: s.contacts,
        min_speed: s.min_speed,
        max_speed: s.max_speed,
        interpolation: s.interpolation,
        camera: base.camera.map(|c| Camera {
            min: c.min,
            max: c.max,
        }),
        bodies: specs,
        // The map's cells are among the bodies, one box per merged run.
        tilemap: None,
        generators: Vec::new(),
        // Chain segments are among the bodies, one by one.
        chains: Vec::new(),
    }
}
