//! Box2D v3 (through `boxdd`, built from C source) given the same bodies as a
//! Passo world: rotation fixed, each body's friction, restitution, velocity
//! and density carried over, 4 substeps of 1/60 s.

use boxdd::{
    BodyBuilder, BodyType, Foundation, MotionLocks, Position, ShapeDef, SurfaceMaterial,
    Vec2 as BoxVec2, WorldBuilder, shapes,
};
use passo_physics::{BodyKind, Shape, World};

/// A Box2D world and which of its bodies is which Passo body.
pub struct Box2d {
    world: boxdd::World,
    bodies: Vec<(passo_physics::BodyId, boxdd::BodyId)>,
}

/// `BOX2D_RECYCLE_DISTANCE` (metres), if set: how far two bodies may
/// move relative to each other before Box2D computes their contact's
/// manifold again (its default is 10 × its linear slop, 5 cm; 0 turns
/// the reuse off).
pub fn recycle_distance() -> Option<f32> {
    let value = std::env::var("BOX2D_RECYCLE_DISTANCE").ok()?;
    match value.parse::<f32>() {
        Ok(d) if d >= 0.0 => Some(d),
        _ => {
            eprintln!(
                "BOX2D_RECYCLE_DISTANCE must be a distance in metres (0 or more), not {value:?}"
            );
            std::process::exit(2)
        }
    }
}

/// The same bodies as a Passo world, in Box2D.
pub fn copy(passo: &World, sleep: bool) -> Box2d {
    let foundation = Foundation::initialize_default().expect("Box2D starts");
    let def = WorldBuilder::from(foundation.world_def())
        .gravity(BoxVec2::new(0.0, -9.81))
        .enable_sleep(sleep)
        .build()
        .expect("a world definition");
    let mut world = foundation.create_world(def).expect("a world");
    if let Some(distance) = recycle_distance() {
        world
            .set_contact_recycle_distance(distance)
            .expect("a recycle distance");
    }
    let mut bodies = Vec::new();
    for b in passo.bodies() {
        let kind = match b.kind {
            BodyKind::Static => BodyType::Static,
            BodyKind::Kinematic => BodyType::Kinematic,
            BodyKind::Dynamic => BodyType::Dynamic,
        };
        let def = BodyBuilder::from(foundation.body_def())
            .body_type(kind)
            .position(Position::new(b.position.x, b.position.y))
            .linear_velocity(BoxVec2::new(b.velocity.x, b.velocity.y))
            .motion_locks(MotionLocks::new(false, false, true))
            .enable_sleep(sleep)
            .build()
            .expect("a body definition");
        let id = world.create_body(def).expect("a body");
        let density = crate::density_of(&b);
        let material = SurfaceMaterial::new()
            .with_friction(b.friction)
            .and_then(|m| m.with_restitution(b.restitution))
            .expect("a material");
        let filter = boxdd::filter::Filter {
            category_bits: u64::from(b.filter.layers),
            mask_bits: u64::from(b.filter.mask),
            ..Default::default()
        };
        let shape_def = ShapeDef::builder()
            .density(density)
            .material(material)
            .filter(filter)
            .build()
            .expect("a shape definition");
        let mut body = world.body(id).expect("the body");
        match b.shape.expect("benchmark bodies have shapes") {
            Shape::Circle { radius } => {
                let circle = shapes::circle([0.0, 0.0], radius).expect("a circle");
                body.create_circle(&shape_def, &circle)
                    .expect("a circle shape");
            }
            Shape::Box { half_extents } => {
                let polygon = shapes::box_polygon(half_extents.x, half_extents.y).expect("a box");
                body.create_polygon(&shape_def, &polygon)
                    .expect("a box shape");
            }
            Shape::Capsule {
                half_segment,
                radius,
            } => {
                let (a, b) = (-half_segment, half_segment);
                let capsule = shapes::capsule([a.x, a.y], [b.x, b.y], radius).expect("a capsule");
                body.create_capsule(&shape_def, &capsule)
                    .expect("a capsule shape");
            }
            Shape::Segment { half } => {
                let segment =
                    shapes::segment([-half.x, -half.y], [half.x, half.y]).expect("a segment");
                body.create_segment(&shape_def, &segment)
                    .expect("a segment shape");
            }
            Shape::ChainSegment {
                half,
                before,
                after,
            } => {
                let (a, b) = (-half, half);
                // A free end's ghost continues the segment.
                let before = before.unwrap_or(a - 2.0 * half);
                let after = after.unwrap_or(b + 2.0 * half);
                // Box2D's chain segments are solid on the left of their
                // direction, Passo's on the right: the same one reversed.
                let p = |v: passo_physics::glam::Vec2| [v.x, v.y];
                let segment = shapes::chain_segment(p(after), p(b), p(a), p(before))
                    .expect("a chain segment");
                body.create_chain_segment(&shape_def, &segment)
                    .expect("a chain segment shape");
            }
            Shape::Polygon(polygon) => {
                let points = polygon.vertices().iter().map(|v| [v.x, v.y]);
                body.create_polygon_from_points(&shape_def, points, 0.0)
                    .expect("a polygon shape");
            }
        }
        bodies.push((b.id, id));
    }
    // Rigid distance joints (rods), as Box2D distance joints between the
    // same anchors, the bodies not colliding with each other.
    let box_id = |id| bodies.iter().find(|(p, _)| *p == id).map(|(_, b)| *b);
    for (_, joint) in passo.joints() {
        let def = joint.def;
        let passo_physics::JointKind::Distance {
            length,
            min_length,
            max_length,
            spring: None,
        } = def.kind
        else {
            panic!("only rods are carried over to Box2D, not {:?}", def.kind);
        };
        assert_eq!(
            min_length, max_length,
            "only rods are carried over to Box2D"
        );
        let (a, b) = (box_id(def.a), def.b.and_then(box_id));
        let (a, b) = (a.expect("body a"), b.expect("body b"));
        let (pa, pb) = joint.anchors;
        world
            .distance(a, b)
            .anchors_world([pa.x, pa.y], [pb.x, pb.y])
            .length(length)
            .build()
            .expect("a distance joint");
    }
    Box2d { world, bodies }
}

impl Box2d {
    /// One step of 1/60 s in 4 substeps.
    pub fn step(&mut self) {
        let _ = self.world.step(1.0 / 60.0, 4).expect("a step");
    }

    /// A copy of `passo` with each body where Box2D has it, moving as fast:
    /// Passo's exact geometry and energy then measure Box2D's state.
    pub fn state(&mut self, passo: &World) -> World {
        let mut copy = passo.clone();
        for &(id, body) in &self.bodies {
            if passo.body(id).is_none_or(|b| b.kind == BodyKind::Static) {
                continue;
            }
            let body = self.world.body(body).expect("the body");
            let p = body.position().expect("its position");
            let v = body.linear_velocity().expect("its velocity");
            copy.set_position(id, passo_physics::glam::Vec2::new(p.x, p.y));
            copy.set_velocity(id, passo_physics::glam::Vec2::new(v.x, v.y));
        }
        copy
    }

    /// Max penetration of the final state, by Passo's exact geometry.
    pub fn penetration(&mut self, passo: &World) -> f32 {
        self.state(passo).max_penetration()
    }
}
