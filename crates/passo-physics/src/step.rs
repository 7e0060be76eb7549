//! The step: a plan made from the settings and the bodies, and the stages
//! it runs, each a function, each skipped when the plan does not need it.
//!
//! ```text
//! World::step(dt)
//!   store previous positions               (interpolation)
//!   without contacts: one pass per body    (forces, integrate, speed limits)
//!   with contacts:
//!     find contacts                        (ContactWorld::begin_step)
//!     substeps h = dt / n:
//!       integrate velocities, hold sleepers, warm start, solve,
//!       integrate positions, relax
//!     restitution, store separations, clamp speeds
//!     record events and sleep              (ContactWorld::end_step)
//!   clear forces
//! ```
//!
//! [`World::active_stages`] and [`World::contact_stages`] read the same
//! plan the step runs, so the list a user reads is the list that runs.

use crate::bodies::{SpeedLimits, flush_subnormal};
use crate::contact_world::{ContactWorld, StepParams};
use crate::forces::{BodyParams, Dissipation, Drive};
use crate::integrator::{Forces, integrate_body};
use crate::kernel::PointMassKernel;
use crate::parallel::for_chunks;
use crate::solver::{self, Motion, SolverParams};
use crate::world::World;
use crate::{ContactSettings, ForceModel, Integrator, WorldSettings};
use glam::Vec2;
use std::sync::Arc;

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
    /// The game's own [`ForceModel`]s.
    CustomForces,
    /// Quadratic drag.
    QuadraticDrag,
    /// Linear drag.
    LinearDrag,
    /// Top-down surface friction.
    SurfaceFriction,
    /// Integration of velocities and positions with the given method.
    Integrate(Integrator),
    /// Broad phase, narrow phase and the contact solver (its own stages:
    /// [`World::contact_stages`]).
    Contacts,
    /// Minimum-speed snap and maximum-speed clamp.
    SpeedLimits,
}

/// One stage of the contact step, in the order [`World::contact_stages`]
/// lists them: the first six run in every substep, the last three once
/// after the substeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactStage {
    /// Forces turned into new velocities over the substep.
    IntegrateVelocities,
    /// Sleeping bodies keep zero velocity (only while some body sleeps).
    HoldSleepers,
    /// The last substep's impulses applied again (warm starting).
    WarmStart,
    /// Gauss-Seidel passes over the contacts: friction, normal, push.
    Solve,
    /// Speed limits, then positions moved by velocity plus push.
    IntegratePositions,
    /// Velocity passes at the new positions.
    Relax,
    /// Contacts hit fast enough bounce (only while some body bounces).
    Restitution,
    /// Each contact's separation at the end of the step, for queries.
    StoreSeparations,
    /// Minimum-speed snap and maximum-speed clamp of the final velocities.
    ClampSpeeds,
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
            (f.quadratic_drag.is_some(), Stage::QuadraticDrag),
            (f.linear_drag.is_some(), Stage::LinearDrag),
            (f.surface_friction.is_some(), Stage::SurfaceFriction),
        ];
        stages.extend(models.iter().filter(|(on, _)| *on).map(|(_, s)| *s));
        stages.push(Stage::Integrate(world.settings().integrator));
        if self.contacts.is_some() {
            stages.push(Stage::Contacts);
        }
        if self.limits.is_some() {
            stages.push(Stage::SpeedLimits);
        }
        stages
    }
}

/// What the substeps of a contact step run.
struct SubstepPlan {
    /// Substeps to run: none when every body sleeps (nothing would move).
    substeps: u32,
    /// The velocity kernel of the common case (no speed limits: they are
    /// applied with the positions).
    kernel: Option<PointMassKernel>,
    /// Some body sleeps: sleeping bodies are held still.
    hold_sleepers: bool,
    /// The integrator makes position corrections (all but semi-implicit
    /// Euler), kept per body between the velocity and position stages.
    corrects: bool,
    limits: Option<Option<SpeedLimits>>,
    solver: SolverParams,
    /// Some body bounces.
    restitution: bool,
}

impl SubstepPlan {
    fn new(world: &World, settings: &ContactSettings, dt: f32, any_asleep: bool) -> Self {
        let all_asleep = any_asleep && world.dynamic.sleep.iter().all(|s| s.is_asleep());
        Self {
            substeps: if all_asleep { 0 } else { settings.substeps },
            kernel: world.kernel(None),
            hold_sleepers: any_asleep,
            corrects: world.settings().integrator != Integrator::SemiImplicitEuler,
            limits: world.speed_limits(),
            solver: SolverParams {
                h: dt / settings.substeps as f32,
                warm_starting: settings.warm_starting,
                iterations: settings.iterations,
                relax_iterations: settings.relax_iterations,
                position_correction: settings.position_correction,
                push_out_speed: settings.push_out_speed,
                slop: settings.slop,
                restitution_threshold: settings.restitution_threshold,
            },
            restitution: world.bouncy > 0,
        }
    }

    fn stages(&self) -> Vec<ContactStage> {
        use ContactStage::*;
        let s = &self.solver;
        let steps = [
            (self.substeps > 0, IntegrateVelocities),
            (self.substeps > 0 && self.hold_sleepers, HoldSleepers),
            (self.substeps > 0 && s.warm_starting, WarmStart),
            (self.substeps > 0, Solve),
            (self.substeps > 0, IntegratePositions),
            (self.substeps > 0 && s.relax_iterations > 0, Relax),
            (self.restitution, Restitution),
            (true, StoreSeparations),
            (self.limits.is_some(), ClampSpeeds),
        ];
        steps
            .iter()
            .filter(|(on, _)| *on)
            .map(|(_, s)| *s)
            .collect()
    }
}

impl World {
    /// The stages [`step`](Self::step) runs with the current settings and
    /// bodies, in order.
    pub fn active_stages(&self) -> Vec<Stage> {
        self.plan().stages(self)
    }

    /// The stages of the contact step with the current settings and
    /// bodies, in order (see [`ContactStage`]); empty when the contact
    /// stage does not run.
    pub fn contact_stages(&self) -> Vec<ContactStage> {
        let Some(settings) = self.plan().contacts else {
            return Vec::new();
        };
        let any_asleep = match &self.contacts {
            Some(cw) => cw.sleeping.any(&self.dynamic),
            None => false,
        };
        SubstepPlan::new(self, &settings, 1.0, any_asleep).stages()
    }

    fn plan(&self) -> StepPlan {
        StepPlan {
            store_previous: self.settings().interpolation,
            contacts: self.contact_settings(),
            limits: self.speed_limits(),
        }
    }

    /// Advances the world by `dt` seconds, stage by stage; each stage runs
    /// only if the settings and bodies ask for it ([`active_stages`](Self::active_stages)):
    ///
    /// 1. store previous positions (interpolation);
    /// 2. without contacts, one pass per body: integrate velocity with every
    ///    active force model, clamp speed, integrate position;
    /// 3. with contacts, broad and narrow phase, then `substeps` times:
    ///    integrate velocities, warm start, solve contacts, clamp speeds,
    ///    integrate positions, relax; then restitution and a last clamp
    ///    ([`contact_stages`](Self::contact_stages));
    /// 4. clear force accumulators.
    ///
    /// Run it from a fixed-timestep loop (`passo-loop`) with a constant `dt`:
    /// a variable `dt` makes the result depend on the frame rate.
    ///
    /// # Panics
    /// If `dt` is not finite and > 0: a zero, negative or NaN timestep is a
    /// programming error, not a state the world can be in.
    pub fn step(&mut self, dt: f32) {
        assert!(
            dt.is_finite() && dt > 0.0,
            "World::step: dt must be finite and > 0 seconds, got {dt}"
        );
        let plan = self.plan();
        if plan.store_previous {
            self.dynamic.prev_pos.copy_from_slice(&self.dynamic.pos);
        }
        match plan.contacts {
            Some(contacts) => self.step_with_contacts(dt, &contacts),
            None => {
                // Sleeping belongs to the contact stage: without it, no body
                // sleeps (the idle step wakes them all).
                if let Some(cw) = &mut self.contacts {
                    cw.idle_step(&mut self.dynamic, &self.statics);
                }
                self.step_bodies(dt, plan.limits);
            }
        }
        self.clear_forces();
        self.stats.steps += 1;
    }

    /// The contact settings if the contact stage runs: contacts are on, a
    /// shaped dynamic body exists and something else is shaped.
    fn contact_settings(&self) -> Option<ContactSettings> {
        let contacts = self.settings().contacts?;
        (self.shaped_dynamic > 0 && self.shaped_dynamic + self.shaped_static >= 2)
            .then_some(contacts)
    }

    /// The fast kernel for the current settings, if it applies.
    fn kernel(&self, limits: Option<Option<SpeedLimits>>) -> Option<PointMassKernel> {
        let settings = self.settings();
        PointMassKernel::new(
            &settings.forces,
            settings.integrator,
            settings.force_form,
            !self.custom.is_empty() || self.game_friction,
            limits,
        )
    }

    /// Integrates velocities, clamps speeds and moves bodies, one body at a
    /// time: a single pass over the arrays.
    fn step_bodies(&mut self, dt: f32, limits: Option<Option<SpeedLimits>>) {
        if let Some(kernel) = self.kernel(limits) {
            self.stats.non_finite_resets += kernel.run(&mut self.dynamic, dt, self.parallel);
            return;
        }
        let integrator = self.settings().integrator;
        let forces = forces(self.settings(), &self.custom, self.game_friction);
        let (pos, vel, arrays) = self.dynamic.split();
        let resets = for_chunks(self.parallel, (pos, vel), |offset, (pos, vel)| {
            let mut resets = 0;
            for (k, (p, v)) in pos.iter_mut().zip(vel.iter_mut()).enumerate() {
                let i = offset + k;
                let params = arrays.params(i);
                let (mut nv, c) =
                    integrate_velocity(integrator, &forces, *p, *v, &params, dt, &mut resets);
                if let Some(uniform) = limits {
                    uniform.unwrap_or(arrays.limits[i]).apply(&mut nv);
                }
                *v = nv;
                *p += nv * dt + c;
            }
            resets
        });
        self.stats.non_finite_resets += resets;
    }

    /// The contact step: find the contacts, run the substeps, finish, and
    /// record what happened.
    fn step_with_contacts(&mut self, dt: f32, settings: &ContactSettings) {
        let mut cw = self
            .contacts
            .take()
            .unwrap_or_else(|| Box::new(ContactWorld::new()));
        if std::mem::take(&mut self.statics_dirty) {
            cw.statics_changed();
        }
        if !settings.sleeping {
            cw.wake_all(&mut self.dynamic);
        }
        let params = StepParams {
            gravity: self.settings().forces.gravity.unwrap_or(Vec2::ZERO),
            dt,
            h: dt / settings.substeps as f32,
            parallel: self.parallel,
        };
        cw.begin_step(&mut self.dynamic, &self.statics, settings, &params);
        let plan = SubstepPlan::new(self, settings, dt, cw.sleeping.any(&self.dynamic));
        let mut correction = std::mem::take(&mut self.correction);
        if plan.corrects {
            correction.clear();
            correction.resize(self.dynamic.len(), Vec2::ZERO);
        }
        let mut resets = 0;
        for _ in 0..plan.substeps {
            resets += self.integrate_velocities(&plan, &mut correction);
            if plan.hold_sleepers {
                self.hold_sleepers(&mut correction, plan.corrects);
            }
            self.solve(&mut cw, &plan);
            self.integrate_positions(&mut cw.motion, &plan, &correction);
            self.relax(&mut cw, &plan);
        }
        self.finish_contacts(&mut cw, &plan);
        cw.end_step(
            &mut self.dynamic,
            &self.statics,
            settings.sleeping.then_some(dt),
        );
        self.contacts = Some(cw);
        self.correction = correction;
        self.stats.non_finite_resets += resets;
    }

    /// Substep stage: forces turned into velocities over `h`; the
    /// multi-stage integrators also leave a position correction.
    fn integrate_velocities(&mut self, plan: &SubstepPlan, correction: &mut [Vec2]) -> u64 {
        let (h, parallel) = (plan.solver.h, self.parallel);
        if let Some(kernel) = &plan.kernel {
            return kernel.velocities(&mut self.dynamic, h, parallel);
        }
        let integrator = self.settings().integrator;
        let forces = forces(self.settings(), &self.custom, self.game_friction);
        let (pos, vel, arrays) = self.dynamic.split();
        let pos: &[Vec2] = pos;
        let velocity = |i: usize, v: Vec2, resets: &mut u64| {
            integrate_velocity(integrator, &forces, pos[i], v, &arrays.params(i), h, resets)
        };
        if plan.corrects {
            for_chunks(parallel, (vel, correction), |offset, (vel, correction)| {
                let mut resets = 0;
                for (k, (v, c)) in vel.iter_mut().zip(correction.iter_mut()).enumerate() {
                    (*v, *c) = velocity(offset + k, *v, &mut resets);
                }
                resets
            })
        } else {
            for_chunks(parallel, vel, |offset, vel| {
                let mut resets = 0;
                for (k, v) in vel.iter_mut().enumerate() {
                    *v = velocity(offset + k, *v, &mut resets).0;
                }
                resets
            })
        }
    }

    /// Substep stage: sleeping bodies hold still (no forces, no correction).
    fn hold_sleepers(&mut self, correction: &mut [Vec2], corrects: bool) {
        let b = &mut self.dynamic;
        for (i, (v, s)) in b.vel.iter_mut().zip(&b.sleep).enumerate() {
            if s.is_asleep() {
                *v = Vec2::ZERO;
                if corrects {
                    correction[i] = Vec2::ZERO;
                }
            }
        }
    }

    /// Substep stages: warm start (with the push impulses cleared), then
    /// the Gauss-Seidel passes with the push.
    fn solve(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan) {
        let ContactWorld { solved, motion, .. } = cw;
        motion.push.fill(Vec2::ZERO);
        let mut bodies = motion.bodies(&mut self.dynamic.vel);
        solver::begin_substep(&mut solved.rows, &mut bodies, plan.solver.warm_starting);
        for _ in 0..plan.solver.iterations {
            solver::solve(&mut solved.rows, &mut bodies, &plan.solver, true);
        }
    }

    /// Substep stage: speed limits, then positions moved by velocity plus
    /// push (and the integrator's correction), and each body's displacement
    /// since the step began.
    fn integrate_positions(
        &mut self,
        motion: &mut Motion,
        plan: &SubstepPlan,
        correction: &[Vec2],
    ) {
        let (h, limits, corrects) = (plan.solver.h, plan.limits, plan.corrects);
        let (pos, vel, arrays) = self.dynamic.split();
        let (push, start) = (&motion.push[..], &motion.start[..]);
        let parts = (pos, vel, &mut motion.delta[..]);
        for_chunks(self.parallel, parts, |offset, (pos, vel, delta)| {
            let bodies = pos.iter_mut().zip(vel.iter_mut()).zip(delta.iter_mut());
            for (k, ((p, v), d)) in bodies.enumerate() {
                let i = offset + k;
                if let Some(uniform) = limits {
                    uniform.unwrap_or(arrays.limits[i]).apply(v);
                }
                // Semi-implicit Euler adds an exact zero here, as the
                // no-contact path does: the same bits either way.
                let c = if corrects { correction[i] } else { Vec2::ZERO };
                *p += (*v + push[i]) * h + c;
                *d = *p - start[i];
            }
            0
        });
    }

    /// Substep stage: velocity passes at the new positions.
    fn relax(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan) {
        let ContactWorld { solved, motion, .. } = cw;
        let mut bodies = motion.bodies(&mut self.dynamic.vel);
        for _ in 0..plan.solver.relax_iterations {
            solver::solve(&mut solved.rows, &mut bodies, &plan.solver, false);
        }
    }

    /// After the substeps: restitution, each contact's final separation,
    /// and the speed limits of the final velocities.
    fn finish_contacts(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan) {
        let ContactWorld { solved, motion, .. } = cw;
        let b = &mut self.dynamic;
        let mut bodies = motion.bodies(&mut b.vel);
        if plan.restitution {
            solver::restitution(
                &mut solved.rows,
                &solved.infos,
                &mut bodies,
                plan.solver.restitution_threshold,
            );
        }
        solver::store_separations(&solved.rows, &mut solved.infos, &bodies);
        if let Some(uniform) = plan.limits {
            for (v, limits) in b.vel.iter_mut().zip(&b.limits) {
                uniform.unwrap_or(*limits).apply(v);
            }
        }
    }

    fn clear_forces(&mut self) {
        self.dynamic.force.fill(Vec2::ZERO);
        if self.game_friction {
            self.dynamic.friction_force.fill(0.0);
            self.game_friction = false;
        }
    }
}

/// The forces of a step, constants hoisted out of the body loop.
fn forces<'a>(
    settings: &WorldSettings,
    custom: &'a [Arc<dyn ForceModel>],
    game_friction: bool,
) -> Forces<'a> {
    Forces::new(
        Drive::new(&settings.forces, custom),
        Dissipation::new(&settings.forces, game_friction),
        settings.force_form,
        settings.integrator,
    )
}

/// One body's new velocity and position correction over `h`. A non-finite
/// result (a broken custom force, an overflow) drops the body's motion for
/// this step and counts a reset.
#[inline(always)]
fn integrate_velocity(
    integrator: Integrator,
    forces: &Forces<'_>,
    p: Vec2,
    v: Vec2,
    params: &BodyParams,
    h: f32,
    resets: &mut u64,
) -> (Vec2, Vec2) {
    let (v, c) = integrate_body(integrator, forces, p, v, params, h);
    guard_finite(v, c, resets)
}

/// Drops a step that produced a non-finite velocity or correction, or a
/// speed whose square overflows `f32` (over 1.8e19 m/s): the body stays
/// where it was with zero velocity, and the reset is counted. Subnormal
/// velocity components are flushed to zero.
#[inline(always)]
fn guard_finite(v: Vec2, c: Vec2, resets: &mut u64) -> (Vec2, Vec2) {
    if v.length_squared().is_finite() && c.is_finite() {
        (flush_subnormal(v), c)
    } else {
        *resets += 1;
        (Vec2::ZERO, Vec2::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::DEFAULT_MAX_SPEED;
    use crate::{BodyDef, CentralGravity, ForceModels, QuadraticDrag};

    fn ball(x: f32) -> BodyDef {
        BodyDef::dynamic(Vec2::new(x, 0.0))
    }

    #[test]
    fn forces_accumulate_and_are_cleared_after_each_step() {
        let mut world = World::new(WorldSettings {
            forces: ForceModels::none(),
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
        world.apply_force(id, Vec2::new(1.0, 0.0)).unwrap();
        world.apply_force(id, Vec2::new(3.0, 2.0)).unwrap();
        assert_eq!(world.body(id).unwrap().force, Vec2::new(4.0, 2.0));
        world.step(0.5);
        // a = F / m = (2, 1); v = a dt.
        assert_eq!(world.body(id).unwrap().velocity, Vec2::new(1.0, 0.5));
        assert_eq!(world.body(id).unwrap().force, Vec2::ZERO);
        world.step(0.5);
        assert_eq!(world.body(id).unwrap().velocity, Vec2::new(1.0, 0.5));
    }

    #[test]
    #[should_panic(expected = "dt must be finite and > 0 seconds, got 0")]
    fn zero_timestep_panics_with_a_clear_message() {
        World::default().step(0.0);
    }

    #[test]
    #[should_panic(expected = "dt must be finite and > 0 seconds, got NaN")]
    fn nan_timestep_panics_with_a_clear_message() {
        World::default().step(f32::NAN);
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
        world
            .apply_force(id, Vec2::new(f32::MAX, f32::MAX))
            .unwrap();
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
        world.apply_force(id, Vec2::new(1e30, 1e30)).unwrap();
        world.step(1.0);
        assert_eq!(world.body(id).unwrap().velocity, Vec2::ZERO);
        assert_eq!(world.stats().non_finite_resets, 1);

        // A large but sane velocity is clamped to exactly the maximum speed.
        let id = world.add_body(ball(0.0)).unwrap();
        world.apply_force(id, Vec2::new(3e6, 4e6)).unwrap();
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
}
