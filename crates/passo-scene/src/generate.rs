//! Generators: many bodies from one template.

use crate::format::{BodySpec, Generator};
use passo_physics::glam::Vec2;

/// A small deterministic generator (xorshift64*): the same seed gives the
/// same scene on every machine.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed ^ 0x9E37_79B9_7F4A_7C15 | 1)
    }

    /// Uniform in `[-1, 1)`.
    fn signed_unit(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40;
        bits as f32 / (1u64 << 23) as f32 - 1.0
    }
}

/// Calls `place` with the template and the position of every body the
/// generator makes, in a fixed order.
pub(crate) fn generate(g: &Generator, mut place: impl FnMut(&BodySpec, Vec2)) {
    match g {
        Generator::Grid {
            origin,
            columns,
            rows,
            spacing,
            body,
        } => {
            for row in 0..*rows {
                for col in 0..*columns {
                    let offset = Vec2::new(col as f32, row as f32) * *spacing;
                    place(body, *origin + offset + body.position);
                }
            }
        }
        Generator::Pyramid {
            base,
            origin,
            gap,
            body,
        } => {
            let half = body
                .shape
                .map(|s| s.half_extents())
                .unwrap_or(Vec2::splat(0.5));
            let step = 2.0 * half.x + gap;
            for row in 0..*base {
                let n = base - row;
                for i in 0..n {
                    let x = (i as f32 - (n - 1) as f32 * 0.5) * step;
                    let y = half.y + row as f32 * 2.0 * half.y;
                    place(body, *origin + Vec2::new(x, y) + body.position);
                }
            }
        }
        Generator::Rain {
            count,
            origin,
            columns,
            spacing,
            jitter,
            seed,
            body,
        } => {
            let mut rng = Rng::new(*seed);
            for k in 0..*count {
                let cell = Vec2::new((k % columns) as f32, (k / columns) as f32);
                let shake = Vec2::new(rng.signed_unit(), rng.signed_unit()) * *jitter;
                place(body, *origin + cell * *spacing + shake + body.position);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use passo_physics::Shape;

    fn positions(g: &Generator) -> Vec<Vec2> {
        let mut out = Vec::new();
        generate(g, |_, p| out.push(p));
        assert_eq!(out.len() as u64, g.count());
        out
    }

    #[test]
    fn a_pyramid_rests_on_its_origin_edge_to_edge() {
        let g = Generator::Pyramid {
            base: 3,
            origin: Vec2::new(10.0, 0.0),
            gap: 0.0,
            body: BodySpec {
                shape: Some(Shape::rect(1.0, 0.5)),
                ..Default::default()
            },
        };
        assert_eq!(
            positions(&g),
            [
                Vec2::new(9.0, 0.25),
                Vec2::new(10.0, 0.25),
                Vec2::new(11.0, 0.25),
                Vec2::new(9.5, 0.75),
                Vec2::new(10.5, 0.75),
                Vec2::new(10.0, 1.25),
            ]
        );
    }

    #[test]
    fn grid_and_rain_follow_their_spacing_and_seed() {
        let body = BodySpec {
            position: Vec2::new(0.0, 100.0),
            ..Default::default()
        };
        let grid = Generator::Grid {
            origin: Vec2::ZERO,
            columns: 2,
            rows: 2,
            spacing: Vec2::new(1.0, 3.0),
            body: body.clone(),
        };
        assert_eq!(
            positions(&grid),
            [
                Vec2::new(0.0, 100.0),
                Vec2::new(1.0, 100.0),
                Vec2::new(0.0, 103.0),
                Vec2::new(1.0, 103.0)
            ]
        );
        let rain = |seed| Generator::Rain {
            count: 50,
            origin: Vec2::ZERO,
            columns: 10,
            spacing: Vec2::splat(2.0),
            jitter: 0.5,
            seed,
            body: BodySpec::default(),
        };
        let a = positions(&rain(7));
        assert_eq!(a, positions(&rain(7)), "same seed, same scene");
        assert_ne!(a, positions(&rain(8)));
        for (k, p) in a.iter().enumerate() {
            let cell = Vec2::new((k % 10) as f32, (k / 10) as f32) * 2.0;
            assert!((*p - cell).abs().max_element() <= 0.5, "{k}: {p}");
        }
    }
}
