//! What a game asks the world: contacts, events, and shape queries (points,
//! boxes, rays and swept shapes), each with a filter.

pub(crate) mod mover;
pub(crate) mod diagnostics;

use crate::body::store::BodyMeta;
use crate::collision::broad_phase::BroadPhase;
use crate::contact::constraint::{Constraint, ContactInfo};
use crate::geometry::cast::cast_shape;
use crate::geometry::manifold::collide;
use crate::geometry::ray::{ray_shape, shape_contains};
use crate::world::query_cache::QueryIndex;
use crate::{Aabb, BodyId, BodyKind, Contact, ContactEvents, SensorPair, Shape, World};
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

/// The first body a swept shape meets ([`World::cast_shape`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeHit {
    /// The body met.
    pub body: BodyId,
    /// How far along the translation the shape got, in `[0, 1]`: it touches
    /// the body at `start + fraction * translation`.
    pub fraction: f32,
    /// Where they touch, on the body's surface.
    pub point: Vec2,
    /// The body's outward normal there (pointing back at the swept shape).
    pub normal: Vec2,
}

/// Which bodies a query sees. The default sees every shaped body;
/// `QueryFilter::solid().excluding(player)` is what a game usually wants
/// for its player's rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct QueryFilter {
    /// A body to leave out (the one casting). Default none.
    pub exclude: Option<BodyId>,
    /// Whether sensors count. Default `true`.
    pub sensors: bool,
    /// The layers to see: a body is seen when `layers & mask != 0` for its
    /// [`CollisionFilter::layers`](crate::CollisionFilter::layers). Default
    /// all.
    pub mask: u32,
    /// Whether one-way platforms stop rays and casts only as they stop
    /// bodies: from their solid side, moving against it, and never a ray
    /// or cast that starts inside one (deeper than a body landing on it,
    /// [`ONE_WAY_DEPTH`](crate::constants::ONE_WAY_DEPTH)).
    /// While the excluded body drops through one-way platforms
    /// ([`World::drop_through`]), they stop nothing. Default `false`
    /// (every side of a one-way platform is solid to a query);
    /// [`solid`](Self::solid) sets it. Point and box queries ignore it.
    pub one_way: bool,
}

impl Default for QueryFilter {
    fn default() -> Self {
        Self {
            exclude: None,
            sensors: true,
            mask: u32::MAX,
            one_way: false,
        }
    }
}

impl QueryFilter {
    /// Every shaped body but sensors, with one-way platforms solid only
    /// from their solid side (see [`one_way`](Self::one_way)): what a
    /// body of the world would meet.
    pub fn solid() -> Self {
        Self {
            sensors: false,
            one_way: true,
            ..Self::default()
        }
    }

    /// The same filter, with one-way platforms solid only from their solid
    /// side (`true`) or from every side (`false`); see
    /// [`one_way`](Self::one_way).
    pub fn with_one_way(self, one_way: bool) -> Self {
        Self { one_way, ..self }
    }

    /// The same filter, leaving out `body`.
    pub fn excluding(self, body: BodyId) -> Self {
        Self {
            exclude: Some(body),
            ..self
        }
    }

    /// The same filter, seeing only bodies on `mask`'s layers.
    pub fn with_mask(self, mask: u32) -> Self {
        Self { mask, ..self }
    }

    fn admits(&self, meta: &BodyMeta) -> bool {
        self.exclude != Some(meta.id)
            && (self.sensors || !meta.sensor)
            && meta.filter.layers & self.mask != 0
    }
}

static NO_EVENTS: ContactEvents = ContactEvents {
    step: 0,
    begin: Vec::new(),
    end: Vec::new(),
    sensor_begin: Vec::new(),
    sensor_end: Vec::new(),
};

/// A shaped body a query found: its id, shape and position, its cold data,
/// and its index in the dynamic arrays (`None` for a static body).
#[derive(Clone, Copy)]
pub(crate) struct Found<'a> {
    pub id: BodyId,
    pub shape: Shape,
    pub position: Vec2,
    pub meta: &'a BodyMeta,
    pub dynamic: Option<usize>,
}

impl World {
    /// Every contact after the last step, in a fixed order (by body ids,
    /// the solved ones first, then those between sleeping bodies),
    /// speculative ones included (see [`Contact::touching`]).
    pub fn contacts(&self) -> impl Iterator<Item = Contact> + '_ {
        self.contacts
            .iter()
            .flat_map(|cw| cw.all_contacts())
            .map(|(c, info)| public_contact(c, info))
    }

    /// How many of the last step's contacts have an awake body: those the
    /// solver worked on, and those of an island that woke at the end of
    /// the step (solved from the next). The rest (between sleeping bodies,
    /// or sleeping and static ones) are kept but cost no solver work.
    pub fn solved_contacts(&self) -> usize {
        self.contacts.as_ref().map_or(0, |cw| cw.solved.len())
    }

    /// The contacts of one body, each seen from it (`contact.a == id`, the
    /// normal pointing away from it), in the order of [`contacts`](Self::contacts).
    /// It costs what the body has, not what the world has: the first call
    /// after a step sorts the step's contacts by body once.
    pub fn contacts_of(&self, id: BodyId) -> impl Iterator<Item = Contact> + use<> {
        let mut found = Vec::new();
        if let (Some(cw), true) = (&self.contacts, self.contains(id)) {
            let mut index = self.query_cache.lock();
            let pairs = cw
                .all_contacts()
                .map(|(_, info)| (info.id_a.index(), info.id_b.index()));
            // The lists change with steps, wakes, removals and restores.
            let version = (self.stats.steps, self.revisions.edits, cw.revision());
            index.update_contacts(version, self.slots.len(), pairs);
            for &k in index.contacts_of(id.index()) {
                let Some((c, info)) = cw.contact_at(k as usize) else {
                    continue;
                };
                // The whole id, generation included: a body that reuses the
                // slot of one removed since the step has none of its contacts.
                let contact = public_contact(c, info);
                if contact.a == id {
                    found.push(contact);
                } else if contact.b == id {
                    found.push(contact.flipped());
                }
            }
        }
        found.into_iter()
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
        let min_cos = libm::cosf(max_slope);
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

    /// Contact and sensor events of the last step (its number is
    /// [`ContactEvents::step`]). Read them after each step inside the tick
    /// loop; a game that reads once per frame compares `step` with the last
    /// one it handled, since a frame may run no tick (the same events
    /// again) or several (only the last step's are here).
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
    /// (sensors, pairs of static or kinematic bodies and pairs a joint
    /// keeps from colliding excluded), metres,
    /// measured from exact geometry at the current positions, not from the
    /// solver's contact data. Finds candidates with a fresh broad phase: a
    /// diagnostic, it allocates.
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
        let mut apart = Vec::new();
        self.joints.apart(&mut apart);
        let joined = |a: BodyId, b: BodyId| {
            apart
                .binary_search(&crate::contact::constraint::key(a, b))
                .is_ok()
        };
        let mut deepest = 0.0f32;
        for (i, j) in pairs {
            let (a, b) = (&bodies[i as usize], &bodies[j as usize]);
            if (a.kind != BodyKind::Dynamic && b.kind != BodyKind::Dynamic)
                || !a.filter.allows(&b.filter)
                || joined(a.id, b.id)
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
        self.query_point_with(point, &QueryFilter::default())
    }

    /// [`query_point`](Self::query_point) with a filter.
    pub fn query_point_with(&self, point: Vec2, filter: &QueryFilter) -> Vec<BodyId> {
        let area = Aabb {
            min: point,
            max: point,
        };
        let mut found = Vec::new();
        self.candidates(&area, filter, |f| {
            if shape_contains(&f.shape, f.position, point) {
                found.push(f.id);
            }
        });
        found.sort_unstable();
        found
    }

    /// Shaped bodies whose bounding box overlaps `aabb`, in id order.
    pub fn query_aabb(&self, aabb: Aabb) -> Vec<BodyId> {
        self.query_aabb_with(aabb, &QueryFilter::default())
    }

    /// [`query_aabb`](Self::query_aabb) with a filter.
    pub fn query_aabb_with(&self, aabb: Aabb, filter: &QueryFilter) -> Vec<BodyId> {
        let mut found = Vec::new();
        self.candidates(&aabb, filter, |f| found.push(f.id));
        found.sort_unstable();
        found
    }

    /// The closest shaped body along the ray from `origin` in `direction`
    /// (any length but zero) within `max_distance` metres; on equal
    /// distances the lower id. A ray starting inside a shape hits it at
    /// distance 0. Returns `None` for a zero or non-finite direction, and
    /// for an origin that is not finite or lies farther from the world's
    /// origin than any body may ([`MAX_COORDINATE`] along either axis).
    ///
    /// [`MAX_COORDINATE`]: crate::constants::MAX_COORDINATE
    pub fn ray_cast(&self, origin: Vec2, direction: Vec2, max_distance: f32) -> Option<RayHit> {
        self.ray_cast_with(origin, direction, max_distance, &QueryFilter::default())
    }

    /// [`ray_cast`](Self::ray_cast) with a filter: leave out the body
    /// casting, sensors, or layers. It searches the world's trees, so its
    /// cost grows with what lies near the ray, not with the world.
    pub fn ray_cast_with(
        &self,
        origin: Vec2,
        direction: Vec2,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Option<RayHit> {
        let dir = crate::body::def::unit_direction(direction)?;
        let origin = crate::error::position("ray origin", origin).ok()?;
        if max_distance.is_nan() || max_distance < 0.0 {
            return None;
        }
        let mut best: Option<RayHit> = None;
        let one_way = self.one_way_rule(filter);
        let mut consider = |f: Found| {
            let limit = best.map_or(max_distance, |h| h.distance);
            let (t, normal) = ray_shape(&f.shape, f.position, origin, dir, limit)?;
            // A ray starting inside a one-way platform passes through it,
            // as a body inside one does.
            if !one_way.stops(&f, normal, || t > 0.0 || !inside_one_way(&f, origin)) {
                return None;
            }
            let better = best.is_none_or(|h| (t, f.id) < (h.distance, h.body));
            if better {
                best = Some(RayHit {
                    body: f.id,
                    distance: t,
                    point: origin + dir * t,
                    normal,
                });
            }
            Some(best.map_or(t, |h| h.distance))
        };
        let index = self.trees();
        for (tree, statics) in [(&index.statics, true), (&index.moving, false)] {
            tree.ray(origin, dir, max_distance, |item| {
                let f = self.found(&index, item, statics, filter)?;
                consider(f)
            });
        }
        best
    }

    /// Sweeps `shape` from `start` along `translation` and returns the first
    /// body it meets (on equal fractions the lower id): where they touch and
    /// the body's normal there. Exact (closed-form times of impact). A shape
    /// that starts overlapping a body meets it at fraction 0; one that only
    /// grazes a body (touches without overlapping) does not meet it. Returns
    /// `None` for a start or an end (`start + translation`) that is not
    /// finite or lies farther from the world's origin than any body may
    /// ([`MAX_COORDINATE`](crate::constants::MAX_COORDINATE) along either
    /// axis), and for an invalid shape.
    pub fn cast_shape(
        &self,
        shape: &Shape,
        start: Vec2,
        translation: Vec2,
        filter: &QueryFilter,
    ) -> Option<ShapeHit> {
        let within = |p| crate::error::position("cast", p).is_ok();
        if !(within(start) && within(start + translation)) || shape.validate().is_err() {
            return None;
        }
        let half = shape.half_extents();
        let swept =
            Aabb::from_centre(start, half).union(&Aabb::from_centre(start + translation, half));
        let mut best: Option<ShapeHit> = None;
        let one_way = self.one_way_rule(filter);
        self.candidates(&swept, filter, |f| {
            if let Some(hit) = cast_shape(shape, start, translation, &f.shape, f.position)
                && one_way.stops(&f, hit.normal, || {
                    hit.fraction > 0.0 || on_solid_side(shape, start, &f)
                })
                && best.is_none_or(|b| (hit.fraction, f.id) < (b.fraction, b.body))
            {
                best = Some(ShapeHit {
                    body: f.id,
                    fraction: hit.fraction,
                    point: hit.point,
                    normal: hit.normal,
                });
            }
        });
        best
    }

    /// How a query with `filter` treats one-way platforms.
    fn one_way_rule(&self, filter: &QueryFilter) -> OneWayRule {
        if !filter.one_way {
            return OneWayRule::Solid;
        }
        let dropping = filter
            .exclude
            .and_then(|id| self.dynamic_index(id).ok().flatten())
            .is_some_and(|i| self.dynamic.meta[i].drop_through > 0.0);
        if dropping {
            OneWayRule::PassThrough
        } else {
            OneWayRule::SolidSide
        }
    }

    /// The query index with its trees up to date.
    fn trees(&self) -> std::sync::MutexGuard<'_, QueryIndex> {
        let mut index = self.query_cache.lock();
        index.update_trees(
            &self.dynamic,
            &self.statics,
            self.query_version(),
            self.revisions.static_edits,
        );
        index
    }

    /// Calls `f` with every shaped body the filter admits whose bounding
    /// box overlaps `area`.
    pub(crate) fn candidates(
        &self,
        area: &Aabb,
        filter: &QueryFilter,
        mut f: impl FnMut(Found<'_>),
    ) {
        let index = self.trees();
        for (tree, statics) in [(&index.statics, true), (&index.moving, false)] {
            tree.query(area, |item| {
                if let Some(found) = self.found(&index, item, statics, filter) {
                    f(found);
                }
            });
        }
    }

    /// The body behind a tree item, if the filter admits it.
    fn found(
        &self,
        index: &QueryIndex,
        item: u32,
        statics: bool,
        filter: &QueryFilter,
    ) -> Option<Found<'_>> {
        let (meta, position, dynamic) = if statics {
            let i = index.static_item(item);
            (&self.statics.meta[i], self.statics.pos[i], None)
        } else {
            let i = index.moving_item(item);
            (&self.dynamic.meta[i], self.dynamic.pos.at(i), Some(i))
        };
        filter.admits(meta).then(|| Found {
            id: meta.id,
            shape: meta.shape.expect("tree items have shapes"),
            position,
            meta,
            dynamic,
        })
    }

    /// The version of the world queries index: steps taken and edits made.
    fn query_version(&self) -> (u64, u64) {
        (self.stats.steps, self.revisions.edits)
    }
}

/// How a ray or cast treats one-way platforms (see [`QueryFilter::one_way`]).
#[derive(Clone, Copy)]
enum OneWayRule {
    /// Solid from every side.
    Solid,
    /// Solid from their solid side only.
    SolidSide,
    /// Not there (the body casting drops through them).
    PassThrough,
}

impl OneWayRule {
    /// Whether a hit on `f` with `normal` (out of `f`) stops the query;
    /// `outside`: whether the query started outside `f` (or no deeper in
    /// it than a body landing on it).
    fn stops(self, f: &Found<'_>, normal: Vec2, outside: impl FnOnce() -> bool) -> bool {
        let Some(solid) = f.meta.one_way else {
            return true;
        };
        match self {
            Self::Solid => true,
            Self::SolidSide => normal.dot(solid) > 0.0 && outside(),
            Self::PassThrough => false,
        }
    }
}

/// Whether `point` lies inside one-way platform `f` deeper than a body
/// landing on it ([`ONE_WAY_DEPTH`](crate::constants::ONE_WAY_DEPTH) below
/// its solid face).
fn inside_one_way(f: &Found<'_>, point: Vec2) -> bool {
    let solid = f.meta.one_way.unwrap_or(Vec2::Y);
    shape_contains(
        &f.shape,
        f.position,
        point + solid * crate::constants::ONE_WAY_DEPTH,
    )
}

/// Whether `shape` at `at`, overlapping one-way platform `f`, lies on its
/// solid side no deeper than a body landing on it
/// ([`ONE_WAY_DEPTH`](crate::constants::ONE_WAY_DEPTH)).
fn on_solid_side(shape: &Shape, at: Vec2, f: &Found<'_>) -> bool {
    let solid = f.meta.one_way.unwrap_or(Vec2::Y);
    collide(shape, at, &f.shape, f.position, 0.0).is_none_or(|m| {
        // `m.normal` points from the shape to the platform.
        -m.normal.dot(solid) > 0.0 && m.separation >= -crate::constants::ONE_WAY_DEPTH
    })
}

/// A contact as the game sees it.
fn public_contact(c: &Constraint, info: &ContactInfo) -> Contact {
    Contact {
        a: info.id_a,
        b: info.id_b,
        normal: c.normal,
        separation: info.separation,
        points: info.points,
        point_count: info.point_count,
        normal_impulse: c.normal_impulse,
        tangent_impulse: c.tangent_impulse,
        touching: info.is_touching(c),
    }
}
