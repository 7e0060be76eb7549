//! Components to bodies and back: bodies made and removed as entities
//! come and go, component changes applied before each tick, and
//! positions and velocities written back after it.

use bevy::ecs::change_detection::Tick;
use bevy::ecs::query::QueryData;
use bevy::ecs::system::SystemChangeTick;
use bevy::prelude::*;
use passo_physics as passo;

use crate::components::{
    BodyError, Bullet, Collider, Filter, GravityScale, KinematicTarget, LinearVelocity, Mass,
    Mover, OneWay, PassoBody, PhysicsMaterial, Position, PreviousPosition, RigidBody, Sensor,
    TransformInterpolation,
};
use crate::convert::{to_bevy, to_passo};
use crate::{BodyEntities, PassoWorld};

/// Everything an entity says about its body.
#[derive(QueryData)]
pub(crate) struct BodyParts {
    rigid_body: &'static RigidBody,
    collider: Option<&'static Collider>,
    mass: Option<&'static Mass>,
    material: Option<&'static PhysicsMaterial>,
    filter: Option<&'static Filter>,
    sensor: Has<Sensor>,
    one_way: Option<&'static OneWay>,
    gravity: Option<&'static GravityScale>,
    bullet: Has<Bullet>,
    velocity: Option<&'static LinearVelocity>,
    position: Option<&'static Position>,
    transform: &'static Transform,
}

impl BodyPartsItem<'_, '_> {
    /// Where the body is: its [`Position`], else its transform's x and y.
    fn start(&self) -> Vec2 {
        self.position
            .map_or(self.transform.translation.truncate(), |p| p.0)
    }

    fn def(&self) -> passo::BodyDef {
        let material = self.material.copied().unwrap_or_default();
        passo::BodyDef {
            kind: self.rigid_body.kind(),
            position: to_passo(self.start()),
            velocity: to_passo(self.velocity.map_or(Vec2::ZERO, |v| v.0)),
            mass: self.mass.copied().unwrap_or_default().0,
            shape: self.collider.map(|c| c.0),
            friction: material.friction,
            friction_mix: material.friction_mix,
            restitution: material.restitution,
            filter: self.filter.map(|f| f.0).unwrap_or_default(),
            sensor: self.sensor,
            one_way: self.one_way.map(|o| to_passo(o.0)),
            bullet: self.bullet,
            gravity_scale: self.gravity.copied().unwrap_or_default().0,
            ..Default::default()
        }
    }
}

/// Makes the body of an entity that just got a [`RigidBody`] (one that
/// already has a [`PassoBody`], such as a scene's, is left alone).
/// Observers run in the order the spawns were queued, so bodies get their
/// ids in that order.
pub(crate) fn on_add_rigid_body(
    add: On<Add, RigidBody>,
    mut world: ResMut<PassoWorld>,
    mut entities: ResMut<BodyEntities>,
    parts: Query<(BodyParts, Has<PassoBody>, Has<TransformInterpolation>)>,
    mut commands: Commands,
    ticks: SystemChangeTick,
) {
    let entity = add.entity;
    let Ok((parts, has_body, interpolated)) = parts.get(entity) else {
        return;
    };
    if has_body {
        return;
    }
    create(
        entity,
        &parts,
        ticks.this_run(),
        interpolated,
        &mut world,
        &mut entities,
        &mut commands,
    );
}

fn create(
    entity: Entity,
    parts: &BodyPartsItem<'_, '_>,
    made: Tick,
    interpolated: bool,
    world: &mut PassoWorld,
    entities: &mut BodyEntities,
    commands: &mut Commands,
) {
    let start = parts.start();
    match world.add_body(parts.def()) {
        Ok(id) => {
            entities.insert(id, entity);
            let mut e = commands.entity(entity);
            e.try_insert((PassoBody(id), Position(start)))
                .try_remove::<BodyError>();
            // A body placed by its Position is drawn there from the start.
            if parts.transform.translation.truncate() != start {
                let mut transform = *parts.transform;
                transform.translation.x = start.x;
                transform.translation.y = start.y;
                e.try_insert(transform);
            }
            if interpolated {
                e.try_insert(PreviousPosition(start));
            }
            e.try_insert(Made(made));
        }
        Err(error) => {
            warn!("entity {entity}: no Passo body: {error}");
            commands
                .entity(entity)
                .try_insert(BodyError(error))
                .try_remove::<(PassoBody, Made)>();
        }
    }
}

/// Removes the body of an entity that lost its [`RigidBody`] or was
/// despawned.
pub(crate) fn on_remove_rigid_body(
    remove: On<Remove, RigidBody>,
    mut world: ResMut<PassoWorld>,
    mut entities: ResMut<BodyEntities>,
    bodies: Query<&PassoBody>,
    mut commands: Commands,
) {
    let entity = remove.entity;
    if let Ok(&PassoBody(id)) = bodies.get(entity) {
        world.remove_body(id);
        entities.remove(id);
        commands
            .entity(entity)
            .try_remove::<(PassoBody, Made, BodyError)>();
    }
}

/// Asks for a rebuild of a body that lost its shape or mass: the body is
/// made again from what is left, before the next tick.
pub(crate) fn on_remove_part<T: Component>(remove: On<Remove, T>, mut commands: Commands) {
    commands.entity(remove.entity).try_insert(Rebuild);
}

impl PhysicsMaterial {
    /// Gives body `id` this material: every part the world accepts, and
    /// the first refusal.
    fn apply(
        &self,
        world: &mut passo::World,
        id: passo::BodyId,
    ) -> Result<(), passo::PhysicsError> {
        let mix = world.set_friction_mix(id, self.friction_mix);
        let friction = world.try_set_friction(id, self.friction);
        let restitution = world.set_restitution(id, self.restitution);
        mix.and(friction).and(restitution)
    }
}

/// A component whose removal puts a body's setting back to its default.
pub(crate) trait Setting: Component {
    /// Only dynamic bodies have this setting.
    const DYNAMIC_ONLY: bool = false;

    /// Puts the setting back to its default.
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError>;
}

impl Setting for Sensor {
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.set_sensor(id, false)
    }
}

impl Setting for OneWay {
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.set_one_way(id, None)
    }
}

impl Setting for Filter {
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.set_filter(id, passo::CollisionFilter::default())
    }
}

impl Setting for PhysicsMaterial {
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        PhysicsMaterial::default().apply(world, id)
    }
}

impl Setting for GravityScale {
    const DYNAMIC_ONLY: bool = true;

    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.set_gravity_scale(id, 1.0)
    }
}

impl Setting for Bullet {
    const DYNAMIC_ONLY: bool = true;

    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.set_bullet(id, false)
    }
}

impl Setting for KinematicTarget {
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.try_set_velocity(id, passo::glam::Vec2::ZERO)
    }
}

impl Setting for Mover {
    fn reset(world: &mut passo::World, id: passo::BodyId) -> Result<(), passo::PhysicsError> {
        world.try_set_velocity(id, passo::glam::Vec2::ZERO)
    }
}

/// Puts a body's setting back to its default when the entity loses the
/// component (the body keeps its id, contacts and joints). Dynamic-only
/// settings on other bodies have nothing to reset.
pub(crate) fn on_remove_setting<T: Setting>(
    remove: On<Remove, T>,
    mut world: ResMut<PassoWorld>,
    bodies: Query<&PassoBody>,
) {
    let Ok(&PassoBody(id)) = bodies.get(remove.entity) else {
        return;
    };
    let dynamic = world
        .body(id)
        .is_some_and(|b| b.kind == passo::BodyKind::Dynamic);
    if world.contains(id)
        && (dynamic || !T::DYNAMIC_ONLY)
        && let Err(error) = T::reset(&mut world, id)
    {
        warn!("body {id:?}: reset refused: {error}");
    }
}

/// A body to make again from its entity's components before the next
/// tick.
#[derive(Component)]
pub(crate) struct Rebuild;

/// When the plugin last made an entity's body from its components (the
/// change tick of the system that made it). A component written after
/// that is a change the body has not seen yet.
#[derive(Component, Clone, Copy, Debug)]
pub(crate) struct Made(pub(crate) Tick);

/// Whether the game changed `part` after the plugin made the body.
fn changed_since<T: Component>(part: &Ref<T>, made: Made, this_run: Tick) -> bool {
    part.is_changed() && part.last_changed().is_newer_than(made.0, this_run)
}

/// A component with a setter changed.
type SettingChanged = Or<(
    Changed<PhysicsMaterial>,
    Changed<Filter>,
    Changed<Sensor>,
    Changed<OneWay>,
    Changed<GravityScale>,
    Changed<Bullet>,
)>;

/// Any component a body is made from changed.
type AnyPartChanged = Or<(
    Changed<RigidBody>,
    Changed<Collider>,
    Changed<Mass>,
    SettingChanged,
    Changed<LinearVelocity>,
    Changed<Position>,
    Changed<Transform>,
)>;

/// Bodies whose kind, shape or mass changed, or that lost a component,
/// are made again; every other changed component is applied with the
/// world's setters. Runs in [`PassoSystems::Prepare`](crate::PassoSystems).
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub(crate) fn apply_changes(
    mut world: ResMut<PassoWorld>,
    mut entities: ResMut<BodyEntities>,
    mut commands: Commands,
    ticks: SystemChangeTick,
    rebuilds: Query<
        (
            Entity,
            Option<(&PassoBody, &Made)>,
            Ref<RigidBody>,
            Option<Ref<Collider>>,
            Option<Ref<Mass>>,
            Has<Rebuild>,
        ),
        Or<(
            Changed<RigidBody>,
            Changed<Collider>,
            Changed<Mass>,
            With<Rebuild>,
            With<BodyError>,
        )>,
    >,
    retry: Query<(), AnyPartChanged>,
    parts: Query<(BodyParts, Has<TransformInterpolation>)>,
    edits: Query<
        (
            Entity,
            &PassoBody,
            &Made,
            Option<Ref<PhysicsMaterial>>,
            Option<Ref<Filter>>,
            Option<Ref<Sensor>>,
            Option<Ref<OneWay>>,
            Option<Ref<GravityScale>>,
            Option<Ref<Bullet>>,
        ),
        SettingChanged,
    >,
    mut moved: Query<
        (
            Entity,
            &PassoBody,
            &Made,
            Ref<Position>,
            Ref<LinearVelocity>,
            Option<&mut PreviousPosition>,
        ),
        Or<(Changed<Position>, Changed<LinearVelocity>)>,
    >,
) {
    let now = ticks.this_run();
    // Rebuilds, in body id order (entities with no body yet last, in
    // entity order) so ids are handed out the same way every run.
    let mut again: Vec<(Option<passo::BodyId>, Entity)> = Vec::new();
    for (entity, body, kind, shape, mass, rebuild) in &rebuilds {
        let wanted = match body {
            // A body that could not be made is tried again when any of
            // its parts changes, or it lost one.
            None => rebuild || retry.contains(entity),
            Some((_, &made)) => {
                rebuild
                    || changed_since(&kind, made, now)
                    || shape.is_some_and(|s| changed_since(&s, made, now))
                    || mass.is_some_and(|m| changed_since(&m, made, now))
            }
        };
        if wanted {
            again.push((body.map(|b| b.0.0), entity));
        }
    }
    again.sort_unstable_by_key(|&(id, entity)| (id.is_none(), id, entity));
    let rebuilt: Vec<Entity> = again.iter().map(|&(_, entity)| entity).collect();
    for (id, entity) in again {
        let Ok((parts, interpolated)) = parts.get(entity) else {
            continue;
        };
        commands.entity(entity).try_remove::<Rebuild>();
        // Its Position and LinearVelocity hold where it is and how fast
        // it goes (written back every tick), so the new body starts there.
        if let Some(id) = id {
            world.remove_body(id);
            entities.remove(id);
        }
        create(
            entity,
            &parts,
            now,
            interpolated,
            &mut world,
            &mut entities,
            &mut commands,
        );
    }

    // Settings that have a setter, in body id order.
    let mut changed: Vec<_> = edits.iter().filter(|e| !rebuilt.contains(&e.0)).collect();
    changed.sort_unstable_by_key(|e| *e.1);
    for (_, &PassoBody(id), &made, material, filter, sensor, one_way, gravity, bullet) in changed {
        let mut results = Vec::new();
        if let Some(material) = material.filter(|m| changed_since(m, made, now)) {
            results.push(material.apply(&mut world, id));
        }
        if let Some(filter) = filter.filter(|f| changed_since(f, made, now)) {
            results.push(world.set_filter(id, filter.0));
        }
        if sensor.is_some_and(|s| changed_since(&s, made, now)) {
            results.push(world.set_sensor(id, true));
        }
        if let Some(one_way) = one_way.filter(|o| changed_since(o, made, now)) {
            results.push(world.set_one_way(id, Some(to_passo(one_way.0))));
        }
        if let Some(gravity) = gravity.filter(|g| changed_since(g, made, now)) {
            results.push(world.set_gravity_scale(id, gravity.0));
        }
        if bullet.is_some_and(|b| changed_since(&b, made, now)) {
            results.push(world.set_bullet(id, true));
        }
        for error in results.into_iter().filter_map(Result::err) {
            warn!("body {id:?}: change refused: {error}");
        }
    }

    // Teleports and new velocities, in body id order.
    let mut changed: Vec<_> = moved
        .iter_mut()
        .filter(|e| !rebuilt.contains(&e.0))
        .collect();
    changed.sort_unstable_by_key(|e| *e.1);
    for (_, &PassoBody(id), &made, position, velocity, previous) in changed {
        // The plugin's own writes of where the body is are no teleport.
        let body_now = world.body(id);
        let moved = body_now.is_some_and(|b| b.position != to_passo(position.0));
        let sped = body_now.is_some_and(|b| b.velocity != to_passo(velocity.0));
        if changed_since(&position, made, now) && moved {
            if let Err(error) = world.try_set_position(id, to_passo(position.0)) {
                warn!("body {id:?}: position refused: {error}");
            }
            // A teleport is drawn where it lands, not swept to.
            if let Some(mut previous) = previous {
                previous.0 = position.0;
            }
        }
        if changed_since(&velocity, made, now)
            && sped
            && let Err(error) = world.try_set_velocity(id, to_passo(velocity.0))
        {
            warn!("body {id:?}: velocity refused: {error}");
        }
    }
}

/// After each tick: every body's [`Position`] and [`LinearVelocity`],
/// its [`PreviousPosition`] (for [`TransformInterpolation`]), and the
/// [`Transform`] of bodies that are not interpolated. Written without
/// marking them changed, so only the game's own writes count as changes.
#[allow(clippy::type_complexity)]
pub(crate) fn write_back(
    world: Res<PassoWorld>,
    mut bodies: Query<(
        &PassoBody,
        &mut Position,
        &mut LinearVelocity,
        Option<&mut PreviousPosition>,
        &mut Transform,
        Has<TransformInterpolation>,
    )>,
) {
    for (&PassoBody(id), mut position, mut velocity, previous, mut transform, interpolated) in
        &mut bodies
    {
        let Some(body) = world.body(id) else {
            continue;
        };
        let now = to_bevy(body.position);
        if let Some(mut previous) = previous {
            previous.bypass_change_detection().0 = position.0;
        }
        position.bypass_change_detection().0 = now;
        velocity.bypass_change_detection().0 = to_bevy(body.velocity);
        if !interpolated && transform.translation.truncate() != now {
            transform.translation.x = now.x;
            transform.translation.y = now.y;
        }
    }
}

/// Every frame, before transforms propagate: interpolated bodies are
/// drawn between their last two ticks, at the fixed clock's overstep.
pub(crate) fn interpolate_transforms(
    time: Option<Res<Time<Fixed>>>,
    mut bodies: Query<(&Position, &PreviousPosition, &mut Transform), With<TransformInterpolation>>,
) {
    let alpha = time.map_or(1.0, |t| t.overstep_fraction().clamp(0.0, 1.0));
    for (position, previous, mut transform) in &mut bodies {
        let at = previous.0.lerp(position.0, alpha);
        transform.translation.x = at.x;
        transform.translation.y = at.y;
    }
}
