//! The hot loop for the common case: point masses under uniform forces.
//!
//! Most game worlds integrate with semi-implicit Euler under gravity (and a
//! force field), perhaps with quadratic drag, with the world's speed
//! limits. For them this kernel walks the body arrays as plain slices with
//! no per-body branch: limits and the non-finite guard are selects, so the
//! compiler can vectorise the loop. It computes exactly what the general
//! path computes (the same operations in the same order, so the same bits);
//! a test checks that.

use crate::body::store::{DynamicBodies, SpeedLimits};
use crate::forces::models::stable_quadratic_drag;
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

    /// One step of every dynamic body, which also clears the force
    /// accumulators; returns how many were reset for a non-finite
    /// velocity.
    pub(crate) fn run(&self, b: &mut DynamicBodies, dt: f32, parallel: bool) -> u64 {
        let step: fn(&Self, Slices<'_>, f32) -> u64 =
            match (self.plain(), self.drag.is_some(), self.limits.is_some()) {
                (false, false, false) => Self::run_with::<false, false, false, true>,
                (false, false, true) => Self::run_with::<false, false, true, true>,
                (false, true, false) => Self::run_with::<false, true, false, true>,
                (false, true, true) => Self::run_with::<false, true, true, true>,
                (true, false, false) => Self::run_with::<true, false, false, true>,
                (true, false, true) => Self::run_with::<true, false, true, true>,
                (true, true, false) => Self::run_with::<true, true, false, true>,
                (true, true, true) => Self::run_with::<true, true, true, true>,
            };
        in_chunks(b, parallel, |s| step(self, s, dt))
    }

    /// New velocities only (the contact solver runs before positions move);
    /// returns the number of non-finite resets.
    pub(crate) fn velocities(&self, b: &mut DynamicBodies, dt: f32, parallel: bool) -> u64 {
        let step: fn(&Self, Slices<'_>, f32) -> u64 = match (self.plain(), self.drag.is_some()) {
            (false, false) => Self::run_with::<false, false, false, false>,
            (false, true) => Self::run_with::<false, true, false, false>,
            (true, false) => Self::run_with::<true, false, false, false>,
            (true, true) => Self::run_with::<true, true, false, false>,
        };
        in_chunks(b, parallel, |s| step(self, s, dt))
    }

    /// Whether there is no force field and no wind: their terms can be
    /// left out of the loops, which then hold fewer values in registers.
    /// Adding a zero changes at most the sign of a zero, and every zero
    /// velocity is flushed to `+0` before it is used (see `velocity`): the
    /// same bits.
    fn plain(&self) -> bool {
        self.field == Vec2::ZERO && self.drag.is_none_or(|(_, air)| air == Vec2::ZERO)
    }

    /// The new velocity `(x, y)` of one body, and whether it was finite
    /// (else it is reset to zero). The same operations, in the same order,
    /// as `Drive::accel`, `Forces::euler_velocity`, `guard_finite` (with its
    /// subnormal flush) and, with `LIMITS`, `SpeedLimits::apply`, written
    /// on components and as selects, so that the loops over the bodies
    /// vectorise (IEEE arithmetic is exact per lane: the same bits).
    /// `PLAIN`: without the zero force field and wind (see [`Self::plain`]).
    #[inline(always)]
    fn velocity<const PLAIN: bool, const DRAG: bool, const LIMITS: bool>(
        &self,
        (vx, vy): (f32, f32),
        (fx, fy): (f32, f32),
        im: f32,
        cda: f32,
        dt: f32,
    ) -> (f32, f32, bool) {
        let (fx, fy) = if PLAIN {
            (fx, fy)
        } else {
            (fx + self.field.x, fy + self.field.y)
        };
        let ax = self.gravity.x + fx * im;
        let ay = self.gravity.y + fy * im;
        let (mut x, mut y) = (vx + ax * dt, vy + ay * dt);
        if DRAG {
            let (half_rho, air) = self.drag.unwrap_or((0.0, Vec2::ZERO));
            let c = half_rho * cda * im;
            (x, y) = if PLAIN {
                // `stable_quadratic_drag` with no air velocity.
                let d = 1.0 + c * (x * x + y * y).sqrt() * dt;
                (x / d, y / d)
            } else {
                stable_quadratic_drag(Vec2::new(x, y), air, c, dt).into()
            };
        }
        let finite = (x * x + y * y).is_finite();
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
            let limits = self.limits.unwrap_or(SpeedLimits::new(0.0, f32::INFINITY));
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
        (x, y, finite)
    }

    /// New velocities over `dt`; with `MOVE`, also the positions moved by
    /// them and the forces cleared (`run`), else the velocities alone
    /// (`velocities`). Returns the number of non-finite resets.
    fn run_with<const PLAIN: bool, const DRAG: bool, const LIMITS: bool, const MOVE: bool>(
        &self,
        s: Slices<'_>,
        dt: f32,
    ) -> u64 {
        let n = s.vx.len();
        let (px, py) = (&mut s.px[..n], &mut s.py[..n]);
        let (vx, vy) = (s.vx, &mut s.vy[..n]);
        let (fx, fy) = (&mut s.fx[..n], &mut s.fy[..n]);
        let (inv_mass, drag_area) = (&s.inv_mass[..n], &s.drag_area[..n]);
        in_blocks(n, |r| {
            let mut resets = 0u32;
            for i in r {
                let v = (vx[i], vy[i]);
                let (x, y, finite) = self.velocity::<PLAIN, DRAG, LIMITS>(
                    v,
                    (fx[i], fy[i]),
                    inv_mass[i],
                    drag_area[i],
                    dt,
                );
                (vx[i], vy[i]) = (x, y);
                if MOVE {
                    // `+ 0` as the general path adds its zero correction:
                    // same bits.
                    px[i] += x * dt + 0.0;
                    py[i] += y * dt + 0.0;
                    // The accumulated force is spent: cleared here, in the
                    // same pass, instead of in one of its own after the step.
                    (fx[i], fy[i]) = (0.0, 0.0);
                }
                resets += u32::from(!finite);
            }
            resets
        })
    }
}

/// Calls `f` on `0..n` in blocks of at most [`BLOCK`] and sums what it
/// returns. Each block counts its resets in a `u32`: with a `u64` count the
/// compiler vectorised the loops two bodies wide instead of four.
#[inline(always)]
fn in_blocks(n: usize, mut f: impl FnMut(std::ops::Range<usize>) -> u32) -> u64 {
    (0..n)
        .step_by(BLOCK)
        .map(|start| u64::from(f(start..(start + BLOCK).min(n))))
        .sum()
}

/// Bodies a block of the kernel's loops counts resets for in a `u32`.
const BLOCK: usize = 1 << 16;

/// The arrays the kernel reads and writes, for a run of bodies: each
/// vector as its x and y components.
struct Slices<'a> {
    px: &'a mut [f32],
    py: &'a mut [f32],
    vx: &'a mut [f32],
    vy: &'a mut [f32],
    fx: &'a mut [f32],
    fy: &'a mut [f32],
    inv_mass: &'a [f32],
    drag_area: &'a [f32],
}

/// Runs `work` over the bodies, in chunks on the thread pool for large
/// worlds (see [`for_chunks`]).
fn in_chunks(
    b: &mut DynamicBodies,
    parallel: bool,
    work: impl Fn(Slices<'_>) -> u64 + Sync,
) -> u64 {
    let parts = (
        b.pos.view_mut(),
        b.vel.view_mut(),
        b.force.view_mut(),
        &b.inv_mass[..],
        &b.drag_area[..],
    );
    for_chunks(
        parallel,
        parts,
        |_, (pos, vel, force, inv_mass, drag_area)| {
            work(Slices {
                px: pos.x,
                py: pos.y,
                vx: vel.x,
                vy: vel.y,
                fx: force.x,
                fy: force.y,
                inv_mass,
                drag_area,
            })
        },
    )
}

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
        // Still air and no field: the plain loops, which leave their zero
        // terms out; a gravity with a negative zero checks that only the
        // sign of a zero could change, and is flushed.
        let still = ForceModels {
            gravity: Some(Vec2::new(-0.0, -9.81)),
            quadratic_drag: Some(QuadraticDrag::default()),
            ..Default::default()
        };
        // With shapes the contact step runs, and its velocity-only kernel
        // is compared with the general path too.
        for (forces, min_speed, max_speed, shaped) in [
            (ForceModels::default(), 0.0, f32::INFINITY, false),
            (ForceModels::default(), 0.5, 12.0, false),
            (drag, 0.0, f32::INFINITY, false),
            (drag, 0.3, 9.0, false),
            (still, 0.0, f32::INFINITY, false),
            (still, 0.3, 9.0, false),
            (ForceModels::default(), 0.0, f32::INFINITY, true),
            (drag, 0.3, 9.0, true),
            (still, 0.3, 9.0, true),
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
