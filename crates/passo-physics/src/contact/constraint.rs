//! Contact rows: what the solver reads and writes of one contact, and the
//! rest of it (who, where, what restitution needs), prepared from a
//! manifold at the start of a step.

use crate::BodyId;
use crate::body::collider::ColliderRef;
use crate::body::store::{Colliders, DynamicBodies};
use crate::geometry::manifold::Manifold;
use glam::Vec2;

/// What the solver reads and writes of one contact between a dynamic body
/// A and a dynamic or static body B: kept small (56 bytes), so the passes
/// over every contact stay in cache.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Constraint {
    /// Body A: always dynamic, by its dynamic index.
    pub a: u32,
    /// Body B: dynamic or static.
    pub b: ColliderRef,
    pub normal: Vec2,
    /// Separation when the step began.
    pub base_separation: f32,
    pub inv_mass_a: f32,
    pub inv_mass_b: f32,
    /// `1 / (1/m_a + 1/m_b)`, the same for the normal and the friction row.
    pub mass: f32,
    pub friction: f32,
    pub normal_impulse: f32,
    pub tangent_impulse: f32,
    /// Push (position) impulse of the current substep (carried on from
    /// substep to substep in a deep pile).
    pub push_impulse: f32,
    pub max_normal_impulse: f32,
    /// Speed of B's surface past A's along the tangent (`normal.perp()`)
    /// that friction drives toward, m/s: zero but for a conveyor set by a
    /// pre-solve hook (see `contact::hooks`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub tangent_speed: f32,
}

/// The rest of a contact: who, where, and what restitution needs.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactInfo {
    pub id_a: BodyId,
    pub id_b: BodyId,
    /// Separation after the last substep.
    pub separation: f32,
    pub points: [Vec2; 2],
    pub point_count: u8,
    pub restitution: f32,
    /// `u = v_n + a_n h / 2` at impact (negative when approaching); zero
    /// for a pair that cannot bounce (restitution zero).
    pub impact_u: f32,
    /// `a_n h / 2` (zero for a pair that cannot bounce).
    pub half_an_h: f32,
    /// Where B was relative to A when this contact's manifold was
    /// computed: a later step keeps the contact while the two bodies stay
    /// within [`ContactSettings::reuse_distance`] of that (see
    /// `reuse::Reuse`).
    ///
    /// [`ContactSettings::reuse_distance`]: crate::ContactSettings::reuse_distance
    #[cfg_attr(feature = "serde", serde(default))]
    pub anchor: Vec2,
    /// The separation when the manifold was computed.
    #[cfg_attr(feature = "serde", serde(default))]
    pub anchor_separation: f32,
    /// Whether a later step may keep the contact: not one with a one-way
    /// platform, a kinematic body or restitution, and no change by game
    /// code to what either body collides with since.
    #[cfg_attr(feature = "serde", serde(default))]
    pub reusable: bool,
    /// How much farther apart the solver sees the two bodies than they
    /// are: a character's approach over one substep (see
    /// [`character_lead`]), zero for every other contact. The reported
    /// separation leaves it out.
    #[cfg_attr(feature = "serde", serde(default))]
    pub lead: f32,
}

const _: () = assert!(std::mem::size_of::<Constraint>() == 56);

/// The inverse masses of bodies `a` (dynamic) and `b` as a contact between
/// them is solved this step, and the contact's effective mass `1 / (1/m_a +
/// 1/m_b)`. A sleeping body holds like a static one: it is not solved this
/// step (an awake body touching it wakes its island for the next). A
/// kinematic body (inverse mass zero) holds too: contacts do not move it,
/// and gravity does not pull it.
#[inline(always)]
pub(crate) fn solver_masses(dynamic: &DynamicBodies, a: usize, b: ColliderRef) -> (f32, f32, f32) {
    let free = |i: usize| {
        if dynamic.sleep[i].is_asleep() {
            0.0
        } else {
            dynamic.inv_mass[i]
        }
    };
    let (inv_mass_a, inv_mass_b) = (free(a), b.dynamic_index().map_or(0.0, free));
    let k = inv_mass_a + inv_mass_b;
    (inv_mass_a, inv_mass_b, if k > 0.0 { 1.0 / k } else { 0.0 })
}

/// How much farther apart than it is the solver sees a contact between a
/// character (a kinematic body moved by `World::move_character`) and a
/// dynamic body: the character's approach over one substep `h`, zero for
/// any other contact.
///
/// The solver assumes each velocity lasts into the next substep, so a
/// character that ends a step closer to a body than one substep's travel
/// would push it at its own speed. The mover decides the next step's
/// velocity afresh and pushes what it walks into itself (with at most
/// `push_mass`), so the contact stops bodies coming at the character but
/// never pushes one ahead of it. (With a whole step's travel it stopped
/// crates 1 mm before they reached the character's head.)
#[inline(always)]
pub(crate) fn character_lead(
    dynamic: &DynamicBodies,
    a: usize,
    b: ColliderRef,
    normal: Vec2,
    h: f32,
) -> f32 {
    let Some(bi) = b.dynamic_index() else {
        return 0.0;
    };
    // `normal` points from A to B.
    let approach = if dynamic.meta[bi].character {
        -dynamic.vel.at(bi).dot(normal)
    } else if dynamic.meta[a].character {
        dynamic.vel.at(a).dot(normal)
    } else {
        return 0.0;
    };
    approach.max(0.0) * h
}

/// A pair's order key: the body with the lower slot index first.
pub(crate) fn key(a: BodyId, b: BodyId) -> (BodyId, BodyId) {
    if a.index() <= b.index() {
        (a, b)
    } else {
        (b, a)
    }
}

impl ContactInfo {
    /// The pair's order key (see [`key`]).
    pub(crate) fn key(&self) -> (BodyId, BodyId) {
        key(self.id_a, self.id_b)
    }

    /// Whether every number is finite, one or two points, and the
    /// restitution in `[0, 1]` and zero on a contact a step may reuse (for
    /// snapshots: a reused contact is solved as it is).
    pub(crate) fn is_valid(&self) -> bool {
        let numbers = [
            self.separation,
            self.restitution,
            self.impact_u,
            self.half_an_h,
            self.anchor_separation,
        ];
        numbers.iter().all(|x| x.is_finite())
            && self.points.iter().all(|p| p.is_finite())
            && self.anchor.is_finite()
            && matches!(self.point_count, 1 | 2)
            && (0.0..=1.0).contains(&self.restitution)
            && !(self.reusable && self.restitution > 0.0)
            && self.lead >= 0.0
            && self.lead.is_finite()
            && !(self.reusable && self.lead > 0.0)
    }

    /// The pair's order key, as the narrow phase's pairs carry it (see
    /// `body::store::pair_order`).
    #[inline(always)]
    pub(crate) fn order(&self) -> u64 {
        crate::body::store::pair_order(self.id_a.index, self.id_b.index)
    }

    /// Touching: the solver pushed the bodies apart this step, or they overlap.
    pub(crate) fn is_touching(&self, c: &Constraint) -> bool {
        (c.max_normal_impulse > 0.0) | (self.separation < 0.0)
    }
}

/// The normal velocity `u` at impact of a contact between dynamic body `a`
/// and body `b` with `normal` and `separation` (see [`Constraint::new`]),
/// and `a_n h / 2`. `holds`: whether each body holds still this step.
#[inline(always)]
pub(crate) fn impact(
    dynamic: &DynamicBodies,
    a: usize,
    b: ColliderRef,
    holds: (bool, bool),
    (normal, separation): (Vec2, f32),
    gravity: Vec2,
    h: f32,
) -> (f32, f32) {
    let vel_b = b
        .dynamic_index()
        .map_or(Vec2::ZERO, |bi| dynamic.vel.at(bi));
    let vn = (vel_b - dynamic.vel.at(a)).dot(normal);
    // Relative normal acceleration: gravity moves only the bodies that
    // are free to fall (a static or sleeping body holds).
    let falls = |holds: bool| if holds { Vec2::ZERO } else { gravity };
    let a_n = (falls(holds.1) - falls(holds.0)).dot(normal);
    let half_an_h = 0.5 * a_n * h;
    let u0 = vn + half_an_h;
    let mut impact_u = u0;
    if separation > 0.0 && (u0 < 0.0 || a_n < 0.0) {
        let u2 = u0 * u0 - 2.0 * a_n * separation;
        if u2 > 0.0 {
            impact_u = -u2.sqrt();
        }
    }
    (impact_u, half_an_h)
}

impl Constraint {
    /// The solver row and the rest of a new contact between dynamic body
    /// `a` and body `b`, from their manifold. (Inlined into the narrow
    /// phase's `pair`, whose outcome it builds.)
    #[inline(always)]
    pub(crate) fn new(
        m: &Manifold,
        a: u32,
        b: ColliderRef,
        bodies: Colliders<'_>,
        gravity: Vec2,
        h: f32,
    ) -> (Self, ContactInfo) {
        let dynamic = bodies.dynamic;
        let ai = a as usize;
        let (inv_mass_a, inv_mass_b, mass) = solver_masses(dynamic, ai, b);
        let (a_holds, b_holds) = (inv_mass_a == 0.0, inv_mass_b == 0.0);
        let (friction_b, restitution_b) = match b.dynamic_index() {
            None => {
                let s = b.index();
                (
                    bodies.statics.friction[s],
                    bodies.statics.meta[s].restitution,
                )
            }
            Some(bi) => (dynamic.friction[bi], dynamic.meta[bi].restitution),
        };
        let restitution = dynamic.meta[ai].restitution.max(restitution_b);
        // Restitution reflects the normal velocity at the moment of impact,
        // in the form the integrator conserves. With a relative normal
        // acceleration `a_n` (gravity; only a static B does not fall with A),
        // semi-implicit Euler over substeps `h` conserves exactly
        // `Q = 1/2 u^2 - a_n s` with `u = v_n + a_n h / 2`. A contact still
        // apart closes the gap `s`, so at impact `u^2 = u0^2 - 2 a_n s`; the
        // bounce sets `u <- -e u`. An elastic ball then keeps `Q`, and so its
        // height, bounce after bounce, wherever in a step the impact falls.
        // Only a pair that can bounce needs it (the restitution stage skips
        // the others), and only it reads the two velocities.
        let (impact_u, half_an_h) = if restitution > 0.0 {
            let holds = (a_holds, b_holds);
            impact(dynamic, ai, b, holds, (m.normal, m.separation), gravity, h)
        } else {
            (0.0, 0.0)
        };
        let lead = character_lead(dynamic, ai, b, m.normal, h);
        let row = Self {
            a,
            b,
            normal: m.normal,
            base_separation: m.separation + lead,
            inv_mass_a,
            inv_mass_b,
            mass,
            friction: dynamic.meta[ai].friction_mix.combine(
                bodies.meta(b).friction_mix,
                dynamic.friction[ai],
                friction_b,
            ),
            normal_impulse: 0.0,
            tangent_impulse: 0.0,
            push_impulse: 0.0,
            max_normal_impulse: 0.0,
            tangent_speed: 0.0,
        };
        let info = ContactInfo {
            id_a: dynamic.meta[ai].id,
            id_b: bodies.meta(b).id,
            separation: m.separation,
            points: m.points,
            point_count: m.point_count,
            restitution,
            impact_u,
            half_an_h,
            anchor: Vec2::ZERO,
            anchor_separation: m.separation,
            reusable: false,
            lead,
        };
        (row, info)
    }

    /// The dynamic bodies this contact moves (inverse mass above zero):
    /// A's and B's indices, `None` for a body it only reads (static,
    /// kinematic or sleeping). The solver never writes the others.
    #[inline(always)]
    pub(crate) fn moved(&self) -> (Option<usize>, Option<usize>) {
        let a = (self.inv_mass_a > 0.0).then_some(self.a as usize);
        let b = self.b.dynamic_index().filter(|_| self.inv_mass_b > 0.0);
        (a, b)
    }

    /// Whether body B is static.
    #[inline(always)]
    pub(crate) fn is_static(&self) -> bool {
        self.b.is_static()
    }

    /// Whether every number is finite, the normal a unit vector, and every
    /// mass term and the friction >= 0 (for snapshots).
    pub(crate) fn is_valid(&self) -> bool {
        let numbers = [
            self.base_separation,
            self.inv_mass_a,
            self.inv_mass_b,
            self.mass,
            self.friction,
            self.normal_impulse,
            self.tangent_impulse,
            self.push_impulse,
            self.max_normal_impulse,
            self.tangent_speed,
        ];
        numbers.iter().all(|x| x.is_finite())
            && (self.normal.length() - 1.0).abs() < 1e-3
            && self.inv_mass_a >= 0.0
            && self.inv_mass_b >= 0.0
            && self.mass >= 0.0
            && self.friction >= 0.0
    }
}

/// Contact rows and the rest of each contact, side by side, sorted by the
/// pair's key.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ContactList {
    pub rows: Vec<Constraint>,
    pub infos: Vec<ContactInfo>,
}

impl ContactList {
    pub(crate) fn len(&self) -> usize {
        self.rows.len()
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    pub(crate) fn clear(&mut self) {
        self.rows.clear();
        self.infos.clear();
    }

    pub(crate) fn push(&mut self, row: Constraint, info: ContactInfo) {
        self.rows.push(row);
        self.infos.push(info);
    }

    /// Each row with the rest of its contact.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (&Constraint, &ContactInfo)> + Clone {
        self.rows.iter().zip(&self.infos)
    }

    /// Keeps the contacts for which `keep` holds, in order, and hands the
    /// others to `removed`, in order.
    pub(crate) fn retain(
        &mut self,
        mut keep: impl FnMut(&Constraint) -> bool,
        mut removed: impl FnMut(Constraint, ContactInfo),
    ) {
        let mut kept = 0;
        for i in 0..self.rows.len() {
            let (c, info) = (self.rows[i], self.infos[i]);
            if keep(&c) {
                self.rows[kept] = c;
                self.infos[kept] = info;
                kept += 1;
            } else {
                removed(c, info);
            }
        }
        self.rows.truncate(kept);
        self.infos.truncate(kept);
    }
}

/// Adds contacts, given in key order, to a contact list sorted by key: the
/// list's old content waits in a scratch list (kept between steps, so
/// merging allocates nothing once warm).
pub(crate) struct Merge<'a> {
    list: &'a mut ContactList,
    old: &'a ContactList,
    next: usize,
}

impl<'a> Merge<'a> {
    pub(crate) fn new(list: &'a mut ContactList, scratch: &'a mut ContactList) -> Self {
        scratch.clear();
        scratch.rows.append(&mut list.rows);
        scratch.infos.append(&mut list.infos);
        Self {
            list,
            old: scratch,
            next: 0,
        }
    }

    pub(crate) fn push(&mut self, row: Constraint, info: ContactInfo) {
        let old = self.old;
        while self.next < old.len() && old.infos[self.next].key() < info.key() {
            self.list.push(old.rows[self.next], old.infos[self.next]);
            self.next += 1;
        }
        self.list.push(row, info);
    }

    pub(crate) fn finish(self) {
        self.list
            .rows
            .extend_from_slice(&self.old.rows[self.next..]);
        self.list
            .infos
            .extend_from_slice(&self.old.infos[self.next..]);
    }
}
