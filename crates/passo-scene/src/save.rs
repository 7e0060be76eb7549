//! Saving a running world as a scene file.

use crate::build::SceneBody;
use crate::format::{BodySpec, Camera, Forces, JointSpec, JointSpecKind, Material, SceneFile};
use passo_physics::{BodyKind, CollisionFilter, JointKind, World};

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
                conveyor: b.conveyor,
                bullet: b.bullet,
                path: None,
                filter: (b.filter != CollisionFilter::default()).then_some(b.filter),
                min_speed: b.min_speed,
                max_speed: b.max_speed,
                gravity_scale: (b.gravity_scale != 1.0).then_some(b.gravity_scale),
                zone: world.force_zone(b.id),
            }
        })
        .collect::<Vec<_>>();
    let (specs, joints) = joint_specs(world, specs);
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
        joints,
    }
}

/// The world's joints as scene joints, and `specs` (one a body, in id
/// order) with a name given to each joined body that had none
/// (`body<index>`). Target joints (a mouse's drag) are not saved; a weld
/// holds its bodies as they are when the scene loads.
fn joint_specs(world: &World, mut specs: Vec<BodySpec>) -> (Vec<BodySpec>, Vec<JointSpec>) {
    let ids: Vec<_> = world.bodies().map(|b| b.id).collect();
    let name_of = |id: passo_physics::BodyId, specs: &mut Vec<BodySpec>| {
        let i = ids.binary_search(&id).expect("a live body");
        specs[i]
            .name
            .get_or_insert_with(|| format!("body{}", id.index()))
            .clone()
    };
    let mut joints = Vec::new();
    for (_, joint) in world.joints() {
        let def = joint.def;
        let kind = match def.kind {
            JointKind::Distance {
                length,
                min_length,
                max_length,
                spring,
            } => match spring {
                Some(s) => JointSpecKind::Spring {
                    length: Some(length),
                    hertz: s.hertz,
                    damping_ratio: s.damping_ratio,
                    limits: (min_length > 0.0 || max_length.is_finite())
                        .then_some((min_length, max_length)),
                },
                None if min_length == max_length => JointSpecKind::Rod {
                    length: Some(length),
                },
                None if min_length == 0.0 => JointSpecKind::Rope {
                    length: Some(max_length),
                },
                None => JointSpecKind::Spring {
                    length: Some(length),
                    hertz: 0.0,
                    damping_ratio: 0.0,
                    limits: Some((min_length, max_length)),
                },
            },
            JointKind::Prismatic {
                axis,
                limits,
                motor,
            } => JointSpecKind::Slider {
                axis,
                limits,
                motor,
            },
            JointKind::Weld { spring } => JointSpecKind::Weld {
                hertz: spring.map_or(0.0, |s| s.hertz),
                damping_ratio: spring.map_or(0.0, |s| s.damping_ratio),
            },
            JointKind::Target { .. } => continue,
        };
        let weld = matches!(kind, JointSpecKind::Weld { .. });
        joints.push(JointSpec {
            a: name_of(def.a, &mut specs),
            b: def.b.map(|b| name_of(b, &mut specs)),
            anchor_a: if weld {
                Default::default()
            } else {
                def.anchor_a
            },
            anchor_b: if weld {
                Default::default()
            } else {
                def.anchor_b
            },
            kind,
            break_force: def.break_force,
            collide: def.collide,
        });
    }
    (specs, joints)
}
