//! Force zones on sensor bodies, and the forces a step starts with: each
//! body's share of gravity and the zones' pushes (see `forces::zones`).

use crate::body::store::SpeedLimits;
use crate::forces::zones::{ForceZone, area_inside};
use crate::world::World;
use crate::{BodyId, PhysicsError, Shape};
use glam::Vec2;

impl World {
    /// Makes sensor body `body` a force zone (or changes its zone): every
    /// dynamic body overlapping its box gets `zone`'s forces each step, in
    /// proportion to the share of its area inside (see [`ForceZone`]). The
    /// zone moves with its body; its sensor events still come.
    ///
    /// Zones act in the order they were added. The bodies it overlaps wake
    /// now; a body that falls asleep inside a zone (a crate floating at
    /// rest) stays asleep until something wakes it.
    ///
    /// ```
    /// use passo_physics::{BodyDef, ForceZone, Liquid, Shape, World, glam::Vec2};
    ///
    /// let mut world = World::default();
    /// // A pool 4 m wide, its surface at y = 0.
    /// let pool = world.add_body(BodyDef::new_static(Vec2::new(0.0, -1.0), Shape::rect(4.0, 2.0)).as_sensor()).unwrap();
    /// let water = Liquid { density: 8.0, drag: 4.0 };
    /// world.add_force_zone(pool, ForceZone { liquid: Some(water), ..Default::default() }).unwrap();
    /// // A crate of 1 kg and 0.5 m × 0.5 m: it floats 1 / (8 × 0.5) = 0.25 m deep.
    /// let crate_ = world.add_body(BodyDef::new_dynamic(Vec2::new(0.0, 1.0), Shape::rect(0.5, 0.5))).unwrap();
    /// for _ in 0..1200 {
    ///     world.step(1.0 / 60.0);
    /// }
    /// let bottom = world.body(crate_).unwrap().position.y - 0.25;
    /// assert!((bottom + 0.25).abs() < 1e-3, "its bottom at {bottom}");
    /// ```
    ///
    /// # Errors
    /// A stale id, a body that is not a sensor with a box shape, or a zone
    /// with a value out of range.
    pub fn add_force_zone(&mut self, body: BodyId, zone: ForceZone) -> Result<(), PhysicsError> {
        zone.validate()?;
        let location = self.locate(body).ok_or(PhysicsError::StaleBody(body))?;
        let meta = self.meta_mut(location);
        if !meta.sensor || !matches!(meta.shape, Some(Shape::Box { .. })) {
            return Err(PhysicsError::OutOfRange {
                what: "World::add_force_zone",
                value: 0.0,
                allowed: "a sensor body with a box shape",
            });
        }
        match self.zones.iter_mut().find(|(id, _)| *id == body) {
            Some((_, z)) => *z = zone,
            None => self.zones.push((body, zone)),
        }
        self.wake_in_zone(body);
        Ok(())
    }

    /// Turns `body`'s force zone off; returns it, or `None` if it had none.
    /// Removing the body does this too.
    pub fn remove_force_zone(&mut self, body: BodyId) -> Option<ForceZone> {
        let at = self.zones.iter().position(|(id, _)| *id == body)?;
        self.wake_in_zone(body);
        Some(self.zones.remove(at).1)
    }

    /// `body`'s force zone, if it has one.
    pub fn force_zone(&self, body: BodyId) -> Option<ForceZone> {
        self.zones.iter().find(|(id, _)| *id == body).map(|z| z.1)
    }

    /// Every force zone with its sensor body, in the order they act.
    pub fn force_zones(&self) -> impl Iterator<Item = (BodyId, ForceZone)> + '_ {
        self.zones.iter().copied()
    }

    /// The box of `body`'s zone, if the body lives.
    fn zone_box(&self, body: BodyId) -> Option<(Vec2, Vec2)> {
        let b = self.body(body)?;
        let h = b.shape?.half_extents();
        Some((b.position - h, b.position + h))
    }

    /// Wakes the dynamic bodies overlapping `body`'s zone.
    fn wake_in_zone(&mut self, body: BodyId) {
        let Some((min, max)) = self.zone_box(body) else {
            return;
        };
        for i in 0..self.dynamic.len() {
            let p = self.dynamic.pos.at(i);
            let h = self.dynamic.meta[i]
                .shape
                .map_or(Vec2::ZERO, |s| s.half_extents());
            if (p - h).cmple(max).all() && (p + h).cmpge(min).all() {
                self.wake_index(i);
            }
        }
    }

    /// Whether some zone holds a liquid: the bodies that float in it have
    /// no minimum speed while they do (see `add_body_forces`), so the step
    /// takes each body's limits from its own entry.
    pub(crate) fn has_liquid(&self) -> bool {
        self.zones.iter().any(|(_, z)| z.liquid.is_some())
    }

    /// Whether the step starts by adding forces of its own: some body's
    /// gravity is scaled, or some zone exists.
    pub(crate) fn has_body_forces(&self) -> bool {
        self.census.gravity_scaled > 0 || !self.zones.is_empty()
    }

    /// Sets each awake dynamic body's force to what game code applied
    /// plus what its gravity scale and the zones it is in ask for over the
    /// next `dt`, at its current position and velocity. `first`: the first
    /// call of the step, which keeps the forces game code applied (the
    /// later ones start again from them).
    pub(crate) fn add_body_forces(&mut self, dt: f32, first: bool) {
        if first {
            self.applied_force.copy_from(&self.dynamic.force);
        } else {
            self.dynamic.force.copy_from(&self.applied_force);
        }
        let g = self.settings.forces.gravity.unwrap_or(Vec2::ZERO);
        let d = &mut self.dynamic;
        if self.census.gravity_scaled > 0 && g != Vec2::ZERO {
            for i in 0..d.len() {
                let meta = &d.meta[i];
                if !meta.kinematic && meta.gravity_scale != 1.0 && !d.sleep[i].is_asleep() {
                    let f = d.force.at(i) + meta.mass * (meta.gravity_scale - 1.0) * g;
                    d.force.set(i, f);
                }
            }
        }
        for &(body, zone) in &self.zones {
            let Some((min, max)) = self.zone_box(body) else {
                continue;
            };
            let d = &mut self.dynamic;
            for i in 0..d.len() {
                let meta = &d.meta[i];
                if meta.kinematic || d.sleep[i].is_asleep() {
                    continue;
                }
                let p = d.pos.at(i);
                let (inside, submerged) = match &meta.shape {
                    Some(shape) => {
                        let h = shape.half_extents();
                        if !((p - h).cmple(max).all() && (p + h).cmpge(min).all()) {
                            continue;
                        }
                        let area = area_inside(shape, p, min, max);
                        (area / shape.area(), area)
                    }
                    None if p.cmpge(min).all() && p.cmple(max).all() => (1.0, 0.0),
                    None => continue,
                };
                if inside <= 0.0 {
                    continue;
                }
                let v = d.vel.at(i);
                let f = zone.force(
                    meta.mass,
                    meta.gravity_scale,
                    meta.drag_area,
                    v,
                    inside,
                    submerged,
                    g,
                    dt,
                );
                d.force.set(i, d.force.at(i) + f);
                if let (Some(liquid), Some(shape)) = (zone.liquid, meta.shape) {
                    // A body lighter than the liquid rests only where it
                    // floats: held up by its weight to within 0.1 %. A
                    // crate bobbing slower than the sleep speed would
                    // otherwise fall asleep up to 5 mm off its depth.
                    let local_g = zone.gravity.unwrap_or(g) * meta.gravity_scale;
                    let weight = meta.mass * local_g;
                    let lift = -liquid.density * submerged * zone.gravity.unwrap_or(g);
                    let floats = meta.mass < liquid.density * shape.area();
                    if floats && (weight + lift).length() > 1e-3 * weight.length() {
                        d.sleep[i].rest_time = 0.0;
                    }
                    if floats && submerged > 0.0 {
                        // Near its depth a floating body gains less than the
                        // minimum speed in a substep: snapped to zero each
                        // time, it would stall up to min_speed / (w^2 h)
                        // off its depth (2.4 mm for a light crate).
                        d.limits[i] = SpeedLimits::new(0.0, d.limits[i].max);
                    }
                }
            }
        }
    }

    /// Puts back every body's own speed limits after a step that lifted
    /// the minimum speed of bodies floating in a liquid.
    pub(crate) fn restore_limits(&mut self) {
        if self.has_liquid() {
            for i in 0..self.dynamic.len() {
                self.dynamic.limits[i] = self.resolve_limits(&self.dynamic.meta[i]);
            }
        }
    }

    /// Removes `body`'s zone (it is being removed).
    pub(crate) fn forget_zone_of(&mut self, body: BodyId) {
        self.zones.retain(|(id, _)| *id != body);
    }
}
