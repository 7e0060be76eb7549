//! The contact step: a plan of its stages, and a function for each. The
//! step runs the plan's list in order; the tick as a whole is described
//! in `step/mod.rs`.

use crate::body::store::{DynamicBodies, SpeedLimits};
use crate::columns::ColumnsMut;
use crate::constants::DEEP_OVERLAP;
use crate::contact_world::{ContactWorld, StepParams};
use crate::forces::integrator::integrate_velocity;
use crate::forces::kernel::PointMassKernel;
use crate::parallel::for_chunks;
use crate::solver::colouring::Pass;
use crate::solver::motion::{Homes, Motion, Start};
use crate::solver::scalar::{self, BodyState, SolverParams};
use crate::world::{World, step_forces};
use crate::{ContactSettings, Integrator};
use glam::Vec2;

/// One stage of the contact step, in the order [`World::contact_stages`]
/// lists them: the first eight run in every substep, the last five once
/// after the substeps. Joints are solved in the warm start, solve and
/// relax stages, before the contacts (as Box2D v3 does). The step runs the stages from that list, one
/// function each.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactStage {
    /// Forces turned into new velocities over the substep.
    IntegrateVelocities,
    /// Sleeping bodies keep zero velocity (only while some body sleeps).
    HoldSleepers,
    /// Kinematic bodies keep their own velocity (only with some).
    HoldKinematic,
    /// The last substep's impulses applied again (warm starting): from
    /// the cache in the first substep, then each body's velocity change in
    /// the last substep (the same sum, with no pass over the contacts or
    /// joints).
    WarmStart,
    /// Gauss-Seidel passes over the joints, with their drift correction,
    /// then over the contacts: normal, friction, push (after the pass that
    /// clears the pushes and measures the separations, when there is no
    /// warm start to do it).
    Solve,
    /// The contacts that hold bodies up against gravity solved once more,
    /// layer by layer from the ground up, each as if its lower body could
    /// not move: shock propagation (only with
    /// [`ContactSettings::shock_propagation`] and gravity). No body then
    /// sinks into the one under it, whatever their masses.
    PropagateShock,
    /// Speed limits, then positions moved by velocity plus push.
    IntegratePositions,
    /// Velocity passes over the joints and contacts at the new positions.
    Relax,
    /// Bodies that moved farther than their speculative contacts reach
    /// swept along their paths and stopped at their first impact (only
    /// with continuous collision).
    SweepFastBodies,
    /// Contacts hit fast enough bounce (only while some body bounces).
    Restitution,
    /// Each contact's separation at the end of the step, for queries.
    StoreSeparations,
    /// Each joint's impulses kept for the next step's warm start, its force
    /// measured, and the joints whose force went over their break force
    /// removed (only with joints that can move something).
    StoreJoints,
    /// Minimum-speed snap and maximum-speed clamp of the final velocities.
    ClampSpeeds,
}

impl ContactStage {
    /// Whether the stage runs in each substep (rather than once after
    /// them).
    pub fn in_substep(self) -> bool {
        use ContactStage::*;
        matches!(
            self,
            IntegrateVelocities
                | HoldSleepers
                | HoldKinematic
                | WarmStart
                | Solve
                | PropagateShock
                | IntegratePositions
                | Relax
        )
    }

    /// Whether the stage works on the solver's copy of the velocities
    /// (see `Motion::load`) rather than on the body arrays.
    fn on_solver_copy(self) -> bool {
        use ContactStage::*;
        matches!(
            self,
            WarmStart | Solve | PropagateShock | IntegratePositions | Relax
        )
    }
}

/// The stages a contact step runs, in order: a list of fixed size, so a
/// step allocates nothing to make it.
#[derive(Clone, Copy, Debug)]
struct StageList {
    stages: [ContactStage; 13],
    len: usize,
}

impl StageList {
    /// No stage.
    const EMPTY: Self = Self {
        stages: [ContactStage::Solve; 13],
        len: 0,
    };

    /// The stages whose condition holds, in order.
    fn new(steps: [(bool, ContactStage); 13]) -> Self {
        let mut list = Self::EMPTY;
        for (on, stage) in steps {
            if on {
                list.stages[list.len] = stage;
                list.len += 1;
            }
        }
        list
    }

    fn all(&self) -> &[ContactStage] {
        &self.stages[..self.len]
    }

    /// The substep's stages on the body arrays, then those on the
    /// solver's copy, then the stages after the substeps.
    fn parts(&self) -> (&[ContactStage], &[ContactStage], &[ContactStage]) {
        let all = self.all();
        let substep = all.partition_point(|s| s.in_substep());
        let (substep, after) = all.split_at(substep);
        let on_bodies = substep.partition_point(|s| !s.on_solver_copy());
        let (on_bodies, on_copy) = substep.split_at(on_bodies);
        (on_bodies, on_copy, after)
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
    /// Some body is kinematic: it keeps its own velocity.
    hold_kinematic: bool,
    /// The integrator makes position corrections (all but semi-implicit
    /// Euler), kept per body between the velocity and position stages.
    corrects: bool,
    limits: Option<Option<SpeedLimits>>,
    solver: SolverParams,
    /// Some body bounces.
    restitution: bool,
    /// Continuous collision: fast bodies are swept.
    sweep: bool,
    /// Shock propagation: on, and there is gravity to hold bodies up
    /// against.
    shock: bool,
    /// The substeps after the first warm start by replaying each body's
    /// velocity change of the last substep (see [`Start::Replay`]): with a
    /// warm start, with a relax pass to measure the separations (the warm
    /// start pass does otherwise), and with a substep after the first.
    replay: bool,
    /// Some joint can move a body this step.
    joints: bool,
    /// The stages to run, in order.
    stages: StageList,
}

impl SubstepPlan {
    /// The plan of a step of `dt` with `settings`. `any_asleep`: some body
    /// sleeps. `carry_push`: a deep pile carries its push from substep to
    /// substep (see `DeepPiles::find`; only with a warm start).
    fn new(
        world: &World,
        settings: &ContactSettings,
        dt: f32,
        any_asleep: bool,
        carry_push: bool,
    ) -> Self {
        let all_asleep = any_asleep && world.dynamic.sleep.iter().all(|s| s.is_asleep());
        let substeps = if all_asleep { 0 } else { settings.substeps };
        let mut plan = Self {
            substeps,
            kernel: world.kernel(None),
            hold_sleepers: any_asleep,
            hold_kinematic: !world.dynamic.kinematic.is_empty(),
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
                carry_push,
            },
            restitution: world.census.bouncy > 0 || world.hooks.is_some(),
            sweep: settings.continuous,
            shock: settings.shock_propagation
                && world
                    .settings()
                    .forces
                    .gravity
                    .is_some_and(|g| g != Vec2::ZERO),
            // Not with joints: their directions turn with their bodies, so
            // a substep's change replayed along the last one's directions
            // pushed a pendulum along its swing and added energy.
            replay: settings.warm_starting
                && settings.relax_iterations > 0
                && substeps > 1
                && world.joints.count == 0,
            joints: !world.joint_rows.rows.is_empty() || !world.joint_rows.rods.is_empty(),
            // Filled in from the rest of the plan just below.
            stages: StageList::EMPTY,
        };
        plan.stages = plan.stage_list();
        plan
    }

    fn stage_list(&self) -> StageList {
        use ContactStage::*;
        let s = &self.solver;
        StageList::new([
            (self.substeps > 0, IntegrateVelocities),
            (self.substeps > 0 && self.hold_sleepers, HoldSleepers),
            (self.substeps > 0 && self.hold_kinematic, HoldKinematic),
            (self.substeps > 0 && s.warm_starting, WarmStart),
            (self.substeps > 0, Solve),
            (self.substeps > 0 && self.shock, PropagateShock),
            (self.substeps > 0, IntegratePositions),
            (self.substeps > 0 && s.relax_iterations > 0, Relax),
            (self.substeps > 0 && self.sweep, SweepFastBodies),
            (self.restitution, Restitution),
            (true, StoreSeparations),
            (self.joints, StoreJoints),
            (self.limits.is_some(), ClampSpeeds),
        ])
    }
}

impl World {
    /// The stages of the contact step with the current settings and
    /// bodies, in order (see [`ContactStage`]); empty when the contact
    /// stage does not run.
    pub fn contact_stages(&self) -> Vec<ContactStage> {
        let Some(settings) = self.contact_settings() else {
            return Vec::new();
        };
        let any_asleep = match &self.contacts {
            Some(cw) => cw.sleeping.any(&self.dynamic),
            None => false,
        };
        let plan = SubstepPlan::new(self, &settings, 1.0, any_asleep, false);
        plan.stages.all().to_vec()
    }

    /// The contact step: find the contacts, run the substeps, finish, and
    /// record what happened.
    pub(crate) fn step_with_contacts(&mut self, dt: f32, settings: &ContactSettings) {
        // A large world steps on a worker of the thread pool: the stages hand
        // work to the other workers dozens of times a step (the regions'
        // passes, the chunks), which costs a few microseconds from a worker
        // and ten times that from a thread outside the pool. (On the pool
        // or not, the bits are the same: only the cost differs.)
        #[cfg(feature = "parallel")]
        if self.parallel && self.dynamic.len() >= crate::constants::PARALLEL_MIN_ITEMS {
            crate::parallel::on_pool(|| self.step_with_contacts_here(dt, settings));
            return;
        }
        self.step_with_contacts_here(dt, settings);
    }

    /// [`step_with_contacts`](Self::step_with_contacts) on this thread.
    fn step_with_contacts_here(&mut self, dt: f32, settings: &ContactSettings) {
        let mut cw = self
            .contacts
            .take()
            .unwrap_or_else(|| Box::new(ContactWorld::new()));
        if cw.switches != self.switches {
            cw.set_switches(self.switches);
        }
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
            // (A wrong count costs time, never a proxy: `Proxies::add_all`
            // finds a shapeless body itself and gives up.)
            all_shaped: self.census.shaped_dynamic == self.dynamic.len(),
        };
        cw.relocate_last_contacts(&self.dynamic, &self.statics, |id| self.collider_of(id));
        cw.begin_step(&mut self.dynamic, &self.statics, settings, &params);
        // (These two tests only skip work: with no joint, or no conveyor,
        // the calls change nothing.)
        if self.joints.count > 0 {
            let rows = &mut self.joint_rows;
            if std::mem::take(&mut rows.apart_stale) {
                self.joints.apart(&mut rows.apart);
            }
            cw.drop_joined(&rows.apart);
        }
        if self.census.conveyors > 0 {
            cw.apply_conveyors(|id| self.meta_of(id).and_then(|m| m.conveyor));
        }
        if let Some(hooks) = self.hooks.clone() {
            let info = |id| crate::PairInfo {
                id,
                user_data: self.body_user_data(id),
            };
            cw.run_hooks(&*hooks, &self.dynamic, info, params.gravity, params.h);
        }
        if cw.crowded() > 0 {
            self.stats.crowded_steps = self.stats.crowded_steps.saturating_add(1);
        }
        let carry_push = settings.warm_starting
            && cw.motion.piles.find(
                &cw.solved.rows,
                self.dynamic.len(),
                DEEP_OVERLAP,
                self.parallel,
            );
        let any_asleep = cw.sleeping.any(&self.dynamic);
        self.prepare_joints(params.h, settings.warm_starting);
        let plan = SubstepPlan::new(self, settings, dt, any_asleep, carry_push);
        // Joints read and write any body's state: the contacts stay in one
        // region, whose states all live in the solver's array. (Split or
        // not, the passes give the same bits: see `regions`.)
        cw.regions.no_split = self.joints.count > 0;
        cw.regions.build(
            &cw.solved.rows,
            &cw.motion.start,
            &cw.motion.piles.deep,
            // (Wrong, it costs a second build: see `ContactRegions::build`.)
            plan.hold_sleepers || plan.hold_kinematic,
            self.parallel,
        );
        if plan.shock {
            (cw.supports).build(
                &cw.solved.rows,
                params.gravity,
                self.dynamic.len(),
                &cw.regions,
            );
        } else {
            cw.supports.clear();
        }
        if plan.hold_kinematic {
            self.note_kinematic_motion();
        }
        let mut correction = std::mem::take(&mut self.correction);
        if plan.corrects {
            correction.clear();
            correction.resize(self.dynamic.len(), Vec2::ZERO);
        }
        let mut resets = 0;
        let (on_bodies, on_copy, after) = plan.stages.parts();
        let body_forces = self.has_body_forces();
        for substep in 0..plan.substeps {
            if body_forces {
                // At the substep's positions and velocities: a force
                // frozen over the step's substeps adds energy to what it
                // holds up (a floating crate bobbed for ever).
                self.add_body_forces(plan.solver.h, substep == 0);
            }
            for &stage in on_bodies {
                resets += self.run_on_bodies(stage, &plan, &mut correction);
            }
            // From here to the end of the substep the passes work on the
            // solver's copy of the velocities (see `Motion::load`).
            let start = match (plan.replay, substep) {
                (false, _) => Start::Plain,
                (true, 0) => Start::Track,
                (true, _) => Start::Replay,
            };
            let far = cw.regions.far_states();
            cw.motion
                .load(self.dynamic.vel.view(), start, self.parallel, far);
            let pass = SubstepPass {
                // The bodies moved since the separations were last measured
                // unless this is the first substep or the relax stage
                // measured. (Measuring again where nothing moved gives the
                // same gaps.)
                moved: substep > 0 && plan.solver.relax_iterations == 0,
                replayed: start == Start::Replay,
            };
            for &stage in on_copy {
                self.run_on_copy(stage, &mut cw, &plan, pass, &correction);
            }
            let far = cw.regions.far_states().map(|(homes, far)| (homes, &*far));
            cw.motion
                .unload(self.dynamic.vel.view_mut(), plan.replay, self.parallel, far);
        }
        cw.regions.store(&mut cw.solved.rows, self.parallel);
        for &stage in after {
            self.run_after_substeps(stage, &mut cw, &plan);
        }
        // (Valid inputs leave nothing to put back here, so through the step
        // no test sees this count; `put_back_non_finite`'s own test does.)
        resets += put_back_non_finite(&mut self.dynamic, &mut cw);
        // Only a body gone non-finite can spoil a joint's impulses. (No
        // valid scene spoils them before its body is reset at the next
        // substep's integration: no test reaches this.)
        if resets > 0 {
            self.joints.drop_non_finite();
        }
        self.may_rest |= settings.sleeping;
        cw.end_step(
            &mut self.dynamic,
            &self.statics,
            &self.joint_rows.links,
            settings.sleeping.then_some((dt, settings.slop)),
            self.stats.steps.saturating_add(1),
            self.parallel,
        );
        self.contacts = Some(cw);
        self.correction = correction;
        self.stats.non_finite_resets = self.stats.non_finite_resets.saturating_add(resets);
    }

    /// Runs a substep stage on the body arrays; returns the non-finite
    /// velocities it put back.
    fn run_on_bodies(
        &mut self,
        stage: ContactStage,
        plan: &SubstepPlan,
        correction: &mut [Vec2],
    ) -> u64 {
        use ContactStage::*;
        match stage {
            IntegrateVelocities => return self.integrate_velocities(plan, correction),
            HoldSleepers => self.hold_sleepers(correction, plan.corrects),
            HoldKinematic => self.hold_kinematic(correction, plan.corrects),
            _ => unreachable!("{stage:?} does not run on the body arrays"),
        }
        0
    }

    /// Runs a substep stage on the solver's copy of the velocities.
    fn run_on_copy(
        &mut self,
        stage: ContactStage,
        cw: &mut ContactWorld,
        plan: &SubstepPlan,
        pass: SubstepPass,
        correction: &[Vec2],
    ) {
        use ContactStage::*;
        match stage {
            WarmStart => self.warm_start(cw, plan, pass),
            Solve => self.solve(cw, plan, pass),
            PropagateShock => self.propagate_shock(cw, plan),
            IntegratePositions => {
                let far = cw.regions.far_states();
                self.integrate_positions(&mut cw.motion, far, plan, correction);
            }
            Relax => self.relax(cw, plan),
            _ => unreachable!("{stage:?} does not run on the solver's copy"),
        }
    }

    /// Runs a stage after the substeps.
    fn run_after_substeps(
        &mut self,
        stage: ContactStage,
        cw: &mut ContactWorld,
        plan: &SubstepPlan,
    ) {
        use ContactStage::*;
        match stage {
            SweepFastBodies => {
                let stops = cw.sweep_fast_bodies(&mut self.dynamic, &self.statics, self.parallel);
                self.stats.swept_stops = self.stats.swept_stops.saturating_add(stops as u64);
            }
            Restitution => self.restitution(cw, plan),
            StoreSeparations => self.store_separations(cw),
            StoreJoints => self.store_joints(),
            ClampSpeeds => self.clamp_speeds(plan),
            _ => unreachable!("{stage:?} runs in the substeps"),
        }
    }

    /// Substep stage: forces turned into velocities over `h`; the
    /// multi-stage integrators also leave a position correction.
    fn integrate_velocities(&mut self, plan: &SubstepPlan, correction: &mut [Vec2]) -> u64 {
        let (h, parallel) = (plan.solver.h, self.parallel);
        if let Some(kernel) = &plan.kernel {
            return kernel.velocities(&mut self.dynamic, h, parallel);
        }
        let integrator = self.settings().integrator;
        let forces = step_forces(&self.settings, &self.custom, self.game_friction);
        let (pos, vel, arrays) = self.dynamic.split();
        let pos = pos.as_ref();
        // Everything it reads is copied in, and each chunk takes a copy of
        // it: stores to the arrays cannot alias the hoisted constants, which
        // then stay in registers (see `step_bodies`).
        let velocity = move |i: usize, v: Vec2, resets: &mut u64| {
            integrate_velocity(
                integrator,
                &forces,
                pos.at(i),
                v,
                &arrays.params(i),
                h,
                resets,
            )
        };
        if plan.corrects {
            for_chunks(parallel, (vel, correction), |offset, (vel, correction)| {
                let (velocity, mut resets) = (velocity, 0);
                let (vx, vy) = vel.into_parts();
                let correction = &mut correction[..vx.len()];
                for k in 0..vx.len() {
                    let v = Vec2::new(vx[k], vy[k]);
                    let (v, c) = velocity(offset + k, v, &mut resets);
                    (vx[k], vy[k], correction[k]) = (v.x, v.y, c);
                }
                resets
            })
        } else {
            for_chunks(parallel, vel, |offset, vel| {
                let (velocity, mut resets) = (velocity, 0);
                let (vx, vy) = vel.into_parts();
                for k in 0..vx.len() {
                    let v = velocity(offset + k, Vec2::new(vx[k], vy[k]), &mut resets).0;
                    (vx[k], vy[k]) = (v.x, v.y);
                }
                resets
            })
        }
    }

    /// Substep stage: sleeping bodies hold still (no forces, no correction).
    fn hold_sleepers(&mut self, correction: &mut [Vec2], corrects: bool) {
        let b = &mut self.dynamic;
        for (i, s) in b.sleep.iter().enumerate() {
            if s.is_asleep() {
                b.vel.set(i, Vec2::ZERO);
                if corrects {
                    correction[i] = Vec2::ZERO;
                }
            }
        }
    }

    /// Substep stage: kinematic bodies keep the velocity they had when
    /// the step began (no forces, no correction; contacts cannot change
    /// it either, their inverse mass being zero).
    fn hold_kinematic(&mut self, correction: &mut [Vec2], corrects: bool) {
        let b = &mut self.dynamic;
        for (&i, &(_, v)) in b.kinematic.iter().zip(&self.held) {
            let i = i as usize;
            let v = if b.sleep[i].is_asleep() {
                Vec2::ZERO
            } else {
                v
            };
            b.vel.set(i, v);
            if corrects {
                correction[i] = Vec2::ZERO;
            }
        }
    }

    /// Substep stage: the last impulses applied again, the push impulses
    /// cleared (or carried in a deep pile) and the separations measured if
    /// the bodies moved since they last were. When the substep was
    /// replayed (see `Start::Replay`) the velocities are warm started
    /// already: the pass then only carries the push in a deep pile.
    fn warm_start(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan, pass: SubstepPass) {
        if plan.joints {
            let motion = &mut cw.motion;
            self.joint_rows.warm_start(&mut motion.state, &motion.delta);
        }
        if pass.fresh(plan) {
            // The first solve pass starts each push from zero instead.
            return;
        }
        let begin = SolverParams {
            warm_starting: !pass.replayed,
            ..plan.solver
        };
        let mut bodies = cw.motion.bodies();
        (cw.regions).run(&mut bodies, &Pass::Begin(begin, pass.moved), self.parallel);
    }

    /// Substep stage: the Gauss-Seidel passes with the push. Without a warm
    /// start, a first pass clears the pushes and measures the separations.
    fn solve(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan, pass: SubstepPass) {
        let ContactWorld {
            regions, motion, ..
        } = cw;
        let mut bodies = motion.bodies();
        if !plan.solver.warm_starting {
            regions.run(
                &mut bodies,
                &Pass::Begin(plan.solver, pass.moved),
                self.parallel,
            );
        }
        let fresh = pass.fresh(plan);
        let (first, solve) = (Pass::fresh(&plan.solver), Pass::solve(&plan.solver, true));
        for k in 0..plan.solver.iterations {
            if plan.joints {
                self.joint_rows.solve(bodies.state, bodies.delta, true);
            }
            let p = if fresh && k == 0 { &first } else { &solve };
            regions.run(&mut bodies, p, self.parallel);
        }
    }

    /// Substep stage: the contacts that hold bodies up solved once more,
    /// from the ground up, each with its lower body held still (see
    /// `solver::shock`).
    fn propagate_shock(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan) {
        let ContactWorld {
            regions,
            motion,
            supports,
            ..
        } = cw;
        let (mut bodies, replay) = motion.bodies_and_replay();
        let replay = plan.replay.then_some(replay);
        supports.run(regions, &mut bodies, &plan.solver, replay);
    }

    /// Substep stage: speed limits, then positions moved by velocity plus
    /// push (and the integrator's correction), and each body's displacement
    /// since the step began.
    fn integrate_positions(
        &mut self,
        motion: &mut Motion,
        far: Option<(&Homes, &mut [BodyState])>,
        plan: &SubstepPlan,
        correction: &[Vec2],
    ) {
        let (h, limits, corrects) = (plan.solver.h, plan.limits, plan.corrects);
        let (pos, _, arrays) = self.dynamic.split();
        let start = &motion.start[..];
        // The bodies' states, without the rest state after them.
        let state = &mut motion.state[..pos.len()];
        let parts = (pos, state, &mut motion.delta[..], &mut motion.replay[..]);
        // One loop for each kind of limit, chosen once: no test of the
        // kind in the loop over the bodies.
        let moves = Moves {
            h,
            correction: corrects.then_some(correction),
            start,
            replay: plan.replay,
        };
        let parallel = self.parallel;
        match limits {
            None => moves.run(parallel, parts, far, |_| None),
            Some(Some(uniform)) => moves.run(parallel, parts, far, |_| Some(uniform)),
            Some(None) => moves.run(parallel, parts, far, |i| Some(arrays.limits[i])),
        }
    }

    /// Substep stage: velocity passes at the new positions.
    fn relax(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan) {
        let ContactWorld {
            regions, motion, ..
        } = cw;
        let mut bodies = motion.bodies();
        // The first pass measures the separations at the new positions.
        let (first, rest) = (Pass::relax(&plan.solver), Pass::solve(&plan.solver, false));
        for k in 0..plan.solver.relax_iterations {
            if plan.joints {
                self.joint_rows.solve(bodies.state, bodies.delta, false);
            }
            let pass = if k == 0 { &first } else { &rest };
            regions.run(&mut bodies, pass, self.parallel);
        }
    }

    /// Stage after the substeps: contacts hit fast enough bounce.
    fn restitution(&mut self, cw: &mut ContactWorld, plan: &SubstepPlan) {
        let solved = &mut cw.solved;
        scalar::restitution(
            &mut solved.rows,
            &solved.infos,
            &mut self.dynamic.vel,
            plan.solver.restitution_threshold,
        );
    }

    /// Stage after the substeps: each contact's final separation.
    fn store_separations(&mut self, cw: &mut ContactWorld) {
        let ContactWorld { solved, motion, .. } = cw;
        scalar::store_separations(
            &solved.rows,
            &mut solved.infos,
            &motion.delta,
            self.parallel,
        );
    }

    /// The rows of the joints for a step of substep `h`.
    fn prepare_joints(&mut self, h: f32, warm: bool) {
        let mut rows = std::mem::take(&mut self.joint_rows);
        if self.joints.count > 0 {
            rows.prepare(&self.joints, h, warm, self.switches, |id| {
                self.joint_end(id)
            });
        } else {
            rows.rows.clear();
            rows.links.clear();
        }
        self.joint_rows = rows;
    }

    /// Stage after the substeps: each joint's impulses and force kept, and
    /// the joints that broke removed.
    fn store_joints(&mut self) {
        let mut broken = Vec::new();
        self.joint_rows
            .store(&mut self.joints, |slot| broken.push(slot));
        for slot in broken {
            let generation = self.joints.slots[slot as usize].generation;
            let id = crate::JointId {
                index: slot,
                generation,
            };
            let force = self.joints.get(id).map_or(0.0, |j| j.force);
            if let Some(def) = self.remove_joint(id) {
                (self.broken_joints).push(crate::BrokenJoint { id, def, force });
            }
        }
    }

    /// Stage after the substeps: the speed limits of the final velocities.
    fn clamp_speeds(&mut self, plan: &SubstepPlan) {
        let Some(uniform) = plan.limits else {
            return;
        };
        let b = &mut self.dynamic;
        for_chunks(
            self.parallel,
            (b.vel.view_mut(), &b.limits[..]),
            |_, (vel, limits)| {
                let (vx, vy) = vel.into_parts();
                for (k, limits) in limits[..vx.len()].iter().enumerate() {
                    let mut v = Vec2::new(vx[k], vy[k]);
                    uniform.unwrap_or(*limits).apply(&mut v);
                    (vx[k], vy[k]) = (v.x, v.y);
                }
                0
            },
        );
    }
}

/// What the solver stages of one substep need to know of it.
#[derive(Clone, Copy)]
struct SubstepPass {
    /// The bodies moved since the separations were last measured.
    moved: bool,
    /// The substep started from the replay of each body's velocity change
    /// (see `Start::Replay`): the warm start is in the velocities already.
    replayed: bool,
}

impl SubstepPass {
    /// Whether the warm start pass is left out: replayed, with no push to
    /// carry, the first solve pass starts each push from zero.
    fn fresh(self, plan: &SubstepPlan) -> bool {
        self.replayed && !plan.solver.carry_push
    }
}

/// Puts every dynamic body the step left with a non-finite position or
/// velocity back where the step began, at rest, and drops its contacts'
/// impulses (so neither the next step's warm start nor a snapshot carries
/// them); returns how many it put back. Only impulses that overflow `f32`
/// get here: the heaviest body allowed (10^30 kg) meeting something at
/// 10^9 m/s with the speed limit turned off. The common case is one pass
/// over the bodies with no branch.
fn put_back_non_finite(dynamic: &mut DynamicBodies, cw: &mut ContactWorld) -> u64 {
    let finite = |p: &Vec2, v: &Vec2| p.is_finite() & v.is_finite();
    let all_finite =
        (dynamic.pos.iter().zip(dynamic.vel.iter())).fold(true, |ok, (p, v)| ok & finite(&p, &v));
    if all_finite {
        return 0;
    }
    let mut resets = 0;
    for (i, start) in cw.motion.start.iter().enumerate() {
        if !finite(&dynamic.pos.at(i), &dynamic.vel.at(i)) {
            dynamic.pos.set(i, *start);
            dynamic.vel.set(i, Vec2::ZERO);
            resets += 1;
        }
    }
    for row in &mut cw.solved.rows {
        let impulses = [row.normal_impulse, row.tangent_impulse, row.push_impulse];
        if !impulses.iter().all(|x| x.is_finite()) || !row.max_normal_impulse.is_finite() {
            row.normal_impulse = 0.0;
            row.tangent_impulse = 0.0;
            row.push_impulse = 0.0;
            row.max_normal_impulse = 0.0;
        }
    }
    resets
}

/// What the position stage moves each body by: its velocity plus push
/// over the substep, and the integrator's correction.
struct Moves<'a> {
    h: f32,
    /// The integrator's corrections (all but semi-implicit Euler).
    correction: Option<&'a [Vec2]>,
    /// Positions at the start of the step.
    start: &'a [Vec2],
    /// The substeps replay the contacts' velocity changes: a change made by
    /// a speed limit is left out of them.
    replay: bool,
}

impl Moves<'_> {
    /// Applies each body's speed limits (`limit(i)`, if any; with the
    /// replay, a limit's change is taken out of the body's replayed
    /// change), then moves it, and keeps its displacement since the step
    /// began. `far`: while the step splits, each body's home and the second
    /// region's states (see [`Homes`]); each run of bodies is read and
    /// written where it lives.
    fn run(
        &self,
        parallel: bool,
        parts: (ColumnsMut<'_>, &mut [BodyState], &mut [Vec2], &mut [Vec2]),
        far: Option<(&Homes, &mut [BodyState])>,
        limit: impl Fn(usize) -> Option<SpeedLimits> + Sync,
    ) {
        let Some((homes, far)) = far else {
            for_chunks(parallel, parts, |offset, (pos, state, delta, replay)| {
                self.move_run(offset, (pos, state, delta, replay), &limit);
                0
            });
            return;
        };
        let (pos, state, delta, replay) = parts;
        let far = &mut far[..pos.len()];
        let parts = (pos, state, delta, replay, far);
        for_chunks(
            parallel,
            parts,
            |offset, (mut pos, state, delta, replay, far)| {
                homes.each_state(offset, state, far, |run, states| {
                    let (pos, delta) = (pos.slice(run.clone()), &mut delta[run.clone()]);
                    let moving = (pos, states, delta, &mut replay[run.clone()]);
                    self.move_run(offset + run.start, moving, &limit);
                });
                0
            },
        );
    }

    /// [`run`](Self::run) over the bodies from `first` on, whose states
    /// are `state`.
    #[inline(always)]
    fn move_run(
        &self,
        first: usize,
        (pos, state, delta, replay): (ColumnsMut<'_>, &mut [BodyState], &mut [Vec2], &mut [Vec2]),
        limit: &impl Fn(usize) -> Option<SpeedLimits>,
    ) {
        // One loop over equal lengths (no bounds checks), with the body's
        // work written out in it.
        let (px, py) = pos.into_parts();
        let n = px.len();
        let (state, delta, replay) = (&mut state[..n], &mut delta[..n], &mut replay[..n]);
        for k in 0..n {
            let (s, i) = (&mut state[k], first + k);
            let mut limited = false;
            if let Some(limits) = limit(i) {
                let before = s.vel;
                limited = limits.apply(&mut s.vel);
                if limited && self.replay {
                    // The contacts' change so far kept, as if the body had
                    // started the substep at the limited speed: a limit's
                    // change is not replayed (and a body no contact touched
                    // starts the next substep at exactly the limited speed).
                    replay[k] = s.vel - (before - replay[k]);
                }
            }
            // Semi-implicit Euler adds an exact zero here, as the
            // no-contact path does: the same bits either way. A limit that
            // changed the velocity leaves the correction out, as that path
            // does (it was worked out for the velocity before the limit).
            let c = match self.correction {
                Some(c) if !limited => c[i],
                _ => Vec2::ZERO,
            };
            let p = Vec2::new(px[k], py[k]) + ((s.vel + s.push) * self.h + c);
            (px[k], py[k]) = (p.x, p.y);
            delta[k] = p - self.start[i];
            // The push is spent: until the next substep's load its slot
            // holds the displacement, which the relax stage's first pass
            // reads with the velocity (see `BodyState`).
            s.push = delta[k];
        }
    }
}

#[cfg(test)]
mod tests;
