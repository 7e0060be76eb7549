//! Tests of `crush` on contacts built by hand: which contacts a search lets
//! go of, exactly, for presses that move off, shear, hold still or are
//! removed, and where the search stops.

use super::*;

/// What body B of a contact is.
#[derive(Clone, Copy)]
enum Other {
    /// A dynamic body, by index: a crate, or a kinematic body.
    Body(u32),
    /// The static ground (or a wall).
    Ground,
}

/// Contacts between crates, kinematic bodies and the ground, as the
/// solver holds them after the warm start: every one pushing.
#[derive(Clone, Default)]
struct Scene {
    rows: Vec<Constraint>,
    /// Per dynamic index: its velocity if it is kinematic.
    kinematic: Vec<Option<Vec2>>,
}

impl Scene {
    fn crate_(&mut self) -> u32 {
        self.kinematic.push(None);
        self.kinematic.len() as u32 - 1
    }

    fn kinematic(&mut self, velocity: Vec2) -> u32 {
        self.kinematic.push(Some(velocity));
        self.kinematic.len() as u32 - 1
    }

    /// Crate `a` pressed against `b`, the normal from `a` to `b`, with a
    /// warm-start impulse of 1 (and friction and push). Returns the row.
    fn touch(&mut self, a: u32, b: Other, normal: Vec2) -> u32 {
        let (b, inv_mass_b) = match b {
            Other::Ground => (ColliderRef::fixed(0), 0.0),
            Other::Body(k) if self.kinematic[k as usize].is_some() => {
                (ColliderRef::dynamic(k), 0.0)
            }
            Other::Body(k) => (ColliderRef::dynamic(k), 1.0),
        };
        self.rows.push(Constraint {
            a,
            b,
            normal,
            base_separation: 0.0,
            inv_mass_a: 1.0,
            inv_mass_b,
            mass: 0.5,
            friction: 0.6,
            normal_impulse: 1.0,
            tangent_impulse: 0.5,
            push_impulse: 0.25,
            max_normal_impulse: 1.0,
            tangent_speed: 0.0,
        });
        self.rows.len() as u32 - 1
    }

    /// A column of `crates` crates from `ground` along `up`: the first on
    /// the ground, each on the one before. Returns the crates, the lowest
    /// first.
    fn column(&mut self, crates: usize, up: Vec2) -> Vec<u32> {
        let mut column: Vec<u32> = Vec::new();
        for _ in 0..crates {
            let c = self.crate_();
            let below = column.last().map_or(Other::Ground, |&b| Other::Body(b));
            self.touch(c, below, -up);
            column.push(c);
        }
        column
    }

    /// Runs [`Crushes::release`] on a copy of the rows: the rows it let
    /// go of, in order. Those lose all three impulses; the rest keep theirs.
    fn released(&self) -> Vec<u32> {
        let mut rows = self.rows.clone();
        let kinematic = |b: ColliderRef| b.dynamic_index().and_then(|k| self.kinematic[k]);
        Crushes::default().release(&mut rows, self.kinematic.len(), kinematic);
        let mut released = Vec::new();
        for (r, (after, before)) in rows.iter().zip(&self.rows).enumerate() {
            if after == before {
                continue;
            }
            let impulses = (
                after.normal_impulse,
                after.tangent_impulse,
                after.push_impulse,
            );
            assert_eq!(impulses, (0.0, 0.0, 0.0), "row {r}: {after:?}");
            released.push(r as u32);
        }
        released
    }

    /// [`Crushes::released_by_removal`] of kinematic body `k`, sorted.
    fn released_by_removal(&self, k: u32) -> Vec<u32> {
        let mut crushes = Crushes::default();
        let released = crushes.released_by_removal(&self.rows, self.kinematic.len(), k);
        // No contact is listed twice (one between two crates of the column
        // is met from both sides).
        let mut sorted = released.to_vec();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), released.len(), "{released:?}");
        sorted
    }
}

fn all(rows: std::ops::Range<u32>) -> Vec<u32> {
    rows.collect()
}

#[test]
fn a_crushed_column_is_let_go_of_when_its_press_moves_and_kept_while_it_holds_still() {
    // Stacks of 1 to 3 crates on the ground, up or sideways (a wall), a
    // press on the top crate.
    for up in [Vec2::Y, Vec2::X, -Vec2::X] {
        for crates in 1..=3 {
            let mut scene = Scene::default();
            let column = scene.column(crates, up);
            let press = scene.kinematic(Vec2::ZERO);
            scene.touch(*column.last().unwrap(), Other::Body(press), up);
            let rows = scene.rows.len() as u32;
            // Off, sideways (shearing) and on, just faster than LEAVING.
            let fast = LEAVING * 1.5;
            for v in [up * fast, up.perp() * fast, -up * 5.0, Vec2::new(3.0, -4.0)] {
                scene.kinematic[press as usize] = Some(v);
                assert_eq!(
                    scene.released(),
                    all(0..rows),
                    "{crates} crates, press at {v}"
                );
            }
            // Still, or at LEAVING itself: the column holds.
            for v in [
                Vec2::ZERO,
                up * LEAVING,
                up.perp() * LEAVING,
                up * LEAVING * 0.5,
            ] {
                scene.kinematic[press as usize] = Some(v);
                assert_eq!(scene.released(), [], "{crates} crates, press at {v}");
            }
            // A press that only touches (no impulse: a speculative contact)
            // presses nothing, however it moves.
            scene.kinematic[press as usize] = Some(up * 5.0);
            scene.rows.last_mut().unwrap().normal_impulse = 0.0;
            assert_eq!(scene.released(), [], "{crates} crates, a touch");
        }
    }
}

#[test]
fn a_column_carried_by_a_lift_is_kept() {
    // Two crates on a lift going up, nothing above: the lift presses them
    // against nothing.
    let mut scene = Scene::default();
    let lift = scene.kinematic(Vec2::Y * 2.0);
    let (low, high) = (scene.crate_(), scene.crate_());
    scene.touch(low, Other::Body(lift), -Vec2::Y);
    scene.touch(high, Other::Body(low), -Vec2::Y);
    assert_eq!(scene.released(), []);
}

#[test]
fn jaws_moving_together_hold_what_they_grip_and_jaws_moving_apart_let_go() {
    // A lift below and a lid above a stack of two crates, both kinematic.
    let mut scene = Scene::default();
    let lift = scene.kinematic(Vec2::ZERO);
    let lid = scene.kinematic(Vec2::ZERO);
    let (low, high) = (scene.crate_(), scene.crate_());
    scene.touch(low, Other::Body(lift), -Vec2::Y);
    scene.touch(high, Other::Body(low), -Vec2::Y);
    scene.touch(high, Other::Body(lid), Vec2::Y);
    let up = Vec2::Y * 2.0;
    for (lift_v, lid_v, let_go) in [
        // Carried together, any way: held.
        (up, up, false),
        (Vec2::X, Vec2::X, false),
        // One still, one moving (on, off or past): let go of.
        (up, Vec2::ZERO, true),
        (Vec2::ZERO, up, true),
        (Vec2::ZERO, -up, true),
        (Vec2::X, Vec2::ZERO, true),
        // Opening or closing.
        (up, up * 2.0, true),
        (up, up * 0.5, true),
    ] {
        scene.kinematic[lift as usize] = Some(lift_v);
        scene.kinematic[lid as usize] = Some(lid_v);
        let expected = if let_go { all(0..3) } else { Vec::new() };
        assert_eq!(scene.released(), expected, "lift {lift_v}, lid {lid_v}");
    }
}

#[test]
fn each_normal_of_a_press_is_followed_its_own_way() {
    // One press moving up: on crate A (A on the ground) and, on its right,
    // against crate B, which presses C against a wall. A second press holds
    // still on crate D on the ground, and crate E rests on the ground alone.
    let mut scene = Scene::default();
    let press = scene.kinematic(Vec2::Y);
    let still = scene.kinematic(Vec2::ZERO);
    let [a, b, c, d, e] = [(); 5].map(|_| scene.crate_());
    let rows = [
        scene.touch(a, Other::Ground, -Vec2::Y),
        scene.touch(a, Other::Body(press), Vec2::Y),
        scene.touch(b, Other::Body(press), -Vec2::X),
        scene.touch(b, Other::Body(c), Vec2::X),
        scene.touch(c, Other::Ground, Vec2::X),
    ];
    scene.touch(d, Other::Ground, -Vec2::Y);
    scene.touch(d, Other::Body(still), Vec2::Y);
    scene.touch(e, Other::Ground, -Vec2::Y);
    assert_eq!(scene.released(), rows);

    // The press still, the other moving off: only D's contacts.
    scene.kinematic[press as usize] = Some(Vec2::ZERO);
    scene.kinematic[still as usize] = Some(Vec2::Y);
    assert_eq!(scene.released(), [5, 6]);
}

#[test]
fn the_pile_under_a_press_is_let_go_of_down_every_branch() {
    // A press on one crate resting on two, on three, on the ground (a
    // pyramid): every contact is let go of, whatever the order of the rows.
    let mut scene = Scene::default();
    let press = scene.kinematic(Vec2::Y * 5.0);
    let rows_of = |scene: &mut Scene| {
        let [t, m1, m2, b1, b2, b3] = [(); 6].map(|_| scene.crate_());
        for b in [b1, b2, b3] {
            scene.touch(b, Other::Ground, -Vec2::Y);
        }
        let down = Vec2::new(0.3, -1.0).normalize();
        let down_left = Vec2::new(-down.x, down.y);
        scene.touch(m1, Other::Body(b1), down_left);
        scene.touch(m1, Other::Body(b2), down);
        scene.touch(m2, Other::Body(b2), down_left);
        scene.touch(m2, Other::Body(b3), down);
        scene.touch(t, Other::Body(m1), down_left);
        scene.touch(t, Other::Body(m2), down);
        t
    };
    let top = rows_of(&mut scene);
    scene.touch(top, Other::Body(press), Vec2::Y);
    assert_eq!(scene.released(), all(0..10));
    // The same rows, the last first.
    scene.rows.reverse();
    assert_eq!(scene.released(), all(0..10));
}

#[test]
fn a_contact_at_sixty_degrees_from_the_press_carries_it_on_and_a_steeper_one_does_not() {
    // A press moving off a crate that rests on the ground through a contact
    // whose normal turns `ALONG` (cos 60 degrees) from straight down, then
    // a little more.
    for (y, carried) in [(ALONG, true), (ALONG - 1e-6, false)] {
        let mut scene = Scene::default();
        let press = scene.kinematic(Vec2::Y);
        let c = scene.crate_();
        // Not quite of length one: the search compares the dot product.
        scene.touch(c, Other::Ground, Vec2::new((1.0 - y * y).sqrt(), -y));
        scene.touch(c, Other::Body(press), Vec2::Y);
        let expected = if carried { all(0..2) } else { Vec::new() };
        assert_eq!(scene.released(), expected, "{y}");
    }
}

/// A press moving off the first of `crates` crates in a row, pressed
/// sideways against a wall by the last.
fn row_against_a_wall(crates: usize) -> Scene {
    let mut scene = Scene::default();
    let column = scene.column(crates, Vec2::X);
    let press = scene.kinematic(Vec2::X * 5.0);
    scene.touch(*column.last().unwrap(), Other::Body(press), Vec2::X);
    scene
}

#[test]
fn a_column_longer_than_the_search_is_left_as_it_is() {
    // `COLUMN` bodies are followed from one pressed body: the wall behind
    // the 256th is met, behind the 257th it is not.
    let scene = row_against_a_wall(COLUMN);
    assert_eq!(scene.released().len(), COLUMN + 1);
    let scene = row_against_a_wall(COLUMN + 1);
    assert_eq!(scene.released(), []);
}

#[test]
fn a_wide_press_follows_four_bodies_for_each_body_it_presses() {
    // A press on 100 columns of 3 crates: 300 bodies, more than `COLUMN`,
    // fewer than four for each of the 100 it presses. Every column is let
    // go of; with one crate more in each, 400 bodies are still followed,
    // and the ground under the fourth layer is met.
    for height in [3, 4] {
        let mut scene = Scene::default();
        let press = scene.kinematic(Vec2::Y);
        for _ in 0..100 {
            let column = scene.column(height, Vec2::Y);
            scene.touch(*column.last().unwrap(), Other::Body(press), Vec2::Y);
        }
        let rows = scene.rows.len() as u32;
        assert_eq!(scene.released(), all(0..rows), "{height} high");
    }
    // Five high, 500 bodies: beyond the 400 followed, nothing is met.
    let mut scene = Scene::default();
    let press = scene.kinematic(Vec2::Y);
    for _ in 0..100 {
        let column = scene.column(5, Vec2::Y);
        scene.touch(*column.last().unwrap(), Other::Body(press), Vec2::Y);
    }
    assert_eq!(scene.released(), []);
}

#[test]
fn the_search_stops_when_its_budget_is_spent() {
    // Five crates in a row against a wall, searched from the first with a
    // budget of 3, 4, 5 and 9 bodies: 5 reach the wall, and the budget is
    // spent exactly.
    let scene = row_against_a_wall(5);
    let press = ColliderRef::dynamic(5);
    for (budget, reaches) in [(3, false), (4, false), (5, true), (9, true)] {
        let mut crushes = Crushes::default();
        crushes.index(&scene.rows, 6, |c| c.normal_impulse > 0.0);
        let mut left = budget;
        let found = crushes.reaches_immovable(
            &scene.rows,
            press,
            std::iter::once(4),
            -Vec2::X,
            |_| true,
            &mut left,
        );
        assert_eq!(found, reaches, "budget {budget}");
        assert_eq!(left, budget.saturating_sub(5), "budget {budget}");
        // The bodies followed, and the one queued after them.
        assert_eq!(crushes.column, [4, 3, 2, 1, 0][..(budget + 1).min(5)]);
    }
}

#[test]
fn a_removed_press_lets_go_of_what_it_pressed_against_something_immovable() {
    // Two crates pressed into the ground, sideways into a wall, or between
    // the press and a still kinematic body: the press is removed.
    for up in [Vec2::Y, Vec2::X] {
        let mut scene = Scene::default();
        let column = scene.column(2, up);
        let press = scene.kinematic(Vec2::ZERO);
        scene.touch(column[1], Other::Body(press), up);
        // Every contact, each once.
        assert_eq!(scene.released_by_removal(press), all(0..3), "{up}");
        // The rows are the caller's: left as they were.
        let before = scene.rows.clone();
        scene.released_by_removal(press);
        assert_eq!(scene.rows, before);
        // Another kinematic body, pressing nothing, lets go of nothing.
        let other = scene.kinematic(Vec2::ZERO);
        assert_eq!(scene.released_by_removal(other), []);
        // Nor does a press that only touched the top crate.
        scene.rows[2].normal_impulse = 0.0;
        assert_eq!(scene.released_by_removal(press), []);
    }
    // On a lift, against nothing: the lift's removal lets go of nothing.
    let mut scene = Scene::default();
    let lift = scene.kinematic(Vec2::ZERO);
    let (low, high) = (scene.crate_(), scene.crate_());
    scene.touch(low, Other::Body(lift), -Vec2::Y);
    scene.touch(high, Other::Body(low), -Vec2::Y);
    assert_eq!(scene.released_by_removal(lift), []);
    // Between the lift and a still lid: all of it.
    let lid = scene.kinematic(Vec2::ZERO);
    scene.touch(high, Other::Body(lid), Vec2::Y);
    assert_eq!(scene.released_by_removal(lift), all(0..3));
}

#[test]
fn presses_from_opposite_sides_are_followed_each_its_own_way() {
    // Two presses moving off: one on the left pushing a row of two crates
    // right against a wall, one on the right pushing another row left
    // against a wall. Their normals differ only in sign along x: each is
    // followed its own way, and every contact of both rows is let go of.
    let mut scene = Scene::default();
    let left = scene.kinematic(Vec2::Y);
    let right = scene.kinematic(Vec2::Y);
    let [a1, a2, b1, b2] = [(); 4].map(|_| scene.crate_());
    // The left press pushes a1 right, a1 pushes a2, a2 meets the wall.
    // (Built as (-1, +0): `-Vec2::X` has a y of -0, other bits.)
    scene.touch(a1, Other::Body(left), Vec2::new(-1.0, 0.0));
    scene.touch(a1, Other::Body(a2), Vec2::X);
    scene.touch(a2, Other::Ground, Vec2::X);
    // The right press pushes b1 left, b1 pushes b2, b2 meets the wall.
    scene.touch(b1, Other::Body(right), Vec2::X);
    scene.touch(b1, Other::Body(b2), -Vec2::X);
    scene.touch(b2, Other::Ground, -Vec2::X);
    assert_eq!(scene.released(), all(0..6));
}
