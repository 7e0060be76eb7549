//! The hot loop for the common case: point masses under uniform forces.
//!
//! Most game worlds integrate with semi-implicit Euler under gravity (and a
//! force field), perhaps with quadratic drag, with the world's speed
//! limits. For them this kernel walks the body arrays as plain slices with
//! no per-body branch: limits and the non-finite guard are selects, so the
//! compiler can vectorise the loop. It computes exactly what the general
//! path computes (the same operations in the same order, so the same bits);
//! a test checks that.

use crate::body::{DynamicBodies, SpeedLimits, flush_subnormal};
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
    pub fn new(
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
    pub fn run(&self, b: &mut DynamicBodies, dt: f32) -> u64 {
        match (self.drag.is_some(), self.limits.is_some()) {
            (false, false) => self.run_with::<false, false>(b, dt),
            (false, true) => self.run_with::<false, true>(b, dt),
            (true, false) => self.run_with::<true, false>(b, dt),
            (true, true) => self.run_with::<true, true>(b, dt),
        }
    }

    fn run_with<const DRAG: bool, const LIMITS: bool>(
        &self,
        b: &mut DynamicBodies,
        dt: f32,
    ) -> u64 {
        let (half_rho, air) = self.drag.unwrap_or((0.0, Vec2::ZERO));
        let limits = self.limits.unwrap_or(SpeedLimits::new(0.0, f32::INFINITY));
        let (gravity, field) = (self.gravity, self.field);
        let mut resets = 0u64;
        let bodies = b.pos.iter_mut().zip(b.vel.iter_mut()).zip(
            b.force
                .iter()
                .zip(b.inv_mass.iter().zip(b.drag_area.iter())),
        );
        for ((p, v), (f, (&im, &cda))) in bodies {
            // The same expression as `Drive::accel` and `Forces::euler_velocity`.
            let a = gravity + (*f + field) * im;
            let mut nv = *v + a * dt;
            if DRAG {
                // `Dissipation::apply_stable`: v <- air + rel / (1 + c |rel| dt).
                let rel = nv - air;
                let c = half_rho * cda * im;
                nv = air + rel / (1.0 + c * rel.length() * dt);
            }
            // `guard_finite` and `SpeedLimits::apply`, written as selects.
            let s2 = nv.length_squared();
            let finite = s2.is_finite();
            resets += u64::from(!finite);
            nv = flush_subnormal(nv);
            if LIMITS {
                // Computed for every body so the loop has no branch.
                let clamp = limits.max / s2.sqrt();
                nv *= if s2 > limits.max_sq { clamp } else { 1.0 };
            }
            if !finite || (LIMITS && s2 < limits.min_sq) {
                nv = Vec2::ZERO;
            }
            *v = nv;
            // `+ 0` as the general path adds its zero correction: same bits.
            *p += nv * dt + Vec2::ZERO;
        }
        resets
    }
}

#[cfg(test)]
mod tests {
    use crate::{BodyDef, ForceModel, ForceModels, QuadraticDrag, World, WorldSettings};
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
        for (forces, min_speed, max_speed) in [
            (ForceModels::default(), 0.0, f32::INFINITY),
            (ForceModels::default(), 0.5, 12.0),
            (drag, 0.0, f32::INFINITY),
            (drag, 0.3, 9.0),
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
                    ..Default::default()
                };
                fast.add_body(def).unwrap();
                general.add_body(def).unwrap();
            }
            for step in 0..300 {
                if step % 50 == 0 {
                    let kick = Vec2::new(30.0, 80.0);
                    let id = fast.bodies().nth(step / 50).unwrap().id;
                    fast.apply_force(id, kick).unwrap();
                    general.apply_force(id, kick).unwrap();
                }
                fast.step(1.0 / 60.0);
                general.step(1.0 / 60.0);
                assert_eq!(fast.state_hash(), general.state_hash(), "step {step}");
            }
        }
    }
}
