//! The window: `passo demo`'s options, winit events and the frame loop
//! (what runs while the window exists is in `running`).

use super::catalogue::{Entry, catalogue};
use super::replay::Replay;
use super::running::{Egui, Fps, Keys, Mouse, Running};
use super::sim::{Sim, load};
use super::ui::ViewOptions;
use crate::draw::BACKGROUND;
use anyhow::{Context, Result, anyhow, bail};
use glam::Vec2;
use passo_loop::RealClock;
use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, Renderer, RgbaImage, WindowSurface};
use std::path::PathBuf;
use std::sync::Arc;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoopProxy};
use winit::keyboard::PhysicalKey;
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
    /// With --frames: save the last presented frame as a PNG (its name
    /// ends in `.png`).
    #[arg(long, requires = "frames", value_parser = crate::render_cmd::png_path)]
    pub screenshot: Option<PathBuf>,
    /// Window size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800", value_parser = crate::render_cmd::parse_size)]
    pub size: (u32, u32),
    /// Render on the software adapter (Mesa lavapipe).
    #[arg(long)]
    pub software: bool,
    /// Record the player's input and commands from the start, and save the
    /// replay to this file on exit.
    #[arg(long, conflicts_with = "replay", value_parser = crate::render_cmd::output_path)]
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
    let event_loop = match winit::event_loop::EventLoop::with_user_event().build() {
        Ok(event_loop) => event_loop,
        Err(e) => bail!(no_display_message(&e.to_string(), no_display)),
    };
    let mut app = App::new(args, sim, first, event_loop.create_proxy());
    event_loop.run_app(&mut app)?;
    app.finish()
}

/// What the window waits for after it opens: the GPU and the window's
/// surface, or why they could not be had. Natively they come at once; in a
/// browser, where nothing may block, later, as this event.
pub(super) struct GpuReady(Result<(Gpu, wgpu::Surface<'static>)>);

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

/// The winit application.
pub(super) struct App {
    args: DemoArgs,
    pending: Option<(Sim, Entry)>,
    /// The window, while its GPU is being opened (in a browser).
    window: Option<Arc<Window>>,
    /// Sends [`GpuReady`] to the event loop (used in a browser).
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
    proxy: EventLoopProxy<GpuReady>,
    /// In a browser: run exactly this many ticks as fast as frames come,
    /// then pause (the page's `?ticks=N`, for tests).
    pub(super) stop_at_tick: Option<u64>,
    /// In a browser: WebGL2 even where WebGPU is there (`?backend=webgl`).
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
    pub(super) webgl_only: bool,
    running: Option<Running>,
    error: Option<anyhow::Error>,
    presented: u64,
    attempted: u64,
    skipped: u64,
    screenshot: Option<RgbaImage>,
    summary: Option<String>,
    /// The replay (`--replay`) reached its end before `--frames` did: the
    /// next frame is the last, captured for `--screenshot`.
    replay_ended: bool,
}

impl App {
    pub(super) fn new(
        args: DemoArgs,
        sim: Sim,
        entry: Entry,
        proxy: EventLoopProxy<GpuReady>,
    ) -> Self {
        Self {
            args,
            pending: Some((sim, entry)),
            window: None,
            proxy,
            stop_at_tick: None,
            webgl_only: false,
            running: None,
            error: None,
            presented: 0,
            attempted: 0,
            skipped: 0,
            screenshot: None,
            summary: None,
            replay_ended: false,
        }
    }

    /// After the event loop: report an error, write the screenshot, print
    /// the summary.
    fn finish(mut self) -> Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if let Some(r) = self.running.as_mut()
            && r.record_to.is_some()
        {
            r.save_recording()?;
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
        // A page has no exit status: the error shows there.
        #[cfg(target_arch = "wasm32")]
        super::page::report_error(&e);
        self.error.get_or_insert(e);
        event_loop.exit();
    }

    /// Opens the window, then its GPU: at once natively, and in a browser
    /// later, as a [`GpuReady`] event.
    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let title = match &self.pending {
            Some((sim, _)) => format!("Passo: {}", sim.scene.name),
            None => "Passo".to_owned(),
        };
        let (w, h) = self.args.size;
        let attributes = Window::default_attributes()
            .with_title(title)
            .with_inner_size(PhysicalSize::new(w, h));
        // In a browser the page's style sizes the canvas (the whole page),
        // and the window follows it.
        #[cfg(target_arch = "wasm32")]
        let attributes = {
            use winit::platform::web::WindowAttributesExtWebSys;
            let mut attributes = attributes.with_append(true).with_prevent_default(true);
            attributes.inner_size = None;
            attributes
        };
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| anyhow!(no_display_message(&e.to_string(), false)))?,
        );
        let descriptor = wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(
            event_loop.owned_display_handle(),
        ));
        let choice = if self.args.software {
            AdapterChoice::Software
        } else {
            AdapterChoice::from_env()?
        };
        #[cfg(not(target_arch = "wasm32"))]
        {
            let instance = wgpu::Instance::new(descriptor);
            let surface = instance
                .create_surface(window.clone())
                .context("creating the window surface")?;
            let gpu = Gpu::with_instance(instance, choice, Some(&surface))?;
            self.finish_start(window, gpu, surface)
        }
        #[cfg(target_arch = "wasm32")]
        {
            let proxy = self.proxy.clone();
            let target = window.clone();
            let webgl_only = self.webgl_only;
            wasm_bindgen_futures::spawn_local(async move {
                let opened = async {
                    let mut descriptor = descriptor;
                    if webgl_only {
                        descriptor.backends = wgpu::Backends::GL;
                    }
                    // WebGPU where the browser can give an adapter, else
                    // WebGL2.
                    let instance = wgpu::util::new_instance_with_webgpu_detection(descriptor).await;
                    let surface = instance
                        .create_surface(target)
                        .context("creating the canvas surface")?;
                    let gpu = Gpu::open(instance, choice, Some(&surface)).await?;
                    Ok((gpu, surface))
                };
                // The event loop outlives the page: sending cannot fail.
                let _ = proxy.send_event(GpuReady(opened.await));
            });
            self.window = Some(window);
            Ok(())
        }
    }

    /// Everything that needs the GPU: the surface, the renderers, egui.
    fn finish_start(
        &mut self,
        window: Arc<Window>,
        gpu: Gpu,
        surface: wgpu::Surface<'static>,
    ) -> Result<()> {
        let (sim, entry) = self.pending.take().expect("started once");
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
            tiles: Default::default(),
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

impl ApplicationHandler<GpuReady> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_none()
            && self.window.is_none()
            && self.pending.is_some()
            && let Err(e) = self.start(event_loop)
        {
            self.fail(event_loop, e);
        }
    }

    fn user_event(&mut self, event_loop: &ActiveEventLoop, event: GpuReady) {
        let Some(window) = self.window.take() else {
            return;
        };
        let started = event
            .0
            .and_then(|(gpu, surface)| self.finish_start(window, gpu, surface));
        if let Err(e) = started {
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
                if let Some(n) = self.stop_at_tick {
                    // Exactly `n` ticks, then the loop stays paused.
                    let timestep = &mut r.sim.session.timestep;
                    timestep.pause();
                    let left = n.saturating_sub(timestep.tick()).min(60) as u32;
                    if left > 0 {
                        r.sim.frame_of_ticks(left);
                    }
                }
                if self.args.stress {
                    r.stress(self.attempted);
                }
                let last =
                    self.args.frames.is_some_and(|n| self.presented + 1 == n) || self.replay_ended;
                match r.redraw(last && self.args.screenshot.is_some()) {
                    Ok(Some(shot)) => {
                        self.presented += 1;
                        if shot.is_some() {
                            self.screenshot = shot;
                        }
                    }
                    Ok(None) => self.skipped += 1,
                    Err(e) => return self.fail(event_loop, e),
                }
                #[cfg(target_arch = "wasm32")]
                super::page::publish(&super::page::Shown {
                    scene: &r.sim.session.entry_name,
                    tick: r.sim.session.timestep.tick(),
                    hash: r.sim.scene.state_hash(),
                    player: (r.sim.scene.player)
                        .and_then(|id| r.sim.scene.lanes[0].world.body(id))
                        .map(|b| b.position.to_array()),
                    backend: format!("{:?}", r.gpu.adapter.get_info().backend),
                    frames: self.presented,
                    size: r.surface.size(),
                    panel: r.panel_px,
                    camera: [r.camera.centre.x, r.camera.centre.y, r.camera.height],
                });
                let replay_done = self.args.replay.is_some()
                    && r.sim
                        .session
                        .playback_status()
                        .is_some_and(|(_, _, result, _)| result.is_some());
                if let Some(n) = self.args.frames {
                    // A replay ending before frame `n` ends the run, once a
                    // frame of its final state is captured for --screenshot
                    // (the run failed with no frame captured).
                    self.replay_ended |= replay_done;
                    let captured = self.args.screenshot.is_none() || self.screenshot.is_some();
                    if self.presented >= n || (replay_done && captured) {
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
