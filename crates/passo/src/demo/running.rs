//! What exists while the demo's window does: the surface, the renderer,
//! egui, the running scene and the camera; what keys and clicks do to it,
//! and how a frame is drawn.

use super::catalogue::Entry;
use super::controls::Input;
use super::replay::{Command, Replay};
use super::sim::{Sim, load};
use super::ui::{self, Actions, ViewOptions};
use crate::draw::{BACKGROUND, DrawOptions, LevelTiles, add_world_hiding};
use anyhow::Result;
use glam::Vec2;
use passo_loop::RealClock;
use passo_physics::BodyId;
use passo_render::{
    Camera2D, DrawList, Gpu, Renderer, RgbaImage, TextureId, WindowSurface, read_texture,
};
use passo_scene::LevelArt;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;
use winit::dpi::PhysicalSize;
use winit::event::MouseButton;
use winit::keyboard::KeyCode;
use winit::window::Window;

/// Keys the game reads every tick.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Keys {
    left: bool,
    right: bool,
    run: bool,
    glide: bool,
    jump: bool,
}

/// What the mouse is doing.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Mouse {
    /// Cursor, physical pixels.
    pub(super) at: Vec2,
    /// Holding a body (a target joint, see `SceneState::grab`): the last
    /// point its target was sent to.
    held: Option<Vec2>,
    /// Panning with the right or middle button.
    pub(super) panning: bool,
}

/// Frames per second, averaged over about half a second.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Fps {
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
pub(super) struct Egui {
    pub(super) ctx: egui::Context,
    pub(super) state: egui_winit::State,
    pub(super) renderer: egui_wgpu::Renderer,
}

/// Everything that exists while the window does.
pub(super) struct Running {
    pub(super) window: Arc<Window>,
    pub(super) gpu: Gpu,
    pub(super) surface: WindowSurface,
    pub(super) renderer: Renderer,
    pub(super) egui: Egui,
    pub(super) sim: Sim,
    pub(super) entry: Entry,
    pub(super) catalogue: Vec<(String, Entry)>,
    pub(super) camera: Camera2D,
    /// The user zoomed or panned: stop fitting the scene to the window.
    pub(super) camera_moved: bool,
    pub(super) list: DrawList,
    pub(super) clock: RealClock,
    pub(super) keys: Keys,
    pub(super) mouse: Mouse,
    pub(super) view: ViewOptions,
    pub(super) fps: Fps,
    /// Width of the panel, physical pixels (the scene is fitted beside it).
    pub(super) panel_px: f32,
    pub(super) message: Option<String>,
    /// A frame time to use instead of the clock's for the next frame.
    pub(super) hitch: Option<Duration>,
    /// Where `--record` saves the replay on exit.
    pub(super) record_to: Option<std::path::PathBuf>,
    /// The last replay saved with the panel's button.
    pub(super) last_replay: Option<Replay>,
    /// The level's tiles, as textures of the renderer.
    pub(super) tiles: Tiles,
}

/// A level's tiles ready to draw, the art they were made from, and every
/// image loaded so far (by path: switching scenes back and forth loads
/// each image once).
#[derive(Default)]
pub(super) struct Tiles {
    drawn: LevelTiles,
    made_from: Option<Arc<LevelArt>>,
    textures: BTreeMap<PathBuf, TextureId>,
}

impl Tiles {
    /// Makes the tiles again for a new scene: one whose art is not the
    /// one they were made from (a rebuilt scene has new art, and its
    /// images are found loaded).
    fn refresh(&mut self, renderer: &mut Renderer, art: &Arc<LevelArt>, cells: &[BodyId]) {
        if self.made_from.as_ref().is_some_and(|a| Arc::ptr_eq(a, art)) {
            return;
        }
        let textures = &mut self.textures;
        self.drawn = LevelTiles::from_art(art, cells, |path| {
            if let Some(&id) = textures.get(path) {
                return Ok(id);
            }
            let image = crate::load_image(path)?;
            let id = renderer.add_texture(&image).map_err(|e| e.to_string())?;
            textures.insert(path.to_path_buf(), id);
            Ok(id)
        });
        self.made_from = Some(Arc::clone(art));
    }
}

impl Running {
    /// The window test's rough handling, by frame number: a resize, a
    /// minimise (the 0×0 size a minimised window reports), a restore, and a
    /// 400 ms frame.
    pub(super) fn stress(&mut self, frame: u64) {
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

    pub(super) fn key(&mut self, code: KeyCode, down: bool, repeat: bool) {
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

    pub(super) fn click(&mut self, button: MouseButton, down: bool) {
        let world_at = self
            .camera
            .pixel_to_world(self.mouse.at, self.surface.size());
        // The panel covers the window's left edge: a press there is the
        // panel's, even when egui has not yet drawn a frame with the pointer
        // over it (a click on a checkbox right after moving onto it also
        // spawned a ball under the panel, out of sight but in replays).
        let on_panel = self.mouse.at.x < self.panel_px;
        match (button, down) {
            (MouseButton::Left, true) if on_panel => {}
            (MouseButton::Left, true) => match self.sim.scene.pick(world_at) {
                Some(id) => {
                    self.mouse.held = Some(world_at);
                    let command = Command::Grab {
                        index: id.index(),
                        generation: id.generation(),
                        at: world_at.to_array(),
                    };
                    self.act(Actions {
                        commands: vec![command],
                        ..Default::default()
                    });
                }
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
            (MouseButton::Left, false) if self.mouse.held.take().is_some() => {
                self.act(Actions {
                    commands: vec![Command::Release],
                    ..Default::default()
                });
            }
            (MouseButton::Right | MouseButton::Middle, pressed) => self.mouse.panning = pressed,
            _ => {}
        }
    }

    /// Switches scene, applies commands, records and replays.
    fn act(&mut self, actions: Actions) {
        let mut result = Ok(());
        if let Some(entry) = actions.switch_to {
            // A new scene ends a recording under way: saved first, not
            // dropped with the old scene.
            result = self.save_recording();
            result = result.and_then(|()| load(&entry)).map(|sim| {
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
        if actions.stop_recording {
            result = result.and_then(|()| self.save_recording());
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

    /// Stops the recording under way, if any, and saves it: to the
    /// `--record` file if one was given, else to
    /// `replays/<scene>-<ticks>.ron`; in a browser, as a download. It is
    /// also kept to replay.
    pub(super) fn save_recording(&mut self) -> Result<()> {
        let Some(replay) = self.sim.stop_recording() else {
            return Ok(());
        };
        let saved = self.save_replay(&replay);
        self.last_replay = Some(replay);
        saved
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn save_replay(&mut self, replay: &Replay) -> Result<()> {
        let path = match &self.record_to {
            Some(path) => path.clone(),
            None => {
                let dir = std::path::Path::new("replays");
                std::fs::create_dir_all(dir)?;
                dir.join(format!("{}-{}.ron", replay.scene, replay.ticks))
            }
        };
        replay.save(&path)?;
        let said = format!(
            "replay of {} ticks saved to {}",
            replay.ticks,
            path.display()
        );
        eprintln!("{said}");
        self.message = Some(said);
        Ok(())
    }

    /// A page has no disk: the browser downloads the file instead.
    #[cfg(target_arch = "wasm32")]
    fn save_replay(&mut self, replay: &Replay) -> Result<()> {
        let name = format!("{}-{}.ron", replay.scene, replay.ticks);
        super::page::download(&name, &replay.to_ron())
            .map_err(|e| anyhow::anyhow!("the replay could not be downloaded ({e})"))?;
        self.message = Some(format!(
            "replay of {} ticks downloaded as {name}",
            replay.ticks
        ));
        Ok(())
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
    pub(super) fn redraw(&mut self, capture: bool) -> Result<Option<Option<RgbaImage>>> {
        // A held body's target follows the pointer: one command a frame
        // at most, and none while the pointer holds still.
        if let Some(sent) = self.mouse.held {
            let at = (self.camera).pixel_to_world(self.mouse.at, self.surface.size());
            if at != sent {
                self.mouse.held = Some(at);
                self.act(Actions {
                    commands: vec![Command::Drag { at: at.to_array() }],
                    ..Default::default()
                });
            }
        }
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
            ui::lane_labels(ui, &self.sim, &camera, size, ppp, panel_width);
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
                let scene = &self.sim.scene;
                self.tiles
                    .refresh(&mut self.renderer, &scene.art, &scene.cell_bodies);
                add_scene(
                    &mut self.list,
                    &self.tiles.drawn,
                    &self.sim,
                    &self.view,
                    size,
                    self.panel_px,
                );
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
    pub(super) fn summary(&self, presented: u64, skipped: u64) -> String {
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

/// The scene's part of a frame, as the demo draws it: the level's tiles and
/// every lane's bodies, nothing under the panel (`panel_px` wide, which
/// has no fill of its own).
fn add_scene(
    list: &mut DrawList,
    tiles: &LevelTiles,
    sim: &Sim,
    view: &ViewOptions,
    size: (u32, u32),
    panel_px: f32,
) {
    list.clear(BACKGROUND);
    tiles.add_to(list, Vec2::ZERO);
    for (i, lane) in sim.scene.lanes.iter().enumerate() {
        let options = DrawOptions {
            alpha: sim.session.stats.alpha,
            velocity_vectors: view.velocities,
            force_vectors: view.forces,
            contact_normals: view.contacts,
            dim_sleeping: view.sleeping,
            offset: lane.offset,
            ..Default::default()
        };
        let hidden = if i == 0 { tiles.hidden() } else { &[] };
        add_world_hiding(list, &lane.world, &lane.bodies, hidden, &options);
    }
    let left = (panel_px.floor() as u32).min(size.0);
    list.clip = Some([left, 0, size.0 - left, size.1]);
}

/// The scene part of the demo's frame for `sim` as it is now, drawn
/// off-screen: `size` pixels through `camera`, the panel's `panel_px`
/// left empty (the background), debug drawing off. The web demo's check
/// compares the browser's frames with it.
#[cfg(not(target_arch = "wasm32"))]
pub fn render_scene_offscreen(
    sim: &Sim,
    camera: Camera2D,
    size: (u32, u32),
    panel_px: f32,
    choice: passo_render::AdapterChoice,
) -> Result<RgbaImage> {
    let gpu = Gpu::headless(choice)?;
    let target = passo_render::OffscreenTarget::new(&gpu, size.0, size.1);
    let mut renderer = Renderer::new(&gpu, target.format());
    let mut tiles = Tiles::default();
    tiles.refresh(&mut renderer, &sim.scene.art, &sim.scene.cell_bodies);
    let mut list = DrawList::new(BACKGROUND);
    let view = ViewOptions::default();
    add_scene(&mut list, &tiles.drawn, sim, &view, size, panel_px);
    renderer.render(target.view(), target.size(), &camera, &list);
    Ok(target.read(&gpu)?)
}
