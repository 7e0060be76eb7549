//! What a game asks the world: contacts, events, and shape queries.

use crate::broad_phase::BroadPhase;
use crate::manifold::{collide, ray_shape, shape_contains};
use crate::{Aabb, BodyId, BodyKind, Contact, ContactEvents, SensorPair, World};
use glam::Vec2;

/// The first body a ray hits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// The body hit.
    pub body: BodyId,
    /// Distance along the ray, metres.
    pub distance: f32,
    /// Where the ray entered the shape.
    pub point: Vec2,
    /// The shape's outward normal there.
    pub normal: Vec2,
}

static NO_EVENTS: ContactEvents = ContactEvents {
    begin: Vec::new(),
    end: Vec::new(),
    sensor_begin: Vec::new(),
    sensor_end: Vec::new(),
};

impl World {
    /// Every contact after the last step, in a fixed order (by body ids,
    /// the solved ones first, then those between sleeping bodies),
    /// speculative ones included (see [`Contact::touching`]).
    pub fn contacts(&self) -> impl Iterator<Item = Contact> + '_ {
        self.contacts
            .iter()
            .flat_map(|cw| cw.all_contacts())
            .map(|(c, info)| Contact {
                a: info.id_a,
                b: info.id_b,
                normal: c.normal,
                separation: info.separation,
                points: info.points,
                point_count: info.point_count,
                normal_impulse: c.normal_impulse,
                tangent_impulse: c.tangent_impulse,
                touching: info.is_touching(c),
            })
    }

    /// How many of the last step's contacts the solver worked on: those
    /// with an awake body. The rest (between sleeping bodies, or sleeping
    /// and static ones) are kept but cost no solver work.
    pub fn solved_contacts(&self) -> usize {
        self.contacts.as_ref().map_or(0, |cw| cw.solved.len())
    }

    /// The contacts of one body, each seen from it (`contact.a == id`, the
    /// normal pointing away from it).
    pub fn contacts_of(&self, id: BodyId) -> impl Iterator<Item = Contact> + '_ {
        self.contacts().filter_map(move |c| {
            if c.a == id {
                Some(c)
            } else if c.b == id {
                Some(c.flipped())
            } else {
                None
            }
        })
    }

    /// Whether the body stands on something: it touches a body whose
    /// supporting normal is within `max_slope` radians of up (up opposes
    /// gravity; +y without gravity). 0.8 rad (46°) is a common choice.
    pub fn is_standing(&self, id: BodyId, max_slope: f32) -> bool {
        self.standing_on(id, max_slope).is_some()
    }

    /// The body this one stands on (see [`is_standing`](Self::is_standing)),
    /// the one pushing it up the most if several.
    pub fn standing_on(&self, id: BodyId, max_slope: f32) -> Option<BodyId> {
        let up = -self
            .settings()
            .forces
            .gravity
            .and_then(|g| g.try_normalize())
            .unwrap_or(-Vec2::Y);
        let min_cos = max_slope.cos();
        self.contacts_of(id)
            .filter(|c| c.touching && (-c.normal).dot(up) >= min_cos)
            .max_by(|x, y| x.normal_impulse.total_cmp(&y.normal_impulse))
            .map(|c| c.b)
    }

    /// Whether the contact stage has allocated its buffers (broad phase,
    /// contacts, warm-start cache). It does so the first time it runs, so a
    /// world without colliders never holds any. (For tests of that.)
    #[doc(hidden)]
    pub fn has_contact_state(&self) -> bool {
        self.contacts.is_some()
    }

    /// Contact and sensor events of the last step.
    pub fn events(&self) -> &ContactEvents {
        self.contacts.as_ref().map_or(&NO_EVENTS, |cw| cw.events())
    }

    /// Bodies inside each sensor after the last step, sorted.
    pub fn sensor_overlaps(&self) -> &[SensorPair] {
        self.contacts
            .as_ref()
            .map_or(&[], |cw| cw.sensor_overlaps())
    }

    /// The deepest overlap between any two shaped bodies that may touch
    /// (sensors and static pairs excluded), metres, measured from exact
    /// geometry at the current positions, not from the solver's contact
    /// data. Finds candidates with a fresh broad phase: a diagnostic, it
    /// allocates.
    pub fn max_penetration(&self) -> f32 {
        let bodies: Vec<_> = self
            .bodies()
            .filter(|b| b.shape.is_some() && !b.sensor)
            .collect();
        let boxes: Vec<Aabb> = bodies
            .iter()
            .map(|b| {
                Aabb::from_centre(
                    b.position,
                    b.shape.map_or(glam::Vec2::ZERO, |s| s.half_extents()),
                )
            })
            .collect();
        let mut pairs = Vec::new();
        BroadPhase::default().find_pairs(&boxes, &[], false, &mut pairs);
        let mut deepest = 0.0f32;
        for (i, j) in pairs {
            let (a, b) = (&bodies[i as usize], &bodies[j as usize]);
            if (a.kind != BodyKind::Dynamic && b.kind != BodyKind::Dynamic)
                || !a.filter.allows(&b.filter)
            {
                continue;
            }
            let (Some(sa), Some(sb)) = (a.shape, b.shape) else {
                continue;
            };
            if let Some(m) = collide(&sa, a.position, &sb, b.position, 0.0) {
                deepest = deepest.max(-m.separation);
            }
        }
        deepest
    }

    /// Shaped bodies whose shape contains `point`, in id order.
    pub fn query_point(&self, point: Vec2) -> Vec<BodyId> {
        self.bodies()
            .filter(|b| {
                b.shape
                    .is_some_and(|s| shape_contains(&s, b.position, point))
            })
            .map(|b| b.id)
            .collect()
    }

    /// Shaped bodies whose bounding box overlaps `aabb`, in id order.
    pub fn query_aabb(&self, aabb: Aabb) -> Vec<BodyId> {
        self.bodies()
            .filter(|b| {
                b.shape.is_some_and(|s| {
                    Aabb::from_centre(b.position, s.half_extents()).overlaps(&aabb)
                })
            })
            .map(|b| b.id)
            .collect()
    }

    /// The closest shaped body along the ray from `origin` in `direction`
    /// (any length but zero) within `max_distance` metres; on equal
    /// distances the lower id. A ray starting inside a shape hits it at
    /// distance 0. Returns `None` for a zero or non-finite direction.
    pub fn ray_cast(&self, origin: Vec2, direction: Vec2, max_distance: f32) -> Option<RayHit> {
        let dir = direction.try_normalize()?;
        if !origin.is_finite() || max_distance.is_nan() || max_distance < 0.0 {
            return None;
        }
        let mut best: Option<RayHit> = None;
        for b in self.bodies() {
            let Some(shape) = b.shape else { continue };
            let limit = best.map_or(max_distance, |h| h.distance);
            if let Some((t, normal)) = ray_shape(&shape, b.position, origin, dir, limit)
                && best.is_none_or(|h| t < h.distance)
            {
                best = Some(RayHit {
                    body: b.id,
                    distance: t,
                    point: origin + dir * t,
                    normal,
                });
            }
        }
        best
    }
}
