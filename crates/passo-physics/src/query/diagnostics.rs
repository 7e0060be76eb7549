//! What a world can tell about itself without changing: the model force
//! on a body, energy, momentum, and a hash of the state.

use crate::BodyId;
use crate::body::store::BodyParams;
use crate::forces::models::{Dissipation, Drive, potential_energy};
use crate::world::{Location, World};
use glam::Vec2;

impl World {
    // ----- diagnostics -----

    /// The force the world's force models exert on a body in its current
    /// state, newtons: weight, drag, friction, fields, springs, custom
    /// models, in their plain form (not the forces game code applied). For
    /// drawing force vectors; zero for a static or kinematic body.
    pub fn model_force(&self, id: BodyId) -> Option<Vec2> {
        let i = match self.locate(id)? {
            Location::Dynamic(i) if !self.dynamic.meta[i as usize].kinematic => i as usize,
            _ => return Some(Vec2::ZERO),
        };
        let b = &self.dynamic;
        let params = BodyParams {
            inv_mass: b.inv_mass[i],
            force: Vec2::ZERO,
            drag_area: b.drag_area[i],
            friction: b.friction[i],
            friction_force: 0.0,
        };
        let drive = Drive::new(&self.settings().forces, &self.custom);
        let dissipation = Dissipation::new(&self.settings().forces, false);
        let a = drive.accel(b.pos.at(i), b.vel.at(i), &params)
            + dissipation.accel(b.vel.at(i), &params);
        Some(a * b.meta[i].mass)
    }

    /// The dynamic bodies that have a mass (not the kinematic ones), in
    /// storage order: what the energies and the momentum sum over.
    fn movable(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.dynamic.len()).filter(|&i| !self.dynamic.meta[i].kinematic)
    }

    /// Kinetic energy `sum 1/2 m |v|^2` of the dynamic bodies (kinematic
    /// ones have no finite mass), joules (summed in f64, in storage order).
    pub fn kinetic_energy(&self) -> f64 {
        self.movable()
            .map(|i| {
                0.5 * f64::from(self.dynamic.meta[i].mass)
                    * f64::from(self.dynamic.vel.at(i).length_squared())
            })
            .sum()
    }

    /// Potential energy of the conservative force models, joules: gravity
    /// (`-m g . p`, zero at the origin), the force field, the spring,
    /// central gravity and custom models.
    pub fn potential_energy(&self) -> f64 {
        self.movable()
            .map(|i| {
                potential_energy(
                    &self.settings().forces,
                    &self.custom,
                    self.dynamic.pos.at(i),
                    self.dynamic.meta[i].mass,
                )
            })
            .sum()
    }

    /// Kinetic plus potential energy, joules.
    pub fn total_energy(&self) -> f64 {
        self.kinetic_energy() + self.potential_energy()
    }

    /// Linear momentum `sum m v`, kilogram metres per second (f64).
    pub fn momentum(&self) -> [f64; 2] {
        let mut p = [0.0f64; 2];
        for i in self.movable() {
            let m = f64::from(self.dynamic.meta[i].mass);
            p[0] += m * f64::from(self.dynamic.vel.at(i).x);
            p[1] += m * f64::from(self.dynamic.vel.at(i).y);
        }
        p
    }

    /// A 64-bit FNV-1a hash of every body's position and velocity bits, in
    /// id order. Equal states give equal hashes on every platform; use it to
    /// check determinism.
    pub fn state_hash(&self) -> u64 {
        let mut h = StateHasher::new();
        for b in self.bodies() {
            for x in [b.position.x, b.position.y, b.velocity.x, b.velocity.y] {
                h.write_u32(x.to_bits());
            }
        }
        h.finish()
    }
}

/// 64-bit FNV-1a over little-endian bytes: the hash of
/// [`World::state_hash`], for a game to fold its own state (or several
/// worlds) into one checksum the same way on every platform.
///
/// ```
/// use passo_physics::{StateHasher, World};
///
/// let mut h = StateHasher::new();
/// h.write_u64(World::default().state_hash());
/// h.write_u32(7); // the game's own state: a score, a tick
/// let checksum = h.finish();
/// # let _ = checksum;
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StateHasher(u64);

impl StateHasher {
    /// FNV-1a's 64-bit offset basis.
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    /// FNV-1a's 64-bit prime.
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    /// A hasher that has eaten nothing.
    pub const fn new() -> Self {
        Self(Self::OFFSET_BASIS)
    }

    /// Eats the four bytes of `word`, least significant first.
    pub fn write_u32(&mut self, word: u32) {
        for byte in word.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(Self::PRIME);
        }
    }

    /// Eats the eight bytes of `word`, least significant first.
    pub fn write_u64(&mut self, word: u64) {
        for byte in word.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(Self::PRIME);
        }
    }

    /// The hash of what was eaten.
    pub const fn finish(self) -> u64 {
        self.0
    }
}

impl Default for StateHasher {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDef, WorldSettings};

    fn ball(x: f32) -> BodyDef {
        BodyDef::point_mass(Vec2::new(x, 0.0))
    }

    #[test]
    fn model_force_is_weight_plus_drag() {
        let mut settings = WorldSettings::default();
        settings.forces.quadratic_drag = Some(crate::QuadraticDrag { density: 2.0 });
        let mut world = World::new(settings).unwrap();
        let id = world
            .add_body(BodyDef {
                mass: 3.0,
                velocity: Vec2::new(0.0, -4.0),
                drag_area: 0.5,
                ..Default::default()
            })
            .unwrap();
        // m g = -29.43 N; drag 1/2 rho v^2 CdA = 8 N upward.
        let f = world.model_force(id).unwrap();
        assert!((f - Vec2::new(0.0, -29.43 + 8.0)).length() < 1e-4, "{f}");
        world.apply_force(id, Vec2::new(100.0, 0.0));
        assert_eq!(
            world.model_force(id).unwrap().x,
            0.0,
            "game forces are not included"
        );
    }

    #[test]
    fn energy_and_momentum_diagnostics() {
        let mut world = World::default();
        world
            .add_body(BodyDef {
                mass: 2.0,
                position: Vec2::new(0.0, 10.0),
                velocity: Vec2::new(3.0, 4.0),
                ..Default::default()
            })
            .unwrap();
        assert!((world.kinetic_energy() - 25.0).abs() < 1e-9);
        assert!((world.potential_energy() - 2.0 * 9.81 * 10.0).abs() < 1e-4);
        assert_eq!(world.momentum(), [6.0, 8.0]);
    }

    #[test]
    fn equal_states_hash_equal_and_any_bit_changes_the_hash() {
        let make = |x: f32| {
            let mut w = World::default();
            w.add_body(ball(x)).unwrap();
            w
        };
        assert_eq!(make(1.0).state_hash(), make(1.0).state_hash());
        assert_ne!(
            make(1.0).state_hash(),
            make(f32::from_bits(1.0f32.to_bits() + 1)).state_hash()
        );
    }
}
