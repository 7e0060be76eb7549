//! The game in a browser tab, against another tab over WebRTC.
//!
//! Each tab joins a room of a signalling server, which introduces it to
//! the other tab; from then on the two talk directly over an unreliable,
//! unordered WebRTC data channel (`matchbox_socket`), and GGRS keeps their
//! worlds in step by rollback, as over UDP natively. The page
//! (`web/netplay.html`) takes its settings from its address:
//! - `room=NAME`: tabs in the same room play each other (default `passo`);
//! - `signal=URL`: the signalling server (default `ws://HOST:3536`, HOST
//!   being the page's);
//! - `stun=URL`: the STUN server the tab learns its address from (default
//!   the signalling server's host and port: `passo-signal` answers STUN;
//!   players on different networks need a public one);
//! - `script`: both players follow [`scripted_input`] instead of the keys;
//! - `frames=N`: keep the checksum of each of the first N ticks, and
//!   publish them once every player has confirmed them.
//!
//! Keys: A and D or the arrows walk, W, the up arrow or Space jumps.
//!
//! The tab publishes its state as `window.passoNetplay`: `state`
//! (`waiting`, `syncing`, `playing` or `over`), `me` (0 or 1), `tick`,
//! `confirmed` (the last tick both players' inputs are in for), `rollbacks`,
//! `desyncs` (checksums the peers exchanged that differ), `error`, and
//! with `frames=N`, `checksums` (hex, `[t]` after `t + 1` ticks).

use crate::game::{Game, Input, Netplay, scripted_input};
use ggrs::{
    DesyncDetection, GgrsError, GgrsEvent, Message, NonBlockingSocket, P2PSession, PlayerType,
    SessionBuilder, SessionState,
};
use matchbox_socket::{ChannelConfig, PeerId, RtcIceServerConfig, WebRtcChannel, WebRtcSocket};
use passo_loop::{FixedTimestep, RealClock};
use passo_physics::{BodyKind, Shape};
use std::cell::{Cell, RefCell};
use std::rc::Rc;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement, KeyboardEvent};

/// The GGRS configuration in a browser: WebRTC peers for addresses.
pub type WebNetplay = Netplay<PeerId>;

/// GGRS's messages over a WebRTC data channel, in bincode (as over UDP
/// natively).
struct Channel(WebRtcChannel);

impl NonBlockingSocket<PeerId> for Channel {
    fn send_to(&mut self, msg: &Message, addr: &PeerId) {
        // A message that does not encode, or a channel already closed, is
        // a lost packet: GGRS sends again, or reports the peer gone.
        if let Ok(bytes) = bincode::serialize(msg) {
            let _ = self.0.try_send(bytes.into_boxed_slice(), *addr);
        }
    }

    fn receive_all_messages(&mut self) -> Vec<(PeerId, Message)> {
        // What does not decode is dropped, as a damaged datagram would be.
        self.0
            .receive()
            .into_iter()
            .filter_map(|(peer, packet)| Some((peer, bincode::deserialize(&packet).ok()?)))
            .collect()
    }
}

/// The page's settings (see the module's documentation).
struct Settings {
    room: String,
    signal: String,
    stun: String,
    script: bool,
    frames: Option<u64>,
}

impl Settings {
    fn from_page(window: &web_sys::Window) -> Self {
        let location = window.location();
        let params = location
            .search()
            .ok()
            .and_then(|s| web_sys::UrlSearchParams::new_with_str(&s).ok());
        let get = |key: &str| params.as_ref().and_then(|p| p.get(key));
        let host = location
            .hostname()
            .ok()
            .filter(|h| !h.is_empty())
            .unwrap_or_else(|| "127.0.0.1".into());
        let signal = get("signal").unwrap_or_else(|| format!("ws://{host}:3536"));
        // The signalling server's host and port: `ws://HOST:PORT/...`.
        let authority = signal.split("://").last().unwrap_or_default();
        let authority = authority.split('/').next().unwrap_or_default();
        Self {
            room: get("room").unwrap_or_else(|| "passo".into()),
            stun: get("stun").unwrap_or_else(|| format!("stun:{authority}")),
            signal,
            script: params.as_ref().is_some_and(|p| p.has("script")),
            frames: get("frames").and_then(|n| n.parse().ok()),
        }
    }
}

enum Phase {
    /// Joined the room; no other player yet.
    Waiting,
    /// Playing against the other tab (GGRS synchronises first).
    Playing {
        session: Box<P2PSession<WebNetplay>>,
        me: usize,
    },
    /// The game ended: the reason.
    Over(String),
}

struct App {
    socket: WebRtcSocket,
    /// Set when the socket's message loop ends with an error.
    socket_error: Rc<RefCell<Option<String>>>,
    phase: Phase,
    game: Game,
    timestep: FixedTimestep,
    clock: RealClock,
    /// The keys held now.
    keys: Rc<Cell<Input>>,
    settings: Settings,
    /// With `frames=N`: the checksum after each tick, `[t]` after `t + 1`
    /// ticks, overwritten when a rollback simulates a tick again.
    checksums: Vec<u128>,
    /// The confirmed frame as it stood at the last advance: every tick up
    /// to it has been simulated with the inputs both players sent.
    settled: i32,
    rollbacks: u64,
    desyncs: u64,
    canvas: HtmlCanvasElement,
    context: CanvasRenderingContext2d,
}

/// Starts the game in the page's first canvas, or reports why it cannot.
pub fn start() {
    if let Err(e) = try_start() {
        let message = e.as_string().unwrap_or_else(|| format!("{e:?}"));
        publish_error(&message);
    }
}

fn try_start() -> Result<(), JsValue> {
    console_error_panic_hook::set_once();
    let window = web_sys::window().ok_or("no window")?;
    let document = window.document().ok_or("no document")?;
    let canvas: HtmlCanvasElement = document
        .query_selector("canvas")?
        .ok_or("the page has no canvas")?
        .dyn_into()?;
    let context: CanvasRenderingContext2d = canvas
        .get_context("2d")?
        .ok_or("no 2D canvas context")?
        .dyn_into()?;
    let settings = Settings::from_page(&window);
    let ice = RtcIceServerConfig {
        urls: vec![settings.stun.clone()],
        username: None,
        credential: None,
    };
    let room_url = format!(
        "{}/{}",
        settings.signal.trim_end_matches('/'),
        settings.room
    );
    let (socket, message_loop) = WebRtcSocket::builder(room_url)
        .ice_server(ice)
        .add_channel(ChannelConfig::unreliable())
        .build();
    let socket_error = Rc::new(RefCell::new(None));
    let report = socket_error.clone();
    let signal = settings.signal.clone();
    wasm_bindgen_futures::spawn_local(async move {
        if let Err(e) = message_loop.await {
            *report.borrow_mut() = Some(format!("the signalling server at {signal}: {e}"));
        }
    });
    let keys = Rc::new(Cell::new(0));
    listen_to_keys(&window, &keys)?;
    let timestep = FixedTimestep::from_hz(60.0).map_err(|e| e.to_string())?;
    let app = Rc::new(RefCell::new(App {
        socket,
        socket_error,
        phase: Phase::Waiting,
        game: Game::new(),
        timestep,
        clock: RealClock::new(),
        keys,
        settings,
        checksums: Vec::new(),
        settled: -1,
        rollbacks: 0,
        desyncs: 0,
        canvas,
        context,
    }));
    run_every_animation_frame(move || app.borrow_mut().frame());
    Ok(())
}

/// Keeps `keys` up to date with the keys held.
fn listen_to_keys(window: &web_sys::Window, keys: &Rc<Cell<Input>>) -> Result<(), JsValue> {
    for down in [true, false] {
        let keys = keys.clone();
        let on_key = Closure::<dyn FnMut(KeyboardEvent)>::new(move |event: KeyboardEvent| {
            let bit = match event.code().as_str() {
                "KeyA" | "ArrowLeft" => 1,
                "KeyD" | "ArrowRight" => 2,
                "KeyW" | "ArrowUp" | "Space" => 4,
                _ => return,
            };
            // The page does not scroll on the arrows and Space.
            event.prevent_default();
            keys.set(if down {
                keys.get() | bit
            } else {
                keys.get() & !bit
            });
        });
        let kind = if down { "keydown" } else { "keyup" };
        window.add_event_listener_with_callback(kind, on_key.as_ref().unchecked_ref())?;
        // The listener lives as long as the page.
        on_key.forget();
    }
    Ok(())
}

/// The callback of the next animation frame, once it is made.
type FrameCallback = Rc<RefCell<Option<Closure<dyn FnMut()>>>>;

/// Calls `frame` on every animation frame, for as long as the page lives.
fn run_every_animation_frame(mut frame: impl FnMut() + 'static) {
    let next: FrameCallback = Rc::new(RefCell::new(None));
    let again = next.clone();
    *next.borrow_mut() = Some(Closure::new(move || {
        frame();
        request_animation_frame(&again);
    }));
    request_animation_frame(&next);
}

fn request_animation_frame(callback: &FrameCallback) {
    if let (Some(window), Some(callback)) = (web_sys::window(), callback.borrow().as_ref()) {
        let _ = window.request_animation_frame(callback.as_ref().unchecked_ref());
    }
}

impl App {
    fn frame(&mut self) {
        if let Some(e) = self.socket_error.borrow_mut().take() {
            self.phase = Phase::Over(e);
        }
        let result = match self.phase {
            Phase::Waiting => self.connect(),
            Phase::Playing { .. } => self.play(),
            Phase::Over(_) => Ok(()),
        };
        if let Err(e) = result {
            self.phase = Phase::Over(e);
        }
        self.draw();
        self.publish();
    }

    /// Starts a session with the first other player in the room.
    fn connect(&mut self) -> Result<(), String> {
        self.socket.update_peers();
        let Some(peer) = self.socket.connected_peers().next() else {
            return Ok(());
        };
        let id = self
            .socket
            .id()
            .ok_or("connected before the server gave an id")?;
        // Both tabs order the players the same way: by id.
        let me = usize::from(id > peer);
        let channel = self.socket.take_channel(0).map_err(|e| e.to_string())?;
        let session = SessionBuilder::<WebNetplay>::new()
            .with_num_players(2)
            .and_then(|b| b.add_player(PlayerType::Local, me))
            .and_then(|b| b.add_player(PlayerType::Remote(peer), 1 - me))
            .map(|b| b.with_desync_detection_mode(DesyncDetection::On { interval: 10 }))
            .and_then(|b| b.start_p2p_session(Channel(channel)))
            .map_err(|e| e.to_string())?;
        self.phase = Phase::Playing {
            session: Box::new(session),
            me,
        };
        Ok(())
    }

    /// Runs the ticks this frame's time asks for, through GGRS.
    fn play(&mut self) -> Result<(), String> {
        let Phase::Playing { session, me } = &mut self.phase else {
            return Ok(());
        };
        let me = *me;
        self.socket.update_peers();
        session.poll_remote_clients();
        for event in session.events() {
            match event {
                GgrsEvent::DesyncDetected { .. } => self.desyncs += 1,
                GgrsEvent::Disconnected { .. } => return Err("the other player left".into()),
                _ => {}
            }
        }
        let elapsed = self.clock.frame_time();
        if session.current_state() != SessionState::Running {
            return Ok(());
        }
        for _ in self.timestep.advance(elapsed).tick_numbers() {
            let frame = u64::try_from(session.current_frame()).unwrap_or(0);
            let input = if self.settings.script {
                scripted_input(me, frame)
            } else {
                self.keys.get()
            };
            session
                .add_local_input(me, input)
                .map_err(|e| e.to_string())?;
            let requests = match session.advance_frame() {
                Ok(requests) => requests,
                // Too far ahead of the other player: wait for its inputs.
                Err(GgrsError::PredictionThreshold) => continue,
                Err(e) => return Err(e.to_string()),
            };
            let keep = self.settings.frames.unwrap_or(0);
            let rollbacks = self
                .game
                .handle_recording(requests, &mut self.checksums, keep)?;
            self.rollbacks += rollbacks as u64;
            self.settled = session.confirmed_frame();
        }
        Ok(())
    }

    /// The world, each player in its colour, and a line of status.
    fn draw(&self) {
        let (width, height) = (
            f64::from(self.canvas.width()),
            f64::from(self.canvas.height()),
        );
        let c = &self.context;
        c.set_fill_style_str("#181a20");
        c.fill_rect(0.0, 0.0, width, height);
        // The playground spans x from -16.5 to 16.5 m and y from -1 to 15 m.
        let scale = (width / 34.0).min(height / 17.0);
        let (cx, cy) = (0.0, 7.0);
        let px = |x: f32| width / 2.0 + (f64::from(x) - cx) * scale;
        let py = |y: f32| height / 2.0 - (f64::from(y) - cy) * scale;
        let players = self.game.players;
        for body in self.game.world.bodies() {
            let Some(shape) = body.shape else { continue };
            let colour = match players.iter().position(|&p| p == body.id) {
                Some(0) => "#f0a040",
                Some(_) => "#50a0f0",
                None => match body.kind {
                    BodyKind::Static => "#6a6f7c",
                    BodyKind::Kinematic => "#9aa37a",
                    BodyKind::Dynamic => "#c8c8d2",
                },
            };
            c.set_fill_style_str(colour);
            let p = body.position;
            match shape {
                Shape::Circle { radius } => {
                    c.begin_path();
                    let _ = c.arc(
                        px(p.x),
                        py(p.y),
                        f64::from(radius) * scale,
                        0.0,
                        std::f64::consts::TAU,
                    );
                    c.fill();
                }
                _ => {
                    let h = shape.half_extents();
                    c.fill_rect(
                        px(p.x - h.x),
                        py(p.y + h.y),
                        f64::from(2.0 * h.x) * scale,
                        f64::from(2.0 * h.y) * scale,
                    );
                }
            }
        }
        c.set_fill_style_str("#e0e0e0");
        c.set_font("16px sans-serif");
        let _ = c.fill_text(&self.status(), 12.0, 24.0);
    }

    fn status(&self) -> String {
        match &self.phase {
            Phase::Waiting => format!(
                "Waiting for a second player: open this page in another tab (room {}).",
                self.settings.room
            ),
            Phase::Playing { session, me } if session.current_state() != SessionState::Running => {
                format!("Player {} found: synchronising...", 2 - me)
            }
            Phase::Playing { me, .. } => format!(
                "You are player {} ({}): A/D or arrows walk, W or Space jumps. Tick {}, {} rollbacks.",
                me + 1,
                if *me == 0 { "orange" } else { "blue" },
                self.game.tick,
                self.rollbacks
            ),
            Phase::Over(reason) => format!("Game over: {reason}. Reload to play again."),
        }
    }

    /// Sets `window.passoNetplay` (see the module's documentation).
    fn publish(&self) {
        let state = js_sys::Object::new();
        let set = |key: &str, value: JsValue| {
            let _ = js_sys::Reflect::set(&state, &key.into(), &value);
        };
        let (name, me) = match &self.phase {
            Phase::Waiting => ("waiting", None),
            Phase::Playing { session, me } if session.current_state() != SessionState::Running => {
                ("syncing", Some(*me))
            }
            Phase::Playing { me, .. } => ("playing", Some(*me)),
            Phase::Over(reason) => {
                set("error", reason.as_str().into());
                ("over", None)
            }
        };
        set("state", name.into());
        if let Some(me) = me {
            set("me", (me as f64).into());
        }
        set("tick", (self.game.tick as f64).into());
        set("confirmed", f64::from(self.settled + 1).into());
        set("rollbacks", (self.rollbacks as f64).into());
        set("desyncs", (self.desyncs as f64).into());
        if let Some(n) = self.settings.frames
            && i64::from(self.settled) + 1 >= n as i64
            && self.checksums.len() as u64 >= n
        {
            let list: js_sys::Array = self.checksums[..n as usize]
                .iter()
                .map(|c| JsValue::from(format!("{c:032x}")))
                .collect();
            set("checksums", list.into());
        }
        if let Some(window) = web_sys::window() {
            let _ = js_sys::Reflect::set(&window, &"passoNetplay".into(), &state);
        }
    }
}

/// Sets `window.passoNetplay` to a game over with `message`.
fn publish_error(message: &str) {
    let state = js_sys::Object::new();
    let _ = js_sys::Reflect::set(&state, &"state".into(), &"over".into());
    let _ = js_sys::Reflect::set(&state, &"error".into(), &message.into());
    if let Some(window) = web_sys::window() {
        let _ = js_sys::Reflect::set(&window, &"passoNetplay".into(), &state);
    }
    web_sys::console::error_1(&message.into());
}
