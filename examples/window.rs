//! The platformer's window: the game of [`platformer`](crate::platformer)
//! drawn with `passo-render`, keys read with winit, a camera that follows
//! the player and a HUD. The `platformer` and `slopes` examples run it.

use crate::platformer::{Keys, Platformer, follow_camera};
use passo_loop::{FixedTimestep, RealClock};
use passo_physics::Shape;
use passo_physics::glam::Vec2;
use passo_render::{
    AdapterChoice, Camera2D, DrawList, Gpu, Renderer, RgbaImage, TextureId, WindowSurface,
    read_texture,
};
use passo_scene::LevelArt;
use std::path::PathBuf;
use std::sync::Arc;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

const BACKGROUND: [u8; 4] = [0x1b, 0x1d, 0x22, 0xff];
/// How much of the level the camera shows: 8 m tall (the shipped level
/// is 7.5 m tall, so it fits, and the camera scrolls along it).
const VIEW_HEIGHT: f32 = 8.0;
/// The HUD's colours: the coins' gold and a light grey for the time.
const HUD_GOLD: [u8; 4] = [0xf0, 0xc0, 0x30, 0xff];
const HUD_TEXT: [u8; 4] = [0xe8, 0xe8, 0xe8, 0xff];

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
    /// The texture of each of the level's images, when they all loaded
    /// and every cell has a tile; else empty, and the cells are boxes.
    textures: Vec<TextureId>,
}

struct App {
    title: String,
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
            .with_title(self.title.clone())
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
        let mut renderer = Renderer::new(&gpu, surface.scene_format());
        let textures = level_textures(&mut renderer, &self.game.art);
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
            textures,
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
        // The camera follows the player, a little behind, and never looks
        // past the level's edges.
        let (w, h) = r.surface.size();
        let view = Vec2::new(VIEW_HEIGHT * w as f32 / h.max(1) as f32, VIEW_HEIGHT);
        r.camera.centre = follow_camera(
            r.camera.centre,
            self.game.player_position(),
            view,
            self.game.bounds,
        );
        r.list.clear(BACKGROUND);
        // The level's cells as their tiles, behind everything else.
        let tiled = !r.textures.is_empty();
        if tiled {
            for tile in &self.game.art.tiles {
                r.list.sprite(
                    r.textures[tile.image],
                    tile.centre,
                    tile.half_extents,
                    tile.uv_min,
                    tile.uv_max,
                );
            }
        }
        for body in self.game.world.bodies() {
            if tiled && self.game.cell_bodies.binary_search(&body.id).is_ok() {
                continue;
            }
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
                Some(shape @ Shape::Capsule { .. }) => {
                    r.list.capsule(at, shape.half_extents(), colour.colour.0)
                }
                Some(Shape::Segment { half } | Shape::ChainSegment { half, .. }) => {
                    r.list.line(at - half, at + half, 3.0, colour.colour.0)
                }
                Some(Shape::Polygon(polygon)) => {
                    let v = polygon.vertices();
                    for (i, a) in v.iter().enumerate() {
                        let b = v[(i + 1) % v.len()];
                        r.list.line(at + *a, at + b, 3.0, colour.colour.0);
                    }
                }
                None => {}
            }
        }
        draw_hud(
            &mut r.list,
            &r.camera,
            r.surface.size(),
            (self.game.coins, self.game.coins_total),
            self.game.seconds(frame.dt),
        );
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

/// Runs the platformer in a window titled `title`, the player of `shape`
/// starting at the level's spawn point named `spawn`, with the options of
/// the command line (see the `platformer` example).
///
/// # Errors
/// A bad option, a level that does not load, or no display.
pub fn run(title: &str, spawn: &str, shape: Shape) -> Result<(), String> {
    let options = options()?;
    let scene = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/platformer.ron");
    let mut game = Platformer::load_with(&scene, spawn, shape)?;
    let settings = passo_physics::WorldSettings {
        interpolation: true,
        ..*game.world.settings()
    };
    game.world
        .set_settings(settings)
        .map_err(|e| e.to_string())?;
    let mut app = App {
        title: title.to_owned(),
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

/// The HUD, in the top-left corner: a coin and the coins taken of all
/// (`3/5`), then the seconds played (`12.4`), in seven-segment digits
/// drawn with the renderer's lines, so no font is needed. Sizes are in
/// pixels, turned into world points through the camera.
fn draw_hud(
    list: &mut DrawList,
    camera: &Camera2D,
    size: (u32, u32),
    (coins, total): (u32, u32),
    seconds: f32,
) {
    let at = |x: f32, y: f32| camera.pixel_to_world(Vec2::new(x, y), size);
    let metres_per_pixel = camera.height / size.1.max(1) as f32;
    list.circle(at(28.0, 28.0), 11.0 * metres_per_pixel, HUD_GOLD);
    let x = draw_text(list, &at, 50.0, 16.0, &format!("{coins}/{total}"), HUD_GOLD);
    draw_text(
        list,
        &at,
        x + 24.0,
        16.0,
        &format!("{seconds:.1}"),
        HUD_TEXT,
    );
}

/// Draws `text` (digits, `/` and `.`) from the pixel `(x, y)`, its top
/// left, 24 px tall; returns the pixel x after it.
fn draw_text(
    list: &mut DrawList,
    at: &impl Fn(f32, f32) -> Vec2,
    mut x: f32,
    y: f32,
    text: &str,
    colour: [u8; 4],
) -> f32 {
    // Segments a to g of a digit 12 px wide and 24 tall, as pixel offsets.
    const SEGMENTS: [((f32, f32), (f32, f32)); 7] = [
        ((0.0, 0.0), (12.0, 0.0)),    // a, top
        ((12.0, 0.0), (12.0, 12.0)),  // b, upper right
        ((12.0, 12.0), (12.0, 24.0)), // c, lower right
        ((0.0, 24.0), (12.0, 24.0)),  // d, bottom
        ((0.0, 12.0), (0.0, 24.0)),   // e, lower left
        ((0.0, 0.0), (0.0, 12.0)),    // f, upper left
        ((0.0, 12.0), (12.0, 12.0)),  // g, middle
    ];
    // Which segments each digit lights, a as bit 0.
    const DIGITS: [u8; 10] = [0x3f, 0x06, 0x5b, 0x4f, 0x66, 0x6d, 0x7d, 0x07, 0x7f, 0x6f];
    const WIDTH: f32 = 3.0;
    for c in text.chars() {
        match c {
            '0'..='9' => {
                let lit = DIGITS[c as usize - '0' as usize];
                for (i, ((x0, y0), (x1, y1))) in SEGMENTS.iter().enumerate() {
                    if lit & (1 << i) != 0 {
                        list.line(at(x + x0, y + y0), at(x + x1, y + y1), WIDTH, colour);
                    }
                }
                x += 20.0;
            }
            '/' => {
                list.line(at(x + 10.0, y), at(x, y + 24.0), WIDTH, colour);
                x += 18.0;
            }
            '.' => {
                list.line(at(x, y + 23.0), at(x + 1.0, y + 23.0), WIDTH + 1.0, colour);
                x += 9.0;
            }
            _ => x += 12.0,
        }
    }
    x
}

/// Loads the level's tileset images (PNG) into `renderer`. Empty when the
/// level has no images, a cell has no tile, or an image does not load
/// (said on stderr): the level is then drawn as boxes.
fn level_textures(renderer: &mut Renderer, art: &LevelArt) -> Vec<TextureId> {
    if !art.complete || art.tiles.is_empty() {
        return Vec::new();
    }
    let mut textures = Vec::new();
    for path in &art.images {
        let loaded = RgbaImage::load_png(path).and_then(|image| renderer.add_texture(&image));
        match loaded {
            Ok(texture) => textures.push(texture),
            Err(e) => {
                eprintln!("the level is drawn as boxes: {e}");
                return Vec::new();
            }
        }
    }
    textures
}
