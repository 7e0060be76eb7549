//! The step: a plan made from the settings and the bodies, and the stages
//! it runs, each a function, each skipped when the plan does not need it.
//!
//! This is the one description of a tick; the other places that speak of
//! it link here. `[Stage]` and `[ContactStage]` name the stages that
//! [`World::active_stages`] and [`World::contact_stages`] list.
//!
//! ```text
//! World::step(dt)
//!   store previous positions                    [StorePrevious, with interpolation]
//!   without contacts, one pass per body:        [the force models, Integrate, SpeedLimits]
//!     forces, integrate, speed limits; kinematic bodies move by their own velocity
//!   with contacts (step::contacts):             [Contacts]
//!     find the contacts: broad phase, narrow phase, warm-start impulses
//!                                               (ContactWorld::begin_step)
//!     find deep piles, plan the substeps, split the contacts in regions,
//!     order the contacts that hold bodies up (solver::shock)
//!     each substep h = dt / substeps, on the body arrays:
//!       integrate velocities                    [IntegrateVelocities]
//!       hold sleepers still                     [HoldSleepers]
//!       hold kinematic bodies at their velocity [HoldKinematic]
//!     then on the solver's copy of the velocities (solver::motion):
//!       warm start                              [WarmStart]
//!       solve: normal, friction, push           [Solve]
//!       shock propagation: from the ground up   [PropagateShock]
//!       integrate positions by velocity + push  [IntegratePositions]
//!       relax: velocity passes, no push         [Relax]
//!     after the substeps:
//!       sweep fast bodies to their first impact [SweepFastBodies]
//!       restitution                             [Restitution]
//!       store each contact's separation         [StoreSeparations]
//!       clamp speeds                            [ClampSpeeds]
//!     put back non-finite bodies; record events and sleep
//!                                               (ContactWorld::end_step)
//!   clear forces, count down drop-through timers
//! ```
//!
//! The contact step runs its stages from the plan's list
//! (`SubstepPlan::stages`), as Box2D walks its stage array: the list a user
//! reads is the list that runs.

pub(crate) mod contacts;
use crate::body::census::BodyCensus;
use crate::body::store::SpeedLimits;
use crate::constants::MAX_STEP;
use crate::forces::integrator::integrate_velocity;
use crate::parallel::for_chunks;
use crate::world::{World, step_forces};
use crate::{ContactSettings, Integrator};
use glam::Vec2;

/// One stage of [`World::step`]. A world runs only the stages its settings
/// and bodies ask for; [`World::active_stages`] lists them in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Copy positions for interpolation.
    StorePrevious,
    /// Weight `m g`.
    Gravity,
    /// Constant force field.
    ForceField,
    /// Spring to an anchor.
    Spring,
    /// Central (orbital) gravity.
    CentralGravity,
    /// The game's own [`ForceModel`](crate::ForceModel)s.
    CustomForces,
    /// Gravity scaled per body ([`BodyDef::gravity_scale`](crate::BodyDef::gravity_scale))
    /// and force zones ([`World::add_force_zone`]): forces added before
    /// the step.
    BodyForces,
    /// Quadratic drag.
    QuadraticDrag,
    /// Linear drag.
    LinearDrag,
    /// Top-down surface friction.
    SurfaceFriction,
    /// Integration of velocities and positions with the given method.
    Integrate(Integrator),
    /// Kinematic bodies move by their own velocity.
    Kinematic,
    /// Broad phase, narrow phase and the contact solver (its own stages:
    /// [`World::contact_stages`]).
    Contacts,
    /// Minimum-speed snap and maximum-speed clamp.
    SpeedLimits,
}

/// What a step runs, decided once from the settings and the bodies.
struct StepPlan {
    store_previous: bool,
    /// The contact settings when the contact stage runs.
    contacts: Option<ContactSettings>,
    /// `Some` when speed limits apply: `Some(uniform)` for the world's,
    /// `None` when some body has its own.
    limits: Option<Option<SpeedLimits>>,
}

impl StepPlan {
    fn stages(&self, world: &World) -> Vec<Stage> {
        let f = &world.settings().forces;
        let mut stages = Vec::new();
        if self.store_previous {
            stages.push(Stage::StorePrevious);
        }
        let models = [
            (f.gravity.is_some(), Stage::Gravity),
            (f.force_field.is_some(), Stage::ForceField),
            (f.spring.is_some(), Stage::Spring),
            (f.central_gravity.is_some(), Stage::CentralGravity),
            (!world.custom.is_empty(), Stage::CustomForces),
            (world.has_body_forces(), Stage::BodyForces),
            (f.quadratic_drag.is_some(), Stage::QuadraticDrag),
            (f.linear_drag.is_some(), Stage::LinearDrag),
            (f.surface_friction.is_some(), Stage::SurfaceFriction),
        ];
        stages.extend(models.iter().filter(|(on, _)| *on).map(|(_, s)| *s));
        stages.push(Stage::Integrate(world.settings().integrator));
        if !world.dynamic.kinematic.is_empty() {
            stages.push(Stage::Kinematic);
        }
        if self.contacts.is_some() {
            stages.push(Stage::Contacts);
        }
        if self.limits.is_some() {
            stages.push(Stage::SpeedLimits);
        }
        stages
    }
}

impl World {
    /// The stages [`step`](Self::step) runs with the current settings and
    /// bodies, in order.
    pub fn active_stages(&self) -> Vec<Stage> {
        self.plan().stages(self)
    }

    fn plan(&self) -> StepPlan {
        StepPlan {
            store_previous: self.settings().interpolation,
            contacts: self.contact_settings(),
            limits: self.speed_limits(),
        }
    }

    /// Advances the world by `dt` seconds, stage by stage; each stage runs
    /// only if the settings and bodies ask for it
    /// ([`active_stages`](Self::active_stages) and
    /// [`contact_stages`](Self::contact_stages) list them). The `step`
    /// module's documentation (in the source, `step/mod.rs`) describes the
    /// tick stage by stage.
    ///
    /// Run it from a fixed-timestep loop (`passo-loop`) with a constant `dt`:
    /// a variable `dt` makes the result depend on the frame rate.
    ///
    /// # Panics
    /// If `dt` is not in `(0, MAX_STEP]` seconds
    /// ([`MAX_STEP`], an hour): a zero,
    /// negative, NaN or enormous timestep is a programming error, not a
    /// state the world can be in.
    pub fn step(&mut self, dt: f32) {
        assert!(
            dt > 0.0 && dt <= MAX_STEP,
            "World::step: dt must be finite and > 0 seconds, at most {MAX_STEP}, got {dt}"
        );
        let plan = self.plan();
        self.broken_joints.clear();
        if plan.store_previous {
            debug_assert_eq!(self.dynamic.prev_pos.len(), self.dynamic.len());
            self.dynamic.prev_pos.copy_from(&self.dynamic.pos);
        }
        let mut forces_cleared = false;
        match plan.contacts {
            Some(contacts) => self.step_with_contacts(dt, &contacts),
            None => {
                // Sleeping belongs to the contact stage: without it, no body
                // sleeps (the idle step wakes them all).
                if let Some(cw) = &mut self.contacts {
                    cw.idle_step(
                        &mut self.dynamic,
                        &self.statics,
                        self.stats.steps.saturating_add(1),
                    );
                }
                self.note_kinematic_motion();
                if self.has_body_forces() {
                    self.add_body_forces(dt, true);
                }
                forces_cleared = self.step_bodies(dt, plan.limits);
                self.move_kinematic(dt);
            }
        }
        self.clear_forces(forces_cleared);
        self.restore_limits();
        self.count_down_drop_through(dt);
        debug_assert_eq!(
            self.census,
            BodyCensus::recount(&self.dynamic, &self.statics),
            "the body census agrees with a recount of the bodies"
        );
        // Saturates rather than wraps: 2^64 steps at 60 Hz is 10^10 years,
        // but a restored snapshot may start anywhere.
        self.stats.steps = self.stats.steps.saturating_add(1);
        if self.stats.steps == u64::MAX {
            // The count no longer changes: queries, which rebuild when it
            // does, see the step as an edit instead.
            self.revisions.edits = self.revisions.edits.wrapping_add(1);
        }
    }

    /// Integrates velocities, clamps speeds and moves bodies, one body at a
    /// time: a single pass over the arrays. Returns whether that pass also
    /// cleared the force accumulators (the point-mass kernel does).
    fn step_bodies(&mut self, dt: f32, limits: Option<Option<SpeedLimits>>) -> bool {
        if let Some(kernel) = self.kernel(limits) {
            let resets = kernel.run(&mut self.dynamic, dt, self.parallel);
            self.stats.non_finite_resets = self.stats.non_finite_resets.saturating_add(resets);
            return true;
        }
        let integrator = self.settings().integrator;
        let forces = step_forces(&self.settings, &self.custom, self.game_friction);
        let (pos, vel, arrays) = self.dynamic.split();
        let resets = for_chunks(self.parallel, (pos, vel), |offset, (pos, vel)| {
            let mut resets = 0;
            // Copies of their own: stores to the arrays cannot alias them,
            // so the hoisted constants stay in registers (read through the
            // closure's references, they were loaded again for each body).
            let (forces, integrator, limits, dt) = (forces, integrator, limits, dt);
            let ((px, py), (vx, vy)) = (pos.into_parts(), vel.into_parts());
            let arrays = arrays.run(offset, px.len());
            let bodies = (px.iter_mut().zip(py)).zip(vx.iter_mut().zip(vy));
            for (k, ((px, py), (vx, vy))) in bodies.enumerate() {
                let (p, v) = (Vec2::new(*px, *py), Vec2::new(*vx, *vy));
                let params = arrays.params(k);
                let (mut nv, mut c) =
                    integrate_velocity(integrator, &forces, p, v, &params, dt, &mut resets);
                // A limit that changed the velocity leaves out the
                // integrator's correction, worked out for the velocity
                // before it: the body moves by its limited velocity, as with
                // semi-implicit Euler. Kept, it moved a body clamped from a
                // hard push backwards (2.61 m in a step with explicit Euler)
                // and made one snapped to rest under gravity climb.
                if let Some(uniform) = limits
                    && uniform.unwrap_or(arrays.limits[k]).apply(&mut nv)
                {
                    c = Vec2::ZERO;
                }
                (*vx, *vy) = (nv.x, nv.y);
                let p = p + (nv * dt + c);
                (*px, *py) = (p.x, p.y);
            }
            resets
        });
        self.stats.non_finite_resets = self.stats.non_finite_resets.saturating_add(resets);
        false
    }

    /// Notes where each kinematic body is and how fast it goes, before
    /// integration treats it as any body.
    pub(crate) fn note_kinematic_motion(&mut self) {
        self.held.clear();
        let b = &self.dynamic;
        let held = b
            .kinematic
            .iter()
            .map(|&i| (b.pos.at(i as usize), b.vel.at(i as usize)));
        self.held.extend(held);
    }

    /// Stage (without contacts): kinematic bodies move by their own
    /// velocity alone, `p <- p + v dt`, whatever integration did to them.
    fn move_kinematic(&mut self, dt: f32) {
        let b = &mut self.dynamic;
        for (&i, &(p, v)) in b.kinematic.iter().zip(&self.held) {
            b.pos.set(i as usize, p + v * dt);
            b.vel.set(i as usize, v);
        }
    }

    /// Bodies dropping through one-way platforms have `dt` less left.
    fn count_down_drop_through(&mut self, dt: f32) {
        if self.census.dropping == 0 {
            return;
        }
        let mut still = 0;
        for m in &mut self.dynamic.meta {
            // (`>=` would do the same: a zero stays zero.)
            if m.drop_through > 0.0 {
                m.drop_through = (m.drop_through - dt).max(0.0);
                still += usize::from(m.drop_through > 0.0);
            }
        }
        self.census.dropping = still;
    }

    /// Clears the force accumulators, unless the step did (`cleared`), and
    /// the friction forces game code set.
    fn clear_forces(&mut self, cleared: bool) {
        if !cleared {
            self.dynamic.force.fill(Vec2::ZERO);
        }
        if self.game_friction {
            self.dynamic.friction_force.fill(0.0);
            self.game_friction = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::DEFAULT_MAX_SPEED;
    use crate::{BodyDef, CentralGravity, ForceModel, ForceModels, QuadraticDrag, WorldSettings};
    use std::sync::Arc;

    fn ball(x: f32) -> BodyDef {
        BodyDef::point_mass(Vec2::new(x, 0.0))
    }

    #[test]
    fn forces_accumulate_and_are_cleared_after_each_step() {
        // The point-mass kernel (which clears the forces in its own pass)
        // and the general path (which clears them after it).
        for integrator in [Integrator::SemiImplicitEuler, Integrator::ExplicitEuler] {
            let mut world = World::new(WorldSettings {
                forces: ForceModels::none(),
                integrator,
                min_speed: 0.0,
                ..Default::default()
            })
            .unwrap();
            let id = world
                .add_body(BodyDef {
                    mass: 2.0,
                    ..Default::default()
                })
                .unwrap();
            let kernel = world.kernel(world.speed_limits()).is_some();
            assert_eq!(kernel, integrator == Integrator::SemiImplicitEuler);
            world.apply_force(id, Vec2::new(1.0, 0.0));
            world.apply_force(id, Vec2::new(3.0, 2.0));
            assert_eq!(world.body(id).unwrap().force, Vec2::new(4.0, 2.0));
            world.step(0.5);
            // a = F / m = (2, 1); v = a dt.
            assert_eq!(world.body(id).unwrap().velocity, Vec2::new(1.0, 0.5));
            assert_eq!(world.body(id).unwrap().force, Vec2::ZERO);
            world.step(0.5);
            assert_eq!(world.body(id).unwrap().velocity, Vec2::new(1.0, 0.5));
        }
    }

    #[test]
    #[should_panic(expected = "dt must be finite and > 0 seconds, at most 3600, got 0")]
    fn zero_timestep_panics_with_a_clear_message() {
        World::default().step(0.0);
    }

    #[test]
    #[should_panic(expected = "dt must be finite and > 0 seconds, at most 3600, got NaN")]
    fn nan_timestep_panics_with_a_clear_message() {
        World::default().step(f32::NAN);
    }

    #[test]
    #[should_panic(expected = "at most 3600, got 100000000")]
    fn an_enormous_timestep_panics_with_a_clear_message() {
        World::default().step(1e8);
    }

    #[test]
    fn the_longest_step_moves_the_fastest_body_a_finite_way() {
        // No speed clamp, no forces: the largest velocity a body may have
        // (its square just finite) over the longest step.
        let settings = WorldSettings {
            forces: ForceModels::none(),
            max_speed: f32::INFINITY,
            ..WorldSettings::default()
        };
        let mut world = World::new(settings).unwrap();
        let v = Vec2::new(1.8e19, 0.0);
        let id = world
            .add_body(BodyDef {
                velocity: v,
                ..BodyDef::default()
            })
            .unwrap();
        world.step(MAX_STEP);
        let b = world.body(id).unwrap();
        assert_eq!(b.velocity, v);
        assert_eq!(b.position.x, v.x * MAX_STEP);
        assert!(b.position.is_finite());
    }

    struct Broken;
    impl ForceModel for Broken {
        fn force(&self, _: Vec2, _: Vec2, _: f32) -> Vec2 {
            Vec2::new(f32::NAN, 0.0)
        }
    }

    #[test]
    fn a_force_model_returning_nan_never_reaches_the_state() {
        for integrator in Integrator::ALL {
            let mut world = World::new(WorldSettings {
                integrator,
                ..Default::default()
            })
            .unwrap();
            world.add_force_model(Arc::new(Broken));
            let id = world
                .add_body(BodyDef {
                    velocity: Vec2::X,
                    ..ball(2.0)
                })
                .unwrap();
            world.step(0.1);
            let b = world.body(id).unwrap();
            assert_eq!((b.position, b.velocity), (Vec2::new(2.0, 0.0), Vec2::ZERO));
            assert_eq!(world.stats().non_finite_resets, 1);
        }
    }

    /// Buoyancy proportional to mass, as in the `ForceModel` docs.
    struct Buoyancy;
    impl ForceModel for Buoyancy {
        fn force(&self, p: Vec2, _: Vec2, mass: f32) -> Vec2 {
            if p.y < 0.0 {
                Vec2::new(0.0, 12.0 * mass)
            } else {
                Vec2::ZERO
            }
        }
    }

    #[test]
    fn a_kinematic_body_never_meets_a_custom_force_model() {
        // A kinematic body's mass is infinite: the model's `12 * mass` times
        // its inverse mass, zero, was NaN, and every step counted a reset.
        for contacts in [false, true] {
            let mut world = World::new(WorldSettings {
                contacts: contacts.then(crate::ContactSettings::default),
                ..Default::default()
            })
            .unwrap();
            world.add_force_model(Arc::new(Buoyancy));
            let lift = world
                .add_body(BodyDef {
                    kind: crate::BodyKind::Kinematic,
                    velocity: Vec2::new(0.0, 1.0),
                    shape: Some(crate::Shape::rect(2.0, 0.5)),
                    ..BodyDef::point_mass(Vec2::new(-3.0, -5.0))
                })
                .unwrap();
            let float = world
                .add_body(BodyDef::point_mass(Vec2::new(3.0, -3.0)))
                .unwrap();
            for _ in 0..30 {
                world.step(0.1);
            }
            assert_eq!(world.stats().non_finite_resets, 0, "contacts {contacts}");
            let lift = world.body(lift).unwrap();
            assert_eq!(lift.velocity, Vec2::new(0.0, 1.0));
            // The dynamic body did feel the model: it rose out of the water
            // (12 m/s² up against gravity's 9.81).
            assert!(world.body(float).unwrap().position.y > -3.0);
        }
    }

    #[test]
    fn impulses_that_overflow_put_the_bodies_back_instead_of_leaving_nan() {
        use crate::Shape;
        // No speed limit: the heaviest bodies allowed, at 1e9 m/s, into a
        // wall and into each other. Their impulses overflow `f32`.
        let mut world = World::new(WorldSettings {
            max_speed: f32::INFINITY,
            ..Default::default()
        })
        .unwrap();
        let wall = BodyDef::new_static(Vec2::new(10.0, 0.0), Shape::rect(1.0, 10.0));
        world.add_body(wall).unwrap();
        let heavy = |x: f32, vx: f32| {
            BodyDef::new_dynamic(Vec2::new(x, 0.0), Shape::circle(0.5))
                .with_mass(1e30)
                .with_velocity(Vec2::new(vx, 0.0))
        };
        let ids = [
            world.add_body(heavy(0.0, 1e9)).unwrap(),
            world.add_body(heavy(-20.0, 1e9)).unwrap(),
            world.add_body(heavy(-30.0, -1e9)).unwrap(),
        ];
        for _ in 0..5 {
            world.step(1.0 / 60.0);
            for &id in &ids {
                let b = world.body(id).unwrap();
                assert!(b.position.is_finite() && b.velocity.is_finite(), "{b:?}");
            }
        }
        assert!(world.stats().non_finite_resets > 0);
        // Put back where its step began, at rest: the first is never past the wall.
        let first = world.body(ids[0]).unwrap();
        assert!(first.position.x < 10.0, "{first:?}");
        // Nothing non-finite is carried to the next step or into a save.
        let restored = World::from_snapshot(world.snapshot());
        assert!(restored.is_ok(), "{:?}", restored.err());
    }

    #[test]
    fn an_overflowing_force_is_clamped_not_turned_into_nan() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            max_speed: f32::INFINITY,
            ..Default::default()
        })
        .unwrap();
        let id = world
            .add_body(BodyDef {
                mass: 1e-30,
                ..ball(0.0)
            })
            .unwrap();
        world.apply_force(id, Vec2::new(f32::MAX, f32::MAX));
        world.step(1.0);
        let b = world.body(id).unwrap();
        assert!(b.position.is_finite() && b.velocity.is_finite());
        assert_eq!(world.stats().non_finite_resets, 1);

        // A finite velocity whose square overflows (1e30 m/s) is dropped too.
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            ..Default::default()
        })
        .unwrap();
        let id = world.add_body(ball(0.0)).unwrap();
        world.apply_force(id, Vec2::new(1e30, 1e30));
        world.step(1.0);
        assert_eq!(world.body(id).unwrap().velocity, Vec2::ZERO);
        assert_eq!(world.stats().non_finite_resets, 1);

        // A large but sane velocity is clamped to exactly the maximum speed.
        let id = world.add_body(ball(0.0)).unwrap();
        world.apply_force(id, Vec2::new(3e6, 4e6));
        world.step(1.0);
        let v = world.body(id).unwrap().velocity;
        assert_eq!(v, Vec2::new(600.0, 800.0));
        assert_eq!(v.length(), DEFAULT_MAX_SPEED);
    }

    #[test]
    fn without_interpolation_no_previous_positions_are_kept() {
        let mut world = World::default();
        world.add_body(ball(0.0)).unwrap();
        world.step(0.1);
        assert!(world.dynamic.prev_pos.is_empty());
        assert!(!world.active_stages().contains(&Stage::StorePrevious));
    }

    #[test]
    fn active_stages_list_only_what_the_settings_ask_for() {
        let world = World::new(WorldSettings {
            max_speed: f32::INFINITY,
            min_speed: 0.0,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(
            world.active_stages(),
            [
                Stage::Gravity,
                Stage::Integrate(Integrator::SemiImplicitEuler)
            ]
        );
        let mut forces = ForceModels::none();
        forces.central_gravity = Some(CentralGravity {
            centre: Vec2::ZERO,
            gm: 1.0,
        });
        forces.quadratic_drag = Some(QuadraticDrag::default());
        let world = World::new(WorldSettings {
            forces,
            integrator: Integrator::Rk4,
            interpolation: true,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(
            world.active_stages(),
            [
                Stage::StorePrevious,
                Stage::CentralGravity,
                Stage::QuadraticDrag,
                Stage::Integrate(Integrator::Rk4),
                Stage::SpeedLimits
            ]
        );
    }

    /// Once the step count stops at `u64::MAX`, each step still counts as
    /// a change for queries: a moving body is found where it is now.
    #[test]
    fn queries_follow_a_body_after_the_step_count_stops() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
            ..Default::default()
        })
        .unwrap();
        let def = BodyDef {
            velocity: Vec2::new(60.0, 0.0),
            shape: Some(crate::Shape::circle(0.1)),
            ..Default::default()
        };
        let id = world.add_body(def).unwrap();
        world.stats.steps = u64::MAX - 2;
        for _ in 0..3 {
            world.step(1.0 / 60.0);
            let x = world.body(id).unwrap().position.x;
            let here = crate::Aabb::from_centre(Vec2::new(x, 0.0), Vec2::splat(0.2));
            assert_eq!(world.query_aabb(here), [id], "at x = {x}");
        }
        assert_eq!(world.stats.steps, u64::MAX);
    }
}
