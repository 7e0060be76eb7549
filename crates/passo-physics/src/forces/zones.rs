//! Force zones: areas that push the bodies inside them (their own gravity,
//! wind, drag, a liquid that holds bodies up), and the exact area of a
//! body's shape inside one.
//!
//! Passo is 2D: a body's "volume" is its area, and a liquid's density is
//! in kilograms per square metre. A body floats when its mass per area is
//! below the liquid's density, with the share `mass / (density * area)`
//! of its area below the surface.

use crate::error::{finite_vec, non_negative, positive};
use crate::{PhysicsError, Shape};
use glam::Vec2;

/// A wind: air moving at `velocity` pushes each body inside with quadratic
/// drag on its velocity relative to the air, `1/2 rho |w - v| (w - v) Cd A`
/// (the body's [`drag_area`](crate::BodyDef::drag_area)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Wind {
    /// The air's velocity, metres per second.
    pub velocity: Vec2,
    /// The air's density, kg/m³, >= 0 (1.225 at sea level,
    /// [`AIR_DENSITY`](crate::constants::AIR_DENSITY)).
    pub density: f32,
}

/// A liquid filling the zone up to its top: it holds each body up with
/// the weight of the liquid its shape displaces, `rho g A_submerged`
/// (exact for circles, boxes and capsules), and slows it with linear drag
/// in proportion to the share of it that is submerged.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Liquid {
    /// Density, kilograms per square metre (2D), > 0: a body lighter per
    /// area floats. Water-like for crates of 1 kg per 0.25 m²: 4 to 10.
    pub density: f32,
    /// Linear drag rate of a body fully under, 1/s, >= 0: each second the
    /// liquid takes this share of the body's velocity (for small rates).
    /// Without some, a floating body bobs for ever.
    pub drag: f32,
}

/// What a zone does to the bodies inside it. Each effect acts on the share
/// of a body's area inside the zone (a point mass: all or nothing, by its
/// centre). Attach one to a sensor body with a box shape
/// ([`World::add_force_zone`](crate::World::add_force_zone)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct ForceZone {
    /// Gravity inside the zone, m/s², instead of the world's (scaled by each
    /// body's gravity scale).
    pub gravity: Option<Vec2>,
    /// A wind.
    pub wind: Option<Wind>,
    /// Linear drag rate, 1/s, >= 0: mud, honey, a slow-motion field.
    pub drag: Option<f32>,
    /// A liquid.
    pub liquid: Option<Liquid>,
}

impl ForceZone {
    /// Checks every value.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        if let Some(g) = self.gravity {
            finite_vec("ForceZone::gravity", g)?;
        }
        if let Some(wind) = self.wind {
            finite_vec("Wind::velocity", wind.velocity)?;
            non_negative("Wind::density", wind.density)?;
        }
        if let Some(drag) = self.drag {
            non_negative("ForceZone::drag", drag)?;
        }
        if let Some(liquid) = self.liquid {
            positive("Liquid::density", liquid.density)?;
            non_negative("Liquid::drag", liquid.drag)?;
        }
        Ok(())
    }

    /// The zone's force on a body of mass `mass`, gravity scale `scale`,
    /// drag area `drag_area`, moving at `v`, of which `inside` (0 to 1)
    /// is in the zone and `submerged` square metres are in its liquid; the
    /// world's gravity `world_g`. A drag never more than stops the body
    /// (relative to the air) within `dt`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn force(
        &self,
        mass: f32,
        scale: f32,
        drag_area: f32,
        v: Vec2,
        inside: f32,
        submerged: f32,
        world_g: Vec2,
        dt: f32,
    ) -> Vec2 {
        let local_g = self.gravity.unwrap_or(world_g);
        let mut force = Vec2::ZERO;
        if let Some(g) = self.gravity {
            force += mass * scale * inside * (g - world_g);
        }
        // A drag force f on the body's relative velocity `rel`, capped so
        // that over `dt` it removes at most `rel`.
        let capped = |f: Vec2, rel: Vec2| {
            let most = rel.length() * mass / dt;
            f.clamp_length_max(most)
        };
        if let Some(wind) = self.wind {
            let rel = wind.velocity - v;
            let f = 0.5 * wind.density * drag_area * inside * rel.length() * rel;
            force += capped(f, rel);
        }
        if let Some(rate) = self.drag {
            force += capped(-rate * inside * mass * v, -v);
        }
        if let Some(liquid) = self.liquid {
            force -= liquid.density * submerged * local_g;
            if submerged > 0.0 {
                force += capped(-liquid.drag * inside * mass * v, -v);
            }
        }
        force
    }
}

/// The area of `shape` at `centre` inside the box from `min` to `max`,
/// square metres: exact for circles, boxes and capsules (a rounded box
/// cut by a box is boxes and quarter discs cut by boxes). Other shapes
/// (level-only, never dynamic) count by their bounding box.
pub(crate) fn area_inside(shape: &Shape, centre: Vec2, min: Vec2, max: Vec2) -> f32 {
    // In the shape's frame.
    let (lo, hi) = (min - centre, max - centre);
    let rect = |h: Vec2| box_inside(-h, h, lo, hi);
    match shape {
        Shape::Circle { .. } | Shape::Box { .. } | Shape::Capsule { .. } => {
            let (core, r) = shape.rounded();
            let mut area =
                rect(core + Vec2::new(r, 0.0)) + rect(core + Vec2::new(0.0, r)) - rect(core);
            if r > 0.0 {
                for sx in [-1.0f32, 1.0] {
                    for sy in [-1.0f32, 1.0] {
                        // The quarter disc at this corner of the core: the
                        // disc there cut by the quadrant away from the core,
                        // and by the zone.
                        let at = Vec2::new(sx * core.x, sy * core.y);
                        let far = at + Vec2::new(sx, sy) * r;
                        let (qmin, qmax) = (at.min(far).max(lo), at.max(far).min(hi));
                        if qmin.cmplt(qmax).all() {
                            area += disc_inside(r, qmin - at, qmax - at);
                        }
                    }
                }
            }
            area
        }
        _ => rect(shape.half_extents()),
    }
}

/// Area of the box `[a0, a1]` inside the box `[b0, b1]`.
fn box_inside(a0: Vec2, a1: Vec2, b0: Vec2, b1: Vec2) -> f32 {
    let size = (a1.min(b1) - a0.max(b0)).max(Vec2::ZERO);
    size.x * size.y
}

/// Area of the disc of radius `r` at the origin inside the box `[lo, hi]`.
fn disc_inside(r: f32, lo: Vec2, hi: Vec2) -> f32 {
    let r = r as f64;
    let c = |x: f32, y: f32| disc_below_left(r, x as f64, y as f64);
    let area = c(hi.x, hi.y) - c(lo.x, hi.y) - c(hi.x, lo.y) + c(lo.x, lo.y);
    area.max(0.0) as f32
}

/// Area of the disc of radius `r` at the origin where `X <= x` and
/// `Y <= y`: the integral over X of the disc's height below `y`.
fn disc_below_left(r: f64, x: f64, y: f64) -> f64 {
    // The integral of the half height s(t) = sqrt(r^2 - t^2).
    let g = |t: f64| {
        let t = t.clamp(-r, r);
        0.5 * (t * libm::sqrt(r * r - t * t) + r * r * libm::asin(t / r))
    };
    let x = x.clamp(-r, r);
    if y <= -r || x <= -r {
        return 0.0;
    }
    if y >= r {
        return 2.0 * (g(x) - g(-r));
    }
    // Where the disc's edge crosses Y = y.
    let x0 = libm::sqrt(r * r - y * y);
    // Between -x0 and x0 the height is s + y; outside, 2 s above the
    // centre line (y >= 0) and nothing below it.
    let mid = |a: f64, b: f64| (g(b) - g(a)) + y * (b - a);
    let side = |a: f64, b: f64| if y >= 0.0 { 2.0 * (g(b) - g(a)) } else { 0.0 };
    let mut area = side(-r, x.min(-x0));
    if x > -x0 {
        area += mid(-x0, x.min(x0));
    }
    if x > x0 {
        area += side(x0, x);
    }
    area
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The area inside by sampling a fine grid of points.
    fn sampled(shape: &Shape, centre: Vec2, min: Vec2, max: Vec2) -> f32 {
        let h = shape.half_extents();
        let n = 800;
        let mut inside = 0u64;
        for i in 0..n {
            for j in 0..n {
                let p = centre - h
                    + Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32) * 2.0 * h;
                let in_zone = p.cmpge(min).all() && p.cmple(max).all();
                let (core, r) = shape.rounded();
                let d = ((p - centre).abs() - core).max(Vec2::ZERO).length();
                if in_zone && d <= r {
                    inside += 1;
                }
            }
        }
        inside as f32 / (n * n) as f32 * 4.0 * h.x * h.y
    }

    #[test]
    fn the_area_inside_a_zone_matches_a_fine_sampling() {
        let shapes = [
            Shape::circle(0.5),
            Shape::rect(1.0, 0.6),
            Shape::capsule(0.3, 1.4),
            Shape::capsule(1.2, 0.4),
        ];
        let zones = [
            (Vec2::new(-5.0, -5.0), Vec2::new(5.0, 0.1)),
            (Vec2::new(-5.0, -5.0), Vec2::new(5.0, -0.3)),
            (Vec2::new(0.2, -5.0), Vec2::new(5.0, 5.0)),
            (Vec2::new(-0.2, -0.1), Vec2::new(0.3, 0.25)),
            (Vec2::new(-5.0, -5.0), Vec2::new(5.0, 5.0)),
            (Vec2::new(2.0, 2.0), Vec2::new(5.0, 5.0)),
        ];
        for shape in shapes {
            for (min, max) in zones {
                let exact = area_inside(&shape, Vec2::ZERO, min, max);
                let grid = sampled(&shape, Vec2::ZERO, min, max);
                assert!(
                    (exact - grid).abs() < 2e-3,
                    "{shape:?} in {min}..{max}: {exact} against {grid}"
                );
            }
            let whole = area_inside(&shape, Vec2::ZERO, Vec2::splat(-9.0), Vec2::splat(9.0));
            assert!((whole - shape.area()).abs() < 1e-5 * shape.area().max(1.0));
        }
    }

    #[test]
    fn a_disc_cut_by_a_surface_has_the_segment_area() {
        // A disc of radius 1 with its centre `d` below the surface: the
        // part under it is pi - (acos(d) - d sqrt(1 - d^2)) for d < 0 ...
        for d in [-0.9f32, -0.5, 0.0, 0.3, 0.99] {
            let under = area_inside(
                &Shape::circle(1.0),
                Vec2::ZERO,
                Vec2::splat(-5.0),
                Vec2::new(5.0, d),
            );
            let d = d as f64;
            let segment_above = d.acos() - d * (1.0 - d * d).sqrt();
            let exact = std::f64::consts::PI - segment_above;
            assert!(
                (under as f64 - exact).abs() < 1e-5,
                "surface at {d}: {under} against {exact}"
            );
        }
    }
}
