//! The window: `passo demo`'s options, winit events, the wgpu surface,
//! egui, and the frame loop.

use super::catalogue::{Entry, catalogue};
use super::controls::Input;
use super::replay::{Command, Replay};
use super::sim::{Sim, load};
use super::ui::{self, Actions, ViewOptions};
use crate::draw::{BACKGROUND, DrawOptions, add_world};
use anyhow::{Context, Result, anyhow, bail};
use glam::Vec2;
use passo_loop::RealClock;
use passo_physics::BodyId;
use passo_render::{
    AdapterChoice, Camera2D, DrawList, Gpu, Renderer, RgbaImage, WindowSurface, read_texture,
};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// Options of `passo demo` (and of `passo` with no command).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct DemoArgs {
    /// Scene to open first (see `passo scenes`; `integrators` too).
    #[arg(long)]
    pub scene: Option<String>,
    /// Run this many frames, then exit (for tests and recordings).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    pub frames: Option<u64>,
    /// With --frames: save the last presented frame as a PNG.
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Window size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800", value_parser = crate::render_cmd::parse_size)]
    pub size: (u32, u32),
    /// Render on the software adapter (Mesa lavapipe).
    #[arg(long)]
    pub software: bool,
    /// Record the player's input and commands from the start, and save the
    /// replay to this file on exit.
    #[arg(long, conflicts_with = "replay")]
    pub record: Option<PathBuf>,
    /// Play this replay file in the window; with --frames, exit when it ends.
    #[arg(long)]
    pub replay: Option<PathBuf>,
    /// With --frames: resize the window, minimise it (0×0), restore it and
    /// inject a 400 ms frame along the way (for the window test).
    #[arg(long, hide = true, requires = "frames")]
    pub stress: bool,
}

/// Opens the demo window and runs until it is closed (or `--frames` ran).
pub fn run(args: DemoArgs) -> Result<()> {
    let first = Entry::named(args.scene.as_deref().unwrap_or("playground"));
    // Load the scene before opening a window, so a bad name fails fast.
    let sim = load(&first)?;
    let no_display =
        std::env::var_os("DISPLAY").is_none() && std::env::var_os("WAYLAND_DISPLAY").is_none();
    let event_loop = match winit::event_loop::EventLoop::new() {
        Ok(event_loop) => event_loop,
        Err(e) => bail!(no_display_message(&e.to_string(), no_display)),
    };
    let mut app = App::new(args, sim, first);
    event_loop.run_app(&mut app)?;
    app.finish()
}

/// What to say when there is no display to open a window on.
pub fn no_display_message(detail: &str, no_display: bool) -> String {
    let why = if no_display {
        "no display: neither DISPLAY nor WAYLAND_DISPLAY is set".to_owned()
    } else {
        format!("cannot open a window ({detail})")
    };
    format!(
        "{why}. The demo needs a window; without one use the headless commands: \
         `passo simulate SCENE --ticks N`, `passo render SCENE --out FILE.png`, `passo bench`. \
         To run the demo on a machine without a screen, use a virtual one: `xvfb-run -a passo`."
    )
}

/// Keys the game reads every tick.
#[derive(Clone, Copy, Debug, Default)]
struct Keys {
    left: bool,
    right: bool,
    run: bool,
    glide: bool,
    jump: bool,
}

/// What the mouse is doing.
#[derive(Clone, Copy, Debug, Default)]
struct Mouse {
    /// Cursor, physical pixels.
    at: Vec2,
    /// A body being flung: its id and the world point the drag started at.
    fling: Option<(BodyId, Vec2)>,
    /// Panning with the right or middle button.
    panning: bool,
}

/// Frames per second, averaged over about half a second.
#[derive(Clone, Copy, Debug, Default)]
struct Fps {
    frames: u32,
    elapsed: Duration,
    value: f64,
}

impl Fps {
    fn tick(&mut self, frame_time: Duration) {
        self.frames += 1;
        self.elapsed += frame_time;
        if self.elapsed >= Duration::from_millis(500) {
            self.value = f64::from(self.frames) / self.elapsed.as_secs_f64();
            self.frames = 0;
            self.elapsed = Duration::ZERO;
        }
    }
}

/// egui's three parts.
struct Egui {
    ctx: egui::Context,
    state: egui_winit::State,
    renderer: egui_wgpu::Renderer,
}

/// Everything that exists while the window does.
struct Running {
    window: Arc<Window>,
    gpu: Gpu,
    surface: WindowSurface,
    renderer: Renderer,
    egui: Egui,
    sim: Sim,
    entry: Entry,
    catalogue: Vec<(String, Entry)>,
    camera: Camera2D,
    /// The user zoomed or panned: stop fitting the scene to the window.
    camera_moved: bool,
    list: DrawList,
    clock: RealClock,
    keys: Keys,
    mouse: Mouse,
    view: ViewOptions,
    fps: Fps,
    /// Width of the panel, physical pixels (the scene is fitted beside it).
    panel_px: f32,
    message: Option<String>,
    /// A frame time to use instead of the clock's for the next frame.
    hitch: Option<Duration>,
    /// Where `--record` saves the replay on exit.
    record_to: Option<std::path::PathBuf>,
    /// The last replay saved with the panel's button.
    last_replay: Option<Replay>,
}

/// The winit application.
struct App {
    args: DemoArgs,
    pending: Option<(Sim, Entry)>,
    running: Option<Running>,
    error: Option<anyhow::Error>,
    presented: u64,
    attempted: u64,
    skipped: u64,
    screenshot: Option<RgbaImage>,
    summary: Option<String>,
}

impl App {
    fn new(args: DemoArgs, sim: Sim, entry: Entry) -> Self {
        Self {
            args,
            pending: Some((sim, entry)),
            running: None,
            error: None,
            presented: 0,
            attempted: 0,
            skipped: 0,
            screenshot: None,
            summary: None,
        }
    }

    /// After the event loop: report an error, write the screenshot, print
    /// the summary.
    fn finish(mut self) -> Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if let Some(r) = self.running.as_mut()
            && let Some(path) = r.record_to.clone()
            && let Some(replay) = r.sim.stop_recording()
        {
            replay.save(&path)?;
            eprintln!(
                "replay of {} ticks saved to {}",
                replay.ticks,
                path.display()
            );
        }
        if let Some(path) = &self.args.screenshot {
            let image = self
                .screenshot
                .take()
                .ok_or_else(|| anyhow!("no frame was captured for the screenshot"))?;
            image
                .save_png(path)
                .with_context(|| format!("writing {}", path.display()))?;
        }
        if let Some(summary) = &self.summary {
            println!("{summary}");
        }
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }

    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let (sim, entry) = self.pending.take().expect("started once");
        let (w, h) = self.args.size;
        let attributes = Window::default_attributes()
            .with_title(format!("Passo: {}", sim.scene.name))
            .with_inner_size(PhysicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| anyhow!(no_display_message(&e.to_string(), false)))?,
        );
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance
            .create_surface(window.clone())
            .context("creating the window surface")?;
        let choice = if self.args.software {
            AdapterChoice::Software
        } else {
            AdapterChoice::from_env()?
        };
        let gpu = Gpu::with_instance(instance, choice, Some(&surface))?;
        log::info!("demo on {}", gpu.adapter_summary());
        let size = window.inner_size();
        let capture = self.args.screenshot.is_some();
        let surface = WindowSurface::new(&gpu, surface, (size.width, size.height), capture)?;
        if capture && !surface.can_capture() {
            return Err(anyhow!(
                "this window surface cannot be copied, so --screenshot is not available"
            ));
        }
        let renderer = Renderer::new(&gpu, surface.scene_format());
        let ctx = egui::Context::default();
        let state = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer = egui_wgpu::Renderer::new(
            &gpu.device,
            surface.format(),
            egui_wgpu::RendererOptions::default(),
        );
        self.running = Some(Running {
            window,
            gpu,
            surface,
            renderer,
            egui: Egui {
                ctx,
                state,
                renderer: egui_renderer,
            },
            sim,
            entry,
            catalogue: catalogue(),
            camera: Camera2D::default(),
            camera_moved: false,
            list: DrawList::new(BACKGROUND),
            clock: RealClock::new(),
            keys: Keys::default(),
            mouse: Mouse::default(),
            view: ViewOptions::default(),
            fps: Fps::default(),
            panel_px: 0.0,
            message: None,
            hitch: None,
            record_to: self.args.record.clone(),
            last_replay: None,
        });
        let r = self.running.as_mut().expect("just made");
        if let Some(path) = &self.args.replay {
            let replay = Replay::load(path)?;
            r.entry = Entry::named(&replay.scene);
            r.sim = load(&r.entry)?;
            r.sim.start_playback(replay)?;
        } else if r.record_to.is_some() {
            r.sim.start_recording()?;
        }
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_none()
            && self.pending.is_some()
            && let Err(e) = self.start(event_loop)
        {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let response = r.egui.state.on_window_event(&r.window, &event);
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                r.surface.resize(&r.gpu.device, (size.width, size.height))
            }
            WindowEvent::RedrawRequested => {
                self.attempted += 1;
                if self.args.stress {
                    r.stress(self.attempted);
                }
                match r.redraw(
                    self.args.frames.is_some_and(|n| self.presented + 1 == n)
                        && self.args.screenshot.is_some(),
                ) {
                    Ok(Some(shot)) => {
                        self.presented += 1;
                        if shot.is_some() {
                            self.screenshot = shot;
                        }
                    }
                    Ok(None) => self.skipped += 1,
                    Err(e) => return self.fail(event_loop, e),
                }
                let replay_done = self.args.replay.is_some()
                    && r.sim
                        .session
                        .playback_status()
                        .is_some_and(|(_, _, result, _)| result.is_some());
                if let Some(n) = self.args.frames {
                    if self.presented >= n || replay_done {
                        self.summary = Some(r.summary(self.presented, self.skipped));
                        event_loop.exit();
                    } else if self.attempted > n * 10 + 100 {
                        let e = anyhow!("only {} of {n} frames could be presented", self.presented);
                        self.fail(event_loop, e);
                    }
                }
            }
            WindowEvent::KeyboardInput { event, .. } if !response.consumed => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    r.key(code, event.state == ElementState::Pressed, event.repeat);
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                let at = Vec2::new(position.x as f32, position.y as f32);
                if r.mouse.panning {
                    let size = r.surface.size();
                    let delta = r.camera.pixel_to_world(r.mouse.at, size)
                        - r.camera.pixel_to_world(at, size);
                    r.camera.pan(delta);
                    r.camera_moved = true;
                }
                r.mouse.at = at;
            }
            WindowEvent::MouseInput { state, button, .. }
                if !response.consumed || state == ElementState::Released =>
            {
                r.click(button, state == ElementState::Pressed);
            }
            WindowEvent::MouseWheel { delta, .. } if !response.consumed => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                let anchor = r.camera.pixel_to_world(r.mouse.at, r.surface.size());
                r.camera.zoom_about(1.15f32.powf(lines), anchor);
                r.camera_moved = true;
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}

impl Running {
    /// The window test's rough handling, by frame number: a resize, a
    /// minimise (the 0×0 size a minimised window reports), a restore, and a
    /// 400 ms frame.
    fn stress(&mut self, frame: u64) {
        let size = self.window.inner_size();
        match frame {
            5 => {
                let _ = self
                    .window
                    .request_inner_size(PhysicalSize::new(size.width + 64, size.height + 32));
            }
            10 => self.surface.resize(&self.gpu.device, (0, 0)),
            14 => self
                .surface
                .resize(&self.gpu.device, (size.width, size.height)),
            18 => self.hitch = Some(Duration::from_millis(400)),
            _ => {}
        }
    }

    fn key(&mut self, code: KeyCode, down: bool, repeat: bool) {
        match code {
            KeyCode::KeyA | KeyCode::ArrowLeft => self.keys.left = down,
            KeyCode::KeyD | KeyCode::ArrowRight => self.keys.right = down,
            KeyCode::ShiftLeft | KeyCode::ShiftRight => self.keys.run = down,
            KeyCode::KeyG => self.keys.glide = down,
            KeyCode::Space if down && !repeat => self.keys.jump = true,
            KeyCode::KeyW if down && !repeat => {
                let mut knobs = self.sim.session.knobs;
                knobs.wind = !knobs.wind;
                let command = Command::Knobs {
                    knobs,
                    friction: false,
                    restitution: false,
                    drag: false,
                };
                self.act(Actions {
                    commands: vec![command],
                    ..Default::default()
                });
            }
            KeyCode::KeyP if down && !repeat => {
                if self.sim.session.timestep.is_paused() {
                    self.sim.session.timestep.resume();
                } else {
                    self.sim.session.timestep.pause();
                }
            }
            KeyCode::KeyN if down => self.sim.session.timestep.step_once(),
            KeyCode::Backspace => self.sim.rewinding = down,
            KeyCode::KeyR if down && !repeat => self.act(Actions {
                commands: vec![Command::Reset],
                ..Default::default()
            }),
            KeyCode::KeyF if down && !repeat => self.camera_moved = false,
            KeyCode::KeyV if down && !repeat => self.view.velocities = !self.view.velocities,
            _ => {}
        }
    }

    fn click(&mut self, button: MouseButton, down: bool) {
        let world_at = self
            .camera
            .pixel_to_world(self.mouse.at, self.surface.size());
        match (button, down) {
            (MouseButton::Left, true) => match self.sim.scene.pick(world_at) {
                Some(id) => self.mouse.fling = Some((id, world_at)),
                None => {
                    let command = Command::Spawn {
                        at: world_at.to_array(),
                        round: !self.keys.run,
                    };
                    self.act(Actions {
                        commands: vec![command],
                        ..Default::default()
                    });
                }
            },
            (MouseButton::Left, false) => {
                if let Some((id, from)) = self.mouse.fling.take() {
                    // A slingshot: 4 m/s for every metre dragged.
                    let command = Command::Fling {
                        index: id.index(),
                        generation: id.generation(),
                        velocity: ((world_at - from) * 4.0).to_array(),
                    };
                    self.act(Actions {
                        commands: vec![command],
                        ..Default::default()
                    });
                }
            }
            (MouseButton::Right | MouseButton::Middle, pressed) => self.mouse.panning = pressed,
            _ => {}
        }
    }

    /// Switches scene, applies commands, records and replays.
    fn act(&mut self, actions: Actions) {
        let mut result = Ok(());
        if let Some(entry) = actions.switch_to {
            result = load(&entry).map(|sim| {
                self.sim = sim;
                self.entry = entry;
                self.camera_moved = false;
                self.window
                    .set_title(&format!("Passo: {}", self.sim.scene.name));
            });
        }
        for command in actions.commands {
            if result.is_ok() {
                result = self.sim.command(command);
            }
        }
        if actions.record {
            result = result.and_then(|()| self.sim.start_recording());
        }
        if actions.stop_recording
            && let Some(replay) = self.sim.stop_recording()
        {
            let dir = std::path::Path::new("replays");
            let path = dir.join(format!("{}-{}.ron", replay.scene, replay.ticks));
            result = result
                .and_then(|()| std::fs::create_dir_all(dir).map_err(Into::into))
                .and_then(|()| replay.save(&path));
            if result.is_ok() {
                self.message = Some(format!("replay saved to {}", path.display()));
            }
            self.last_replay = Some(replay);
        }
        if actions.replay_last
            && let Some(replay) = self.last_replay.clone()
        {
            result = result.and_then(|()| self.sim.start_playback(replay));
        }
        if let Err(e) = result {
            self.message = Some(format!("{e:#}"));
        }
    }

    /// Fits the scene into the part of the window beside the panel.
    fn fit_camera(&mut self) {
        let (w, h) = self.surface.size();
        let free = ((w as f32 - self.panel_px).max(1.0) as u32, h);
        let b = self.sim.scene.bounds;
        let mut camera = Camera2D::fit(b.min, b.max, free);
        camera.centre.x -= 0.5 * self.panel_px * camera.pixel_size((w, h));
        self.camera = camera;
    }

    /// One frame: tick the simulation, build the panel, draw, present.
    /// Returns `Ok(None)` when the frame was skipped, else whether a
    /// screenshot was taken.
    fn redraw(&mut self, capture: bool) -> Result<Option<Option<RgbaImage>>> {
        let frame_time = self.clock.frame_time();
        let frame_time = self.hitch.take().unwrap_or(frame_time);
        self.sim.scene.set_input(Input {
            left: self.keys.left,
            right: self.keys.right,
            run: self.keys.run,
            glide: self.keys.glide,
            jump: std::mem::take(&mut self.keys.jump),
        });
        self.sim.frame(frame_time);
        self.fps.tick(frame_time);

        // The panel.
        let raw = self.egui.state.take_egui_input(&self.window);
        let mut actions = Actions::default();
        let panel = ui::PanelInput {
            catalogue: &self.catalogue,
            current: &self.entry,
            fps: self.fps.value,
            message: self.message.as_deref(),
            last_replay: self.last_replay.is_some(),
        };
        let camera = self.camera;
        let size = self.surface.size();
        let ppp = self.window.scale_factor() as f32;
        let mut panel_width = 0.0;
        let mut full = self.egui.ctx.run_ui(raw, |ui| {
            panel_width = ui::panel(ui, &mut self.sim, &mut self.view, &panel, &mut actions);
            ui::lane_labels(ui, &self.sim, &camera, size, ppp);
        });
        self.panel_px = panel_width * full.pixels_per_point;
        self.egui
            .state
            .handle_platform_output(&self.window, full.platform_output);
        let jobs = self.egui.ctx.tessellate(full.shapes, full.pixels_per_point);
        self.act(actions);
        if !self.camera_moved {
            self.fit_camera();
        }

        // Draw. Textures are updated and freed whether or not the frame is drawn.
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let mut textures = std::mem::take(&mut full.textures_delta);
        for (id, deltas) in textures.set.drain() {
            for delta in &deltas {
                self.egui.renderer.update_texture(device, queue, id, delta);
            }
        }
        let result = match self.surface.acquire(device) {
            None => Ok(None),
            Some(frame) => {
                let scene_view = self.surface.scene_view(&frame);
                let view = frame
                    .texture
                    .create_view(&wgpu::TextureViewDescriptor::default());
                self.list.clear(BACKGROUND);
                for lane in &self.sim.scene.lanes {
                    let options = DrawOptions {
                        alpha: self.sim.session.stats.alpha,
                        velocity_vectors: self.view.velocities,
                        force_vectors: self.view.forces,
                        contact_normals: self.view.contacts,
                        dim_sleeping: self.view.sleeping,
                        offset: lane.offset,
                        ..Default::default()
                    };
                    add_world(&mut self.list, &lane.world, &lane.bodies, &options);
                }
                let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("passo demo frame"),
                });
                self.renderer
                    .encode(&mut encoder, &scene_view, size, &self.camera, &self.list);
                let screen = egui_wgpu::ScreenDescriptor {
                    size_in_pixels: [size.0, size.1],
                    pixels_per_point: full.pixels_per_point,
                };
                let extra =
                    self.egui
                        .renderer
                        .update_buffers(device, queue, &mut encoder, &jobs, &screen);
                {
                    let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("passo panel"),
                        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                            view: &view,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Load,
                                store: wgpu::StoreOp::Store,
                            },
                        })],
                        ..Default::default()
                    });
                    self.egui
                        .renderer
                        .render(&mut pass.forget_lifetime(), &jobs, &screen);
                }
                queue.submit(extra.into_iter().chain(Some(encoder.finish())));
                let shot = if capture {
                    Some(read_texture(&self.gpu, &frame.texture)?)
                } else {
                    None
                };
                queue.present(frame);
                Ok(Some(shot))
            }
        };
        for id in textures.free.drain() {
            self.egui.renderer.free_texture(&id);
        }
        result
    }

    /// A line for tests and logs: frames, ticks, window, camera, the state
    /// hash and how a replay ended.
    fn summary(&self, presented: u64, skipped: u64) -> String {
        let (w, h) = self.surface.size();
        let replay = match self.sim.session.playback_status() {
            Some((_, _, Some(hash), recorded)) if hash == recorded => "; replay matched",
            Some((_, _, Some(_), _)) => "; replay differed",
            Some((_, _, None, _)) => "; replay unfinished",
            None => "",
        };
        format!(
            "presented {presented} frames; skipped {skipped}; ticks {}; dropped {:.3} s; window {w}x{h}; \
             camera centre ({}, {}) height {}; hash {:016x}{replay}",
            self.sim.session.timestep.tick(),
            self.sim.session.timestep.dropped_total().as_secs_f64(),
            self.camera.centre.x,
            self.camera.centre.y,
            self.camera.height,
            self.sim.scene.state_hash()
        )
    }
}
