//! The hot loop for the common case: point masses under uniform forces.
//!
//! Most game worlds integrate with semi-implicit Euler under gravity (and a
//! force field), perhaps with quadratic drag, with the world's speed
//! limits. For them this kernel walks the body arrays as plain slices with
//! no per-body branch: limits and the non-finite guard are selects, so the
//! compiler can vectorise the loop. It computes exactly what the general
//! path computes (the same operations in the same order, so the same bits);
//! a test checks that.

use crate::bodies::{DynamicBodies, SpeedLimits, flush_subnormal};
use crate::forces::stable_quadratic_drag;
use crate::parallel::for_chunks;
use crate::{ForceForm, ForceModels, Integrator};
use glam::Vec2;

/// The hoisted parameters of the fast kernel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PointMassKernel {
    gravity: Vec2,
    field: Vec2,
    /// `(1/2 rho, air velocity)` with quadratic drag.
    drag: Option<(f32, Vec2)>,
    limits: Option<SpeedLimits>,
}

impl PointMassKernel {
    /// The kernel for these settings, or `None` if some stage needs the
    /// general path (another integrator, springs, friction, custom models,
    /// per-body speed limits, plain explicit drag).
    pub(crate) fn new(
        models: &ForceModels,
        integrator: Integrator,
        form: ForceForm,
        general_needed: bool,
        limits: Option<Option<SpeedLimits>>,
    ) -> Option<Self> {
        let simple = integrator == Integrator::SemiImplicitEuler
            && !general_needed
            && models.spring.is_none()
            && models.central_gravity.is_none()
            && models.linear_drag.is_none()
            && models.surface_friction.is_none()
            && (models.quadratic_drag.is_none() || form == ForceForm::Stable);
        // `Some(None)`: limits that differ per body.
        let limits = match limits {
            None => None,
            Some(Some(uniform)) => Some(uniform),
            Some(None) => return None,
        };
        simple.then(|| Self {
            gravity: models.gravity.unwrap_or(Vec2::ZERO),
            field: models.force_field.unwrap_or(Vec2::ZERO),
            drag: models
                .quadratic_drag
                .map(|d| (0.5 * d.density, models.air_velocity)),
            limits,
        })
    }

    /// One step of every dynamic body; returns how many were reset for a
    /// non-finite velocity.
    pub(crate) fn run(&self, b: &mut DynamicBodies, dt: f32, parallel: bool) -> u64 {
        let step: fn(&Self, Slices<'_>, f32) -> u64 =
            match (self.drag.is_some(), self.limits.is_some()) {
                (false, false) => Self::run_with::<false, false>,
                (false, true) => Self::run_with::<false, true>,
                (true, false) => Self::run_with::<true, false>,
                (true, true) => Self::run_with::<true, true>,
            };
        in_chunks(b, parallel, |s| step(self, s, dt))
    }

    /// New velocities only (the contact solver runs before positions move);
    /// returns the number of non-finite resets.
    pub(crate) fn velocities(&self, b: &mut DynamicBodies, dt: f32, parallel: bool) -> u64 {
        let step: fn(&Self, Slices<'_>, f32) -> u64 = if self.drag.is_some() {
            Self::velocities_with::<true>
        } else {
            Self::velocities_with::<false>
        };
        in_chunks(b, parallel, |s| step(self, s, dt))
    }

    /// The new velocity of one body (with the non-finite guard and the
    /// subnormal flush): the same operations, in the same order, as
    /// `Drive::accel`, `Forces::euler_velocity` and `guard_finite`.
    #[inline(always)]
    fn velocity<const DRAG: bool>(
        &self,
        v: Vec2,
        f: Vec2,
        im: f32,
        cda: f32,
        dt: f32,
    ) -> (Vec2, bool) {
        let a = self.gravity + (f + self.field) * im;
        let mut nv = v + a * dt;
        if DRAG {
            let (half_rho, air) = self.drag.unwrap_or((0.0, Vec2::ZERO));
            nv = stable_quadratic_drag(nv, air, half_rho * cda * im, dt);
        }
        let finite = nv.length_squared().is_finite();
        (
            Vec2::select(glam::BVec2::splat(finite), flush_subnormal(nv), Vec2::ZERO),
            finite,
        )
    }

    fn velocities_with<const DRAG: bool>(&self, s: Slices<'_>, dt: f32) -> u64 {
        let mut resets = 0u64;
        let bodies = s
            .vel
            .iter_mut()
            .zip(s.force.iter().zip(s.inv_mass.iter().zip(s.drag_area)));
        for (v, (&f, (&im, &cda))) in bodies {
            let (nv, finite) = self.velocity::<DRAG>(*v, f, im, cda, dt);
            resets += u64::from(!finite);
            *v = nv;
        }
        resets
    }

    fn run_with<const DRAG: bool, const LIMITS: bool>(&self, mut s: Slices<'_>, dt: f32) -> u64 {
        let n = s.pos.len();
        let whole = n - n % LANES;
        let mut resets = 0;
        for start in (0..whole).step_by(LANES) {
            resets += self.lanes::<DRAG, LIMITS>(&mut s, start, dt);
        }
        for i in whole..n {
            resets += self.one::<DRAG, LIMITS>(&mut s, i, dt);
        }
        resets
    }

    /// One body, for the remainder after whole groups of lanes.
    #[inline(always)]
    fn one<const DRAG: bool, const LIMITS: bool>(
        &self,
        s: &mut Slices<'_>,
        i: usize,
        dt: f32,
    ) -> u64 {
        let (mut nv, finite) =
            self.velocity::<DRAG>(s.vel[i], s.force[i], s.inv_mass[i], s.drag_area[i], dt);
        if LIMITS {
            self.limits
                .unwrap_or(SpeedLimits::new(0.0, f32::INFINITY))
                .apply(&mut nv);
        }
        s.vel[i] = nv;
        // `+ 0` as the general path adds its zero correction: same bits.
        s.pos[i] += nv * dt + Vec2::ZERO;
        u64::from(!finite)
    }

    /// `LANES` bodies at once, component by component in arrays, so the
    /// compiler turns each line into vector instructions. Every lane does
    /// exactly the scalar operations of `velocity` and `SpeedLimits::apply`
    /// (IEEE arithmetic is exact per lane), so the bits are the same.
    #[inline(always)]
    fn lanes<const DRAG: bool, const LIMITS: bool>(
        &self,
        s: &mut Slices<'_>,
        start: usize,
        dt: f32,
    ) -> u64 {
        let r = start..start + LANES;
        let (pos, vel) = (&mut s.pos[r.clone()], &mut s.vel[r.clone()]);
        let (force, inv_mass, drag_area) =
            (&s.force[r.clone()], &s.inv_mass[r.clone()], &s.drag_area[r]);
        let (half_rho, air) = self.drag.unwrap_or((0.0, Vec2::ZERO));
        let limits = self.limits.unwrap_or(SpeedLimits::new(0.0, f32::INFINITY));
        let mut vx = [0.0f32; LANES];
        let mut vy = [0.0f32; LANES];
        let mut reset = [0u32; LANES];
        for k in 0..LANES {
            let im = inv_mass[k];
            let ax = self.gravity.x + (force[k].x + self.field.x) * im;
            let ay = self.gravity.y + (force[k].y + self.field.y) * im;
            let (mut x, mut y) = (vel[k].x + ax * dt, vel[k].y + ay * dt);
            if DRAG {
                let c = half_rho * drag_area[k] * im;
                (x, y) = stable_quadratic_drag(Vec2::new(x, y), air, c, dt).into();
            }
            let finite = (x * x + y * y).is_finite();
            reset[k] = u32::from(!finite);
            // `flush_subnormal`, then the reset of a non-finite velocity.
            x = if finite && x.abs() >= f32::MIN_POSITIVE {
                x
            } else {
                0.0
            };
            y = if finite && y.abs() >= f32::MIN_POSITIVE {
                y
            } else {
                0.0
            };
            if LIMITS {
                let s2 = x * x + y * y;
                let clamp = if s2 > limits.max_sq {
                    limits.max / s2.sqrt()
                } else {
                    1.0
                };
                let keep = s2 >= limits.min_sq;
                x = if keep { x * clamp } else { 0.0 };
                y = if keep { y * clamp } else { 0.0 };
            }
            vx[k] = x;
            vy[k] = y;
        }
        for k in 0..LANES {
            let v = Vec2::new(vx[k], vy[k]);
            vel[k] = v;
            pos[k] += v * dt + Vec2::ZERO;
        }
        reset.iter().map(|&r| u64::from(r)).sum()
    }
}

/// The arrays the kernel reads and writes, for a run of bodies.
struct Slices<'a> {
    pub pos: &'a mut [Vec2],
    pub vel: &'a mut [Vec2],
    pub force: &'a [Vec2],
    pub inv_mass: &'a [f32],
    pub drag_area: &'a [f32],
}

/// Runs `work` over the bodies, in chunks on the thread pool for large
/// worlds (see [`for_chunks`]).
fn in_chunks(
    b: &mut DynamicBodies,
    parallel: bool,
    work: impl Fn(Slices<'_>) -> u64 + Sync,
) -> u64 {
    let parts = (
        &mut b.pos[..],
        &mut b.vel[..],
        &b.force[..],
        &b.inv_mass[..],
        &b.drag_area[..],
    );
    for_chunks(
        parallel,
        parts,
        |_, (pos, vel, force, inv_mass, drag_area)| {
            work(Slices {
                pos,
                vel,
                force,
                inv_mass,
                drag_area,
            })
        },
    )
}

/// Bodies the fast kernel handles at once: 32. The compiler vectorises
/// the lane loops as loops at this width; at 8 it unrolled them into
/// shuffles and register spills (one thread, 10 000 to 10⁶ bodies,
/// `steps integration`: 4 lanes 6.9-7.6, 8 lanes 4.2-4.4, 16 lanes 3.3-3.4,
/// 32 lanes 2.9-3.0, 64 lanes 3.0-3.2 ns per body-step). The lanes are
/// independent, so the width changes the speed, never the bits.
const LANES: usize = 32;

#[cfg(test)]
mod tests {
    use crate::{BodyDef, ForceModel, ForceModels, QuadraticDrag, Shape, World, WorldSettings};
    use glam::Vec2;
    use std::sync::Arc;

    /// Adds exactly nothing, but sends the world down the general path.
    struct Nothing;
    impl ForceModel for Nothing {
        fn force(&self, _: Vec2, _: Vec2, _: f32) -> Vec2 {
            Vec2::ZERO
        }
    }

    #[test]
    fn the_fast_kernel_gives_the_general_paths_bits() {
        let drag = ForceModels {
            quadratic_drag: Some(QuadraticDrag::default()),
            air_velocity: Vec2::new(4.0, 0.5),
            force_field: Some(Vec2::new(0.5, 0.0)),
            ..Default::default()
        };
        // With shapes the contact step runs, and its velocity-only kernel
        // is compared with the general path too.
        for (forces, min_speed, max_speed, shaped) in [
            (ForceModels::default(), 0.0, f32::INFINITY, false),
            (ForceModels::default(), 0.5, 12.0, false),
            (drag, 0.0, f32::INFINITY, false),
            (drag, 0.3, 9.0, false),
            (ForceModels::default(), 0.0, f32::INFINITY, true),
            (drag, 0.3, 9.0, true),
        ] {
            let settings = WorldSettings {
                forces,
                min_speed,
                max_speed,
                ..Default::default()
            };
            let mut fast = World::new(settings).unwrap();
            let mut general = World::new(settings).unwrap();
            general.add_force_model(Arc::new(Nothing));
            for i in 0..200 {
                let def = BodyDef {
                    position: Vec2::new(i as f32 * 0.37, (i % 7) as f32),
                    velocity: Vec2::new((i % 13) as f32 - 6.0, (i % 5) as f32 * 3.0 - 0.2),
                    mass: 0.5 + (i % 4) as f32,
                    drag_area: (i % 3) as f32 * 0.2,
                    shape: shaped.then_some(Shape::circle(0.15)),
                    ..Default::default()
                };
                fast.add_body(def).unwrap();
                general.add_body(def).unwrap();
            }
            if shaped {
                let ground = BodyDef::new_static(Vec2::new(37.0, -3.0), Shape::rect(100.0, 1.0));
                fast.add_body(ground).unwrap();
                general.add_body(ground).unwrap();
                assert!(!fast.contact_stages().is_empty());
            }
            // The fast world takes the kernel, the other the general path
            // (else the test would compare the general path with itself).
            assert!(fast.kernel(fast.speed_limits()).is_some());
            assert!(general.kernel(general.speed_limits()).is_none());
            for step in 0..300 {
                if step % 50 == 0 {
                    let kick = Vec2::new(30.0, 80.0);
                    let id = fast.bodies().nth(step / 50).unwrap().id;
                    // (the kick also wakes a body that fell asleep)
                    fast.apply_force(id, kick);
                    general.apply_force(id, kick);
                }
                fast.step(1.0 / 60.0);
                general.step(1.0 / 60.0);
                assert_eq!(fast.state_hash(), general.state_hash(), "step {step}");
            }
        }
    }
}
