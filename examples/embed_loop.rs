//! Embeds the fixed-timestep loop in a minimal game with no window.
//!
//! The game renders at an uneven frame rate, with an occasional slow frame;
//! the physics still advances in exact 60 Hz ticks, and each frame prints
//! the ticks it ran and the interpolation factor it would draw with.
//!
//! Run: `cargo run -p passo-examples --example embed_loop`

use passo_loop::{FixedTimestep, Game, run_frame};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, BodyId, World, WorldSettings};
use std::time::Duration;

struct Ball {
    world: World,
    ball: BodyId,
}

impl Game for Ball {
    fn fixed_update(&mut self, dt: f32, tick: u64) {
        if tick == 0 {
            // Throw the ball: an impulse of 1 kg * (4, 6) m/s.
            self.world.apply_impulse(self.ball, Vec2::new(4.0, 6.0));
        }
        self.world.step(dt);
    }

    fn render(&mut self, alpha: f32) {
        let p = self.world.interpolated_position(self.ball, alpha).unwrap();
        println!(
            "    draw ball at ({:6.3}, {:6.3}) with alpha {alpha:.3}",
            p.x, p.y
        );
    }
}

fn main() {
    let mut world = World::new(WorldSettings {
        interpolation: true, // keep previous positions for drawing
        ..Default::default()
    })
    .expect("default settings are valid");
    let ball = world.add_body(BodyDef::default()).expect("valid body");
    let mut game = Ball { world, ball };

    let mut timestep = FixedTimestep::from_hz(60.0).expect("60 Hz is valid");
    // Frame times of a game rendering at about 90 FPS; frame 6 hitches.
    let frames_ms = [11.0, 11.5, 10.8, 11.2, 11.0, 11.3, 400.0, 11.0, 11.1, 10.9];
    for (n, ms) in frames_ms.into_iter().enumerate() {
        let frame_time = Duration::from_secs_f64(ms / 1000.0);
        println!("frame {n}: {ms} ms");
        let frame = run_frame(&mut timestep, &mut game, frame_time);
        println!(
            "    ran {} tick(s) of {:.4} s, dropped {:?}",
            frame.ticks, frame.dt, frame.dropped
        );
    }
    println!(
        "{} ticks in all; {:?} dropped by the death-spiral guard",
        timestep.tick(),
        timestep.dropped_total()
    );
}
