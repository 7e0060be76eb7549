//! A small platformer in a window: the level made in the Tiled editor
//! (`assets/levels/first.tmx`), a player moved by the character mover,
//! a lift, a crate, coins and a goal, and a camera that follows.
//!
//! ```text
//! cargo run --release -p passo-examples --example platformer
//! ```
//!
//! A / D or the arrow keys walk, Shift runs, Space jumps (hold it to jump
//! higher), G glides, Q turns the wind on and off. `--autopilot` plays the level by script;
//! `--frames N` runs N frames and exits, printing a line with the ticks,
//! the coins and the tick the goal was reached (`--until-goal`: or as soon
//! as the goal is reached); `--screenshot FILE` saves the last frame as a
//! PNG; `--software` draws on Mesa's lavapipe.

use passo_examples::platformer::{Keys, Platformer};
use passo_loop::{FixedTimestep, RealClock};
use passo_physics::Shape;
use passo_render::{
    AdapterChoice, Camera2D, DrawList, Gpu, Renderer, RgbaImage, WindowSurface, read_texture,
};
use std::path::PathBuf;
use std::sync::Arc;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

const BACKGROUND: [u8; 4] = [0x1b, 0x1d, 0x22, 0xff];
/// How much of the level the camera shows: 9 m tall.
const VIEW_HEIGHT: f32 = 9.0;

#[derive(Default)]
struct Options {
    frames: Option<u64>,
    screenshot: Option<PathBuf>,
    autopilot: bool,
    until_goal: bool,
    software: bool,
}

fn options() -> Result<Options, String> {
    let mut o = Options::default();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--frames" => {
                let n = args.next().ok_or("--frames needs a number")?;
                o.frames = Some(
                    n.parse()
                        .map_err(|_| format!("--frames {n}: not a number"))?,
                );
            }
            "--screenshot" => {
                o.screenshot = Some(args.next().ok_or("--screenshot needs a file")?.into())
            }
            "--autopilot" => o.autopilot = true,
            "--until-goal" => o.until_goal = true,
            "--software" => o.software = true,
            other => return Err(format!("unknown option {other}")),
        }
    }
    Ok(o)
}

/// What exists once the window is open.
struct Running {
    window: Arc<Window>,
    gpu: Gpu,
    surface: WindowSurface,
    renderer: Renderer,
    list: DrawList,
    camera: Camera2D,
}

struct App {
    options: Options,
    game: Platformer,
    timestep: FixedTimestep,
    clock: RealClock,
    keys: Keys,
    running: Option<Running>,
    presented: u64,
    shot: Option<RgbaImage>,
    error: Option<String>,
}

impl App {
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let attributes = Window::default_attributes()
            .with_title("Passo platformer")
            .with_inner_size(PhysicalSize::new(960, 600));
        let window = Arc::new(event_loop.create_window(attributes).map_err(|e| {
            format!("cannot open a window ({e}); without a display run it under xvfb-run")
        })?);
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| e.to_string())?;
        let choice = if self.options.software {
            AdapterChoice::Software
        } else {
            AdapterChoice::from_env().map_err(|e| e.to_string())?
        };
        let gpu =
            Gpu::with_instance(instance, choice, Some(&surface)).map_err(|e| e.to_string())?;
        let size = window.inner_size();
        let capture = self.options.screenshot.is_some();
        let surface = WindowSurface::new(&gpu, surface, (size.width, size.height), capture)
            .map_err(|e| e.to_string())?;
        let renderer = Renderer::new(&gpu, surface.scene_format());
        let camera = Camera2D {
            centre: self.game.player_position(),
            height: VIEW_HEIGHT,
        };
        self.running = Some(Running {
            window,
            gpu,
            surface,
            renderer,
            list: DrawList::new(BACKGROUND),
            camera,
        });
        Ok(())
    }

    fn key(&mut self, code: KeyCode, down: bool) {
        match code {
            KeyCode::KeyA | KeyCode::ArrowLeft => self.keys.left = down,
            KeyCode::KeyD | KeyCode::ArrowRight => self.keys.right = down,
            KeyCode::ShiftLeft | KeyCode::ShiftRight => self.keys.run = down,
            KeyCode::Space | KeyCode::KeyW | KeyCode::ArrowUp => self.keys.jump = down,
            KeyCode::KeyG => self.keys.glide = down,
            KeyCode::KeyQ if down => self.keys.wind = !self.keys.wind,
            _ => {}
        }
    }

    /// Runs the fixed ticks this frame asks for, then draws.
    fn frame(&mut self) -> Result<(), String> {
        let frame = self.timestep.advance(self.clock.frame_time());
        for _ in frame.tick_numbers() {
            let keys = if self.options.autopilot {
                self.game.autopilot()
            } else {
                self.keys
            };
            self.game.update(keys, frame.dt);
        }
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        // The camera follows the player, a little behind.
        let target = self.game.player_position();
        r.camera.centre += (target - r.camera.centre) * 0.1;
        r.list.clear(BACKGROUND);
        for body in self.game.world.bodies() {
            let Some(colour) = self.game.bodies.iter().find(|b| b.id == body.id) else {
                continue;
            };
            let at = self
                .game
                .world
                .interpolated_position(body.id, frame.alpha)
                .unwrap_or(body.position);
            match body.shape {
                Some(Shape::Circle { radius }) => r.list.circle(at, radius, colour.colour.0),
                Some(Shape::Box { half_extents }) => r.list.rect(at, half_extents, colour.colour.0),
                None => {}
            }
        }
        let Some(texture) = r.surface.acquire(&r.gpu.device) else {
            return Ok(());
        };
        let view = r.surface.scene_view(&texture);
        r.renderer
            .render(&view, r.surface.size(), &r.camera, &r.list);
        let last = self.options.frames.is_some_and(|n| self.presented + 1 == n)
            || (self.options.until_goal && self.game.reached.is_some());
        if last && self.options.screenshot.is_some() {
            self.shot = Some(read_texture(&r.gpu, &texture.texture).map_err(|e| e.to_string())?);
        }
        r.gpu.queue.present(texture);
        self.presented += 1;
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_none()
            && let Err(e) = self.open(event_loop)
        {
            self.error = Some(e);
            event_loop.exit();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(r) = self.running.as_mut() {
                    r.surface.resize(&r.gpu.device, (size.width, size.height));
                }
            }
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    self.key(code, event.state == ElementState::Pressed);
                }
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame() {
                    self.error = Some(e);
                    event_loop.exit();
                } else if self.options.frames.is_some_and(|n| self.presented >= n)
                    || (self.options.until_goal && self.game.reached.is_some())
                {
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}

fn main() -> Result<(), String> {
    let options = options()?;
    let scene = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/platformer.ron");
    let mut game = Platformer::load(&scene)?;
    let settings = passo_physics::WorldSettings {
        interpolation: true,
        ..*game.world.settings()
    };
    game.world
        .set_settings(settings)
        .map_err(|e| e.to_string())?;
    let mut app = App {
        options,
        game,
        timestep: FixedTimestep::from_hz(60.0).map_err(|e| e.to_string())?,
        clock: RealClock::new(),
        keys: Keys::default(),
        running: None,
        presented: 0,
        shot: None,
        error: None,
    };
    let event_loop = EventLoop::new()
        .map_err(|e| format!("cannot reach a display ({e}); without one run it under xvfb-run"))?;
    event_loop.run_app(&mut app).map_err(|e| e.to_string())?;
    if let Some(e) = app.error {
        return Err(e);
    }
    if let (Some(path), Some(shot)) = (&app.options.screenshot, &app.shot) {
        shot.save_png(path).map_err(|e| e.to_string())?;
    }
    let g = &app.game;
    let reached = g
        .reached
        .map_or("not reached".to_owned(), |t| format!("reached at tick {t}"));
    println!(
        "presented {} frames; ticks {}; coins {}; goal {reached}; player at ({}, {})",
        app.presented,
        g.tick,
        g.coins,
        g.player_position().x,
        g.player_position().y
    );
    Ok(())
}
