//! What game code changes on a body between steps: position, velocity,
//! forces and impulses, material. Every value is checked where it enters,
//! and a change wakes what it may have disturbed.

use crate::body::census::BodyCensus;
use crate::body::def::{check_drag_area, check_friction, check_one_way};
use crate::error::{finite, finite_vec, non_negative, positive, unit_interval};
use crate::world::{Location, World};
use crate::{BodyId, CollisionFilter, FrictionMix, PhysicsError};
use glam::Vec2;

impl World {
    // ----- per-tick calls: they cannot fail -----
    //
    // Game code calls these every tick with values it computed. A stale id
    // or a value the `try_` form refuses (NaN, infinity, out of range) does
    // nothing to the world, which never stores a NaN, and is counted in
    // `StepStats::rejected_inputs`; the `try_` forms say why.

    /// Moves a body (see [`try_set_position`](Self::try_set_position)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn set_position(&mut self, id: BodyId, position: Vec2) {
        let result = self.try_set_position(id, position);
        self.count_rejected(result);
    }

    /// Sets a body's velocity (see [`try_set_velocity`](Self::try_set_velocity)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn set_velocity(&mut self, id: BodyId, velocity: Vec2) {
        let result = self.try_set_velocity(id, velocity);
        self.count_rejected(result);
    }

    /// Steers a kinematic body to `target` by the next step (see [`try_set_kinematic_target`](Self::try_set_kinematic_target)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn set_kinematic_target(&mut self, id: BodyId, target: Vec2, dt: f32) {
        let result = self.try_set_kinematic_target(id, target, dt);
        self.count_rejected(result);
    }

    /// Adds a force for the next step (see [`try_apply_force`](Self::try_apply_force)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn apply_force(&mut self, id: BodyId, force: Vec2) {
        let result = self.try_apply_force(id, force);
        self.count_rejected(result);
    }

    /// Applies an impulse now (see [`try_apply_impulse`](Self::try_apply_impulse)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn apply_impulse(&mut self, id: BodyId, impulse: Vec2) {
        let result = self.try_apply_impulse(id, impulse);
        self.count_rejected(result);
    }

    /// Applies kinetic friction for the next step (see [`try_apply_friction`](Self::try_apply_friction)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn apply_friction(&mut self, id: BodyId, mu: f32, normal: f32) {
        let result = self.try_apply_friction(id, mu, normal);
        self.count_rejected(result);
    }

    /// Sets a body's friction coefficient (see [`try_set_friction`](Self::try_set_friction)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn set_friction(&mut self, id: BodyId, mu: f32) {
        let result = self.try_set_friction(id, mu);
        self.count_rejected(result);
    }

    /// Lets a body pass one-way platforms for a while (see [`try_drop_through`](Self::try_drop_through)). A stale id or a refused value changes nothing and counts
    /// in [`StepStats::rejected_inputs`](crate::StepStats::rejected_inputs).
    pub fn drop_through(&mut self, id: BodyId, seconds: f32) {
        let result = self.try_drop_through(id, seconds);
        self.count_rejected(result);
    }

    fn count_rejected(&mut self, result: Result<(), PhysicsError>) {
        if result.is_err() {
            self.stats.rejected_inputs = self.stats.rejected_inputs.saturating_add(1);
        }
    }

    /// Moves a body (a teleport: no velocity is implied, and an interpolated
    /// drawing jumps too). A static body moved this way carries no rider
    /// and is not interpolated: move platforms as
    /// [`BodyKind::Kinematic`](crate::BodyKind::Kinematic) bodies, with
    /// [`set_velocity`](Self::set_velocity) or
    /// [`set_kinematic_target`](Self::set_kinematic_target).
    ///
    /// # Errors
    /// A stale id, or a position that is not finite or lies beyond
    /// [`MAX_COORDINATE`](crate::constants::MAX_COORDINATE).
    pub fn try_set_position(&mut self, id: BodyId, position: Vec2) -> Result<(), PhysicsError> {
        crate::error::position("position", position)?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        match location {
            Location::Dynamic(i) => {
                // Its contacts are kept for now: moved less than the reuse
                // distance, it moves as if it had travelled there.
                let i = i as usize;
                self.dynamic.pos.set(i, position);
                if i < self.dynamic.prev_pos.len() {
                    self.dynamic.prev_pos.set(i, position);
                }
            }
            Location::Static(i) => {
                self.statics.pos[i as usize] = position;
                self.statics_dirty = true;
                // What it covers of its neighbours changed.
                self.contacts_changed(id, location);
            }
        }
        self.note_edit(matches!(location, Location::Static(_)));
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets a body's velocity, metres per second: a dynamic body's current
    /// velocity, or the velocity a kinematic body moves at until it is set
    /// again. Ignored for static bodies.
    ///
    /// # Errors
    /// A stale id, a velocity that is not finite (or whose square
    /// overflows), or a kinematic body's speed above the world's
    /// [`max_speed`](crate::WorldSettings::max_speed).
    pub fn try_set_velocity(&mut self, id: BodyId, velocity: Vec2) -> Result<(), PhysicsError> {
        finite_vec("velocity", velocity)?;
        if let Some(i) = self.dynamic_index(id)? {
            self.check_velocity(i, velocity, "velocity")?;
            self.dynamic.vel.set(i, velocity);
            self.wake_index(i);
        }
        Ok(())
    }

    /// Refuses a velocity whose square overflows (its body's speed limit
    /// could not scale it), and a kinematic body's speed above the world's
    /// maximum (nothing else limits it, and positions would overflow).
    fn check_velocity(
        &self,
        i: usize,
        velocity: Vec2,
        what: &'static str,
    ) -> Result<(), PhysicsError> {
        let speed_sq = velocity.length_squared();
        if !speed_sq.is_finite() {
            return Err(PhysicsError::NonFinite { what });
        }
        let max = self.settings.max_speed;
        if self.dynamic.meta[i].kinematic && speed_sq > max * max {
            return Err(PhysicsError::OutOfRange {
                what,
                value: speed_sq.sqrt(),
                allowed: "at most WorldSettings::max_speed for a kinematic body",
            });
        }
        Ok(())
    }

    /// Sets a kinematic body's velocity so that it reaches `target` at the
    /// end of the next step of `dt` seconds: `(target - position) / dt`.
    /// Call it every tick to move a platform along a path. Ignored for
    /// dynamic and static bodies.
    ///
    /// # Errors
    /// A stale id, a non-finite target, or a `dt` that is not finite and
    /// > 0.
    pub fn try_set_kinematic_target(
        &mut self,
        id: BodyId,
        target: Vec2,
        dt: f32,
    ) -> Result<(), PhysicsError> {
        crate::error::position("target", target)?;
        positive("dt", dt)?;
        if let Some(i) = self.dynamic_index(id)?
            && self.dynamic.meta[i].kinematic
        {
            let velocity = (target - self.dynamic.pos.at(i)) / dt;
            finite_vec("velocity to the target", velocity)?;
            self.check_velocity(i, velocity, "velocity to the target")?;
            // A platform held still may sleep with its riders: only a
            // change of velocity wakes them.
            if self.dynamic.vel.at(i) != velocity {
                self.dynamic.vel.set(i, velocity);
                self.wake_index(i);
            }
        }
        Ok(())
    }

    /// Adds a force, newtons, to the body's accumulator for the next step
    /// (acceleration = F / m). Forces are cleared after each step. Ignored
    /// for static and kinematic bodies.
    pub fn try_apply_force(&mut self, id: BodyId, force: Vec2) -> Result<(), PhysicsError> {
        finite_vec("force", force)?;
        if let Some(i) = self.movable_index(id)? {
            let total = self.dynamic.force.at(i) + force;
            finite_vec("accumulated force", total)?;
            self.dynamic.force.set(i, total);
            self.wake_index(i);
        }
        Ok(())
    }

    /// Changes the body's velocity now by `impulse / m` (impulse in newton
    /// seconds): a jump, a hit. Ignored for static and kinematic bodies.
    pub fn try_apply_impulse(&mut self, id: BodyId, impulse: Vec2) -> Result<(), PhysicsError> {
        finite_vec("impulse", impulse)?;
        if let Some(i) = self.movable_index(id)? {
            let velocity = self.dynamic.vel.at(i) + impulse * self.dynamic.inv_mass[i];
            self.check_velocity(i, velocity, "velocity after the impulse")?;
            self.dynamic.vel.set(i, velocity);
            self.wake_index(i);
        }
        Ok(())
    }

    /// Applies kinetic friction `-mu |N| v_hat` for the next step, with the
    /// normal force magnitude `normal` in newtons (the seed's
    /// `ApplyFriction(mu, N)`). With [`ForceForm::Stable`](crate::ForceForm::Stable) it slows the body
    /// by at most its speed: it stops, never reverses. Accumulates like a
    /// force and is cleared after each step. Ignored for static and
    /// kinematic bodies.
    pub fn try_apply_friction(
        &mut self,
        id: BodyId,
        mu: f32,
        normal: f32,
    ) -> Result<(), PhysicsError> {
        non_negative("mu", mu)?;
        finite("normal", normal)?;
        if let Some(i) = self.movable_index(id)? {
            let total = self.dynamic.friction_force[i] + mu * normal.abs();
            finite("accumulated friction force", total)?;
            self.dynamic.friction_force[i] = total;
            self.wake_index(i);
            self.game_friction = true;
        }
        Ok(())
    }

    /// Sets a body's friction coefficient `mu` (0 to
    /// [`MAX_FRICTION`](crate::constants::MAX_FRICTION)), for surface
    /// friction and contacts.
    pub fn try_set_friction(&mut self, id: BodyId, mu: f32) -> Result<(), PhysicsError> {
        check_friction("friction", mu)?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        match location {
            Location::Dynamic(i) => self.dynamic.friction[i as usize] = mu,
            Location::Static(i) => self.statics.friction[i as usize] = mu,
        }
        self.contacts_changed(id, location);
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets a body's restitution, in `[0, 1]`.
    pub fn set_restitution(&mut self, id: BodyId, restitution: f32) -> Result<(), PhysicsError> {
        unit_interval("restitution", restitution)?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        let is_static = matches!(location, Location::Static(_));
        let meta = self.meta_mut(location);
        let before = BodyCensus::share(meta, is_static);
        meta.restitution = restitution;
        let after = BodyCensus::share(meta, is_static);
        self.census.remove(before);
        self.census.add(after);
        self.contacts_changed(id, location);
        self.wake_after_change(location);
        Ok(())
    }

    /// Lets a dynamic body pass through one-way platforms for `seconds`
    /// (the player pressing down): contacts with them are ignored until the
    /// time runs out, and a body then still inside one goes on through.
    /// `0` ends it. On a kinematic body it is for
    /// [`move_character`](Self::move_character), which then lets the
    /// character through. Ignored for static bodies.
    ///
    /// # Errors
    /// A stale id, or `seconds` not finite and >= 0.
    pub fn try_drop_through(&mut self, id: BodyId, seconds: f32) -> Result<(), PhysicsError> {
        non_negative("drop_through seconds", seconds)?;
        if let Some(i) = self.dynamic_index(id)? {
            let meta = &mut self.dynamic.meta[i];
            let before = BodyCensus::share(meta, false);
            meta.drop_through = seconds;
            let after = BodyCensus::share(meta, false);
            self.census.remove(before);
            self.census.add(after);
            self.wake_index(i);
        }
        Ok(())
    }

    /// Changes how a body's friction combines with another's in contacts.
    pub fn set_friction_mix(&mut self, id: BodyId, mix: FrictionMix) -> Result<(), PhysicsError> {
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        self.meta_mut(location).friction_mix = mix;
        self.contacts_changed(id, location);
        self.wake_after_change(location);
        Ok(())
    }

    /// Changes which bodies this one may touch.
    pub fn set_filter(&mut self, id: BodyId, filter: CollisionFilter) -> Result<(), PhysicsError> {
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        self.meta_mut(location).filter = filter;
        self.contacts_changed(id, location);
        self.static_shape_changed(location);
        self.wake_after_change(location);
        Ok(())
    }

    /// Makes a body a sensor (it reports overlaps and pushes nothing) or a
    /// solid body again.
    pub fn set_sensor(&mut self, id: BodyId, sensor: bool) -> Result<(), PhysicsError> {
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        self.meta_mut(location).sensor = sensor;
        self.contacts_changed(id, location);
        self.static_shape_changed(location);
        self.wake_after_change(location);
        Ok(())
    }

    /// Makes a body a conveyor whose surface moves at `velocity` (see
    /// [`BodyDef::conveyor`](crate::BodyDef::conveyor)), or an ordinary body
    /// again with `None`. What touches it wakes.
    ///
    /// # Errors
    /// A stale id, or a velocity that is not finite.
    pub fn set_conveyor(&mut self, id: BodyId, velocity: Option<Vec2>) -> Result<(), PhysicsError> {
        if let Some(v) = velocity {
            crate::error::finite_vec("conveyor", v)?;
        }
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        let is_static = matches!(location, Location::Static(_));
        let meta = self.meta_mut(location);
        let before = BodyCensus::share(meta, is_static);
        meta.conveyor = velocity;
        let after = BodyCensus::share(meta, is_static);
        self.census.remove(before);
        self.census.add(after);
        self.contacts_changed(id, location);
        if is_static {
            self.revisions.statics_changed();
        }
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets how much of the world's gravity acts on a dynamic body (see
    /// [`BodyDef::gravity_scale`](crate::BodyDef::gravity_scale)). The body
    /// wakes.
    ///
    /// # Errors
    /// A stale id, a scale that is not finite or beyond
    /// [`MAX_GRAVITY_SCALE`](crate::constants::MAX_GRAVITY_SCALE), or a
    /// static or kinematic body.
    pub fn set_gravity_scale(&mut self, id: BodyId, scale: f32) -> Result<(), PhysicsError> {
        crate::body::def::check_gravity_scale("gravity_scale", scale)?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        let Location::Dynamic(i) = location else {
            return Err(PhysicsError::OutOfRange {
                what: "gravity_scale",
                value: scale,
                allowed: "set only on dynamic bodies",
            });
        };
        let meta = &mut self.dynamic.meta[i as usize];
        if meta.kinematic {
            return Err(PhysicsError::OutOfRange {
                what: "gravity_scale",
                value: scale,
                allowed: "set only on dynamic bodies",
            });
        }
        let before = BodyCensus::share(meta, false);
        meta.gravity_scale = scale;
        let after = BodyCensus::share(meta, false);
        self.census.remove(before);
        self.census.add(after);
        self.wake_index(i as usize);
        Ok(())
    }

    /// Makes a dynamic body a bullet, or an ordinary body again (see
    /// [`BodyDef::bullet`](crate::BodyDef::bullet)).
    ///
    /// # Errors
    /// A stale id, or `true` for a static or kinematic body.
    pub fn set_bullet(&mut self, id: BodyId, bullet: bool) -> Result<(), PhysicsError> {
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        let meta = self.meta_mut(location);
        if bullet && (matches!(location, Location::Static(_)) || meta.kinematic) {
            return Err(PhysicsError::OutOfRange {
                what: "bullet",
                value: 1.0,
                allowed: "set only on dynamic bodies",
            });
        }
        meta.bullet = bullet;
        Ok(())
    }

    /// Makes a static or kinematic body a one-way platform with the given
    /// solid side (see [`BodyDef::one_way`](crate::BodyDef::one_way)), or
    /// solid from every side again with `None`.
    ///
    /// # Errors
    /// A stale id, a zero or non-finite normal, or a dynamic body.
    pub fn set_one_way(&mut self, id: BodyId, one_way: Option<Vec2>) -> Result<(), PhysicsError> {
        let normal = one_way.map(|n| check_one_way("one_way", n)).transpose()?;
        let location = self.locate(id).ok_or(PhysicsError::StaleBody(id))?;
        let meta = self.meta_mut(location);
        if normal.is_some() && matches!(location, Location::Dynamic(_)) && !meta.kinematic {
            return Err(PhysicsError::OutOfRange {
                what: "one_way",
                value: 1.0,
                allowed: "set only on static and kinematic bodies",
            });
        }
        meta.one_way = normal;
        self.contacts_changed(id, location);
        self.static_shape_changed(location);
        self.wake_after_change(location);
        Ok(())
    }

    /// Sets a body's drag area `Cd A`, square metres (>= 0): a glider
    /// opening its wings.
    pub fn set_drag_area(&mut self, id: BodyId, drag_area: f32) -> Result<(), PhysicsError> {
        check_drag_area("drag_area", drag_area)?;
        match self.locate(id).ok_or(PhysicsError::StaleBody(id))? {
            Location::Dynamic(i) => {
                self.dynamic.drag_area[i as usize] = drag_area;
                self.dynamic.meta[i as usize].drag_area = drag_area;
                self.wake_index(i as usize);
            }
            Location::Static(i) => {
                // Nothing steps with it, but snapshots carry it.
                self.statics.meta[i as usize].drag_area = drag_area;
                self.revisions.statics_changed();
            }
        }
        Ok(())
    }

    /// Where to draw a body between the last two steps: `lerp(previous,
    /// current, alpha)` with `alpha` in `[0, 1]` (clamped; NaN draws the
    /// current position). Without
    /// [`WorldSettings::interpolation`](crate::WorldSettings::interpolation) this is the current position.
    pub fn interpolated_position(&self, id: BodyId, alpha: f32) -> Option<Vec2> {
        Some(match self.locate(id)? {
            Location::Dynamic(i) => self.lerp_dynamic(i as usize, alpha),
            Location::Static(i) => self.statics.pos[i as usize],
        })
    }

    /// Game code changed what the body at `location` collides with
    /// (friction, restitution, friction mix, filter, sensor, one-way side):
    /// its contacts are found afresh at the next step, and all of them
    /// after a static body's change, which may change what it covers of
    /// its neighbours.
    pub(crate) fn contacts_changed(&mut self, id: BodyId, location: Location) {
        match (location, &mut self.contacts) {
            (Location::Dynamic(_), Some(cw)) => cw.forget_reuse(id),
            (Location::Static(_), _) => self.forget_all_reuse(),
            (_, None) => {}
        }
    }

    /// Every contact is found afresh at the next step (a static body or
    /// the settings changed).
    pub(crate) fn forget_all_reuse(&mut self) {
        if let Some(cw) = &mut self.contacts {
            cw.forget_all_reuse();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::ForceModels;
    use crate::{BodyDef, PhysicsError, QuadraticDrag, Shape, World, WorldSettings};
    use glam::Vec2;

    fn ball(x: f32) -> BodyDef {
        BodyDef::point_mass(Vec2::new(x, 0.0))
    }

    #[test]
    fn impulse_changes_velocity_by_j_over_m() {
        let mut world = World::default();
        let id = world
            .add_body(BodyDef {
                mass: 4.0,
                ..Default::default()
            })
            .unwrap();
        world.apply_impulse(id, Vec2::new(2.0, 8.0));
        assert_eq!(world.body(id).unwrap().velocity, Vec2::new(0.5, 2.0));
    }

    #[test]
    fn non_finite_forces_and_settings_are_rejected() {
        let mut world = World::default();
        let id = world.add_body(ball(0.0)).unwrap();
        let nan = Vec2::new(f32::NAN, 0.0);
        assert!(world.try_apply_force(id, nan).is_err());
        assert!(world.try_apply_impulse(id, nan).is_err());
        assert!(world.try_set_position(id, nan).is_err());
        assert!(world.try_set_velocity(id, nan).is_err());
        assert!(world.try_apply_friction(id, -1.0, 10.0).is_err());
        assert!(world.try_apply_friction(id, 0.5, f32::INFINITY).is_err());
        let mut bad = WorldSettings::default();
        bad.forces.gravity = Some(nan);
        assert_eq!(
            world.set_settings(bad).unwrap_err().to_string(),
            "ForceModels::gravity must be finite (got NaN or infinity)"
        );
        let bad = WorldSettings {
            min_speed: -1.0,
            ..Default::default()
        };
        assert!(World::new(bad).is_err());
        let mut bad = WorldSettings::default();
        bad.forces.quadratic_drag = Some(QuadraticDrag { density: -1.0 });
        assert!(World::new(bad).is_err());
        assert_eq!(world.body(id).unwrap().force, Vec2::ZERO);
    }

    #[test]
    fn interpolation_draws_between_the_last_two_positions() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            interpolation: true,
            ..Default::default()
        })
        .unwrap();
        let id = world
            .add_body(BodyDef {
                velocity: Vec2::new(2.0, 0.0),
                ..ball(0.0)
            })
            .unwrap();
        world.step(0.5);
        assert_eq!(world.interpolated_position(id, 0.0), Some(Vec2::ZERO));
        assert_eq!(
            world.interpolated_position(id, 0.5),
            Some(Vec2::new(0.5, 0.0))
        );
        assert_eq!(
            world.interpolated_position(id, 1.0),
            Some(Vec2::new(1.0, 0.0))
        );
        world.set_position(id, Vec2::new(9.0, 0.0));
        assert_eq!(
            world.interpolated_position(id, 0.0),
            Some(Vec2::new(9.0, 0.0))
        );
    }

    #[test]
    fn material_setters_check_their_input_and_take_effect() {
        let mut world = World::default();
        let id = world.add_body(ball(0.0)).unwrap();
        world.set_friction(id, 0.1);
        world.set_restitution(id, 0.9).unwrap();
        world.set_drag_area(id, 2.0).unwrap();
        let b = world.body(id).unwrap();
        assert_eq!((b.friction, b.restitution, b.drag_area), (0.1, 0.9, 2.0));
        assert!(world.try_set_friction(id, -1.0).is_err());
        assert!(world.set_restitution(id, 1.1).is_err());
        assert!(world.set_drag_area(id, f32::NAN).is_err());
        let ground = world
            .add_body(BodyDef::new_static(Vec2::ZERO, Shape::circle(1.0)))
            .unwrap();
        world.set_friction(ground, 0.02);
        assert_eq!(world.body(ground).unwrap().friction, 0.02);
        world.remove_body(id);
        assert_eq!(
            world.try_set_friction(id, 0.5),
            Err(PhysicsError::StaleBody(id))
        );
    }
}
