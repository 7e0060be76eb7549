//! Rollback netplay with GGRS over UDP: the two-player game of
//! `passo-netplay` (re-exported here), a GGRS sync test of it, and two
//! peer-to-peer sessions on the loopback interface, through a simulated
//! link of chosen latency and loss. The same game plays in two browser
//! tabs over WebRTC: `web/netplay/`.

use ggrs::{
    DesyncDetection, GgrsError, GgrsEvent, Message, NonBlockingSocket, P2PSession, PlayerType,
    SessionBuilder, SessionState,
};
pub use passo_netplay::game::{
    DT, Game, Input, KEYS, Rollback, check_inputs, scripted_input, straight_checksums, straight_run,
};
use passo_physics::glam::Vec2;
use std::net::{Ipv4Addr, SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The GGRS configuration of the game over UDP.
pub type Netplay = passo_netplay::game::Netplay<SocketAddr>;

/// A force model that is not deterministic: it reads a counter that grows
/// with every call, so a re-simulated tick pushes differently. For showing
/// that the sync test catches such a bug.
pub struct Nondeterministic(pub AtomicU64);

impl passo_physics::ForceModel for Nondeterministic {
    fn force(&self, _: Vec2, _: Vec2, _: f32) -> Vec2 {
        let n = self.0.fetch_add(1, Ordering::Relaxed);
        // Scrambled, so no rollback distance repeats the pattern.
        let bits = n.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 60;
        Vec2::new(bits as f32 * 0.01, 0.0)
    }
}

/// Runs a GGRS sync test of `frames` frames: every frame GGRS saves, rolls
/// back `check_distance` frames and simulates them again, comparing
/// checksums. Returns the final checksum, or GGRS's error (a checksum
/// mismatch when the game is not deterministic). With `broken`, the game
/// gets a [`Nondeterministic`] force model. Use a check distance of 2 or
/// more: with 1, the broken model passed GGRS 0.13's sync test (2 and 7
/// catch it, `tests/netplay.rs`).
pub fn sync_test(frames: u64, check_distance: usize, broken: bool) -> Result<u128, GgrsError> {
    let mut game = Game::new();
    if broken {
        game.world
            .add_force_model(Arc::new(Nondeterministic(AtomicU64::new(0))));
    }
    let mut session = SessionBuilder::<Netplay>::new()
        .with_num_players(2)?
        .with_check_distance(check_distance)
        .start_synctest_session()?;
    for frame in 0..frames {
        for player in 0..2 {
            session.add_local_input(player, scripted_input(player, frame))?;
        }
        let requests = session.advance_frame()?;
        game.handle(requests)
            .map_err(|info| GgrsError::InvalidRequest { info })?;
    }
    Ok(game.checksum())
}

/// What one peer of [`p2p_loopback`] saw.
#[derive(Debug, Default)]
pub struct PeerReport {
    /// The checksum after each tick (`[t]` after `t + 1` ticks), as it
    /// stood at the end: a tick simulated again after a rollback
    /// overwrites its first checksum.
    pub checksums: Vec<u128>,
    /// Rollbacks: GGRS loaded a saved state.
    pub rollbacks: usize,
    /// Desyncs GGRS reported (checksums the peers exchanged that differ).
    pub desyncs: usize,
    /// Packets the link delivered to this peer before one sent earlier.
    pub overtaken: u64,
}

/// A simulated network between the peers of [`p2p_loopback`]: every
/// packet arrives `latency` late, plus up to `jitter` more (so packets
/// overtake each other), and `loss_percent` of them never do.
#[derive(Clone, Copy, Debug, Default)]
pub struct Link {
    /// One-way delay of every packet.
    pub latency: Duration,
    /// Extra delay, from zero to this, drawn per packet: a packet sent
    /// later may arrive first.
    pub jitter: Duration,
    /// Packets dropped, percent (chosen by a seeded generator, so a run
    /// drops the same share each time).
    pub loss_percent: u32,
}

/// A non-blocking UDP socket bound to the loopback interface alone, on a
/// port the system picks, speaking GGRS's wire format (its messages in
/// bincode, as `ggrs::UdpNonBlockingSocket` does). That socket binds every
/// interface (`0.0.0.0`): peers that only talk to each other on this
/// machine should not listen on the network.
pub struct LoopbackSocket {
    socket: UdpSocket,
    buffer: Box<[u8; LoopbackSocket::BUFFER]>,
}

impl LoopbackSocket {
    /// The largest datagram read (GGRS's own buffer size); a longer one is
    /// cut short, fails to decode and is dropped.
    const BUFFER: usize = 4096;

    /// Binds `127.0.0.1` on a free port.
    pub fn bind() -> std::io::Result<Self> {
        let socket = UdpSocket::bind((Ipv4Addr::LOCALHOST, 0))?;
        socket.set_nonblocking(true)?;
        Ok(Self {
            socket,
            buffer: Box::new([0; Self::BUFFER]),
        })
    }

    /// Where the other peer sends to.
    pub fn local_addr(&self) -> std::io::Result<SocketAddr> {
        self.socket.local_addr()
    }
}

impl NonBlockingSocket<SocketAddr> for LoopbackSocket {
    fn send_to(&mut self, msg: &Message, addr: &SocketAddr) {
        // A message that does not encode, or a send that fails, is a lost
        // packet: GGRS sends again.
        if let Ok(bytes) = bincode::serialize(msg) {
            let _ = self.socket.send_to(&bytes, addr);
        }
    }

    fn receive_all_messages(&mut self) -> Vec<(SocketAddr, Message)> {
        let mut received = Vec::new();
        loop {
            match self.socket.recv_from(&mut self.buffer[..]) {
                Ok((n, from)) => {
                    // What does not decode (noise, a cut datagram) is dropped.
                    if let Ok(msg) = bincode::deserialize(&self.buffer[..n]) {
                        received.push((from, msg));
                    }
                }
                // A send to a peer that is gone reports here on some systems.
                Err(e) if e.kind() == std::io::ErrorKind::ConnectionReset => {}
                // Nothing more now (`WouldBlock`), or a failure: try next frame.
                Err(_) => return received,
            }
        }
    }
}

/// A [`LoopbackSocket`] behind a [`Link`]: packets are held on arrival
/// until their delay is over, and some are dropped.
struct LinkSocket {
    socket: LoopbackSocket,
    link: Link,
    /// Packets arrived and not yet delivered, in arrival order, each with
    /// when it is due and its place in the arrival order.
    held: Vec<(Instant, u64, SocketAddr, Message)>,
    /// Packets that arrived so far.
    arrived: u64,
    /// The arrival place of the last packet delivered.
    last_delivered: u64,
    /// Packets delivered before one that arrived earlier (shared with
    /// [`p2p_loopback`], which reports them).
    overtaking: Arc<AtomicU64>,
    rng: u64,
}

impl NonBlockingSocket<SocketAddr> for LinkSocket {
    fn send_to(&mut self, msg: &Message, addr: &SocketAddr) {
        self.socket.send_to(msg, addr);
    }

    fn receive_all_messages(&mut self) -> Vec<(SocketAddr, Message)> {
        let now = Instant::now();
        for (from, msg) in self.socket.receive_all_messages() {
            let roll = self.next_random();
            if roll % 100 >= u64::from(self.link.loss_percent) {
                let jitter = self
                    .link
                    .jitter
                    .mul_f64((self.next_random() % 1000) as f64 / 1000.0);
                self.arrived += 1;
                let due = now + self.link.latency + jitter;
                self.held.push((due, self.arrived, from, msg));
            }
        }
        // Every packet that is due, in the order they fall due.
        let (mut due, held): (Vec<_>, Vec<_>) =
            self.held.drain(..).partition(|(at, ..)| *at <= now);
        self.held = held;
        due.sort_by_key(|&(at, place, ..)| (at, place));
        let mut out = Vec::with_capacity(due.len());
        for (_, place, from, msg) in due {
            if place < self.last_delivered {
                self.overtaking.fetch_add(1, Ordering::Relaxed);
            }
            self.last_delivered = place;
            out.push((from, msg));
        }
        out
    }
}

impl LinkSocket {
    /// xorshift64*: the same drops and delays on every run.
    fn next_random(&mut self) -> u64 {
        self.rng ^= self.rng >> 12;
        self.rng ^= self.rng << 25;
        self.rng ^= self.rng >> 27;
        self.rng.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
}

/// Two peers in this process, each a GGRS peer-to-peer session on its own
/// UDP port of the loopback interface with one local player, play
/// `frames` frames of scripted input through `link`, exchanging inputs and
/// (every ten frames) checksums. With a latency they run at 60 frames a
/// second of wall time, as games do, so inputs arrive frames late and GGRS
/// predicts and rolls back; without one they advance in turn as fast as
/// they can (each before it has the other's input for the frame, so the
/// first still rolls back). Returns each peer's report once both have
/// confirmed `frames` frames.
pub fn p2p_loopback(frames: u64, link: Link) -> Result<[PeerReport; 2], String> {
    let bind = || LoopbackSocket::bind().map_err(|e| format!("cannot bind a UDP socket: {e}"));
    let sockets = [bind()?, bind()?];
    let address = |s: &LoopbackSocket| s.local_addr().map_err(|e| e.to_string());
    let addresses = [address(&sockets[0])?, address(&sockets[1])?];
    let mut sessions = Vec::new();
    let overtaking = [Arc::new(AtomicU64::new(0)), Arc::new(AtomicU64::new(0))];
    for (me, socket) in sockets.into_iter().enumerate() {
        let other = 1 - me;
        let remote = addresses[other];
        let socket = LinkSocket {
            socket,
            link,
            held: Default::default(),
            arrived: 0,
            last_delivered: 0,
            overtaking: overtaking[me].clone(),
            rng: 0x9e37_79b9_7f4a_7c15 ^ me as u64,
        };
        let session = SessionBuilder::<Netplay>::new()
            .with_num_players(2)
            .and_then(|b| b.add_player(PlayerType::Local, me))
            .and_then(|b| b.add_player(PlayerType::Remote(remote), other))
            .map(|b| b.with_desync_detection_mode(DesyncDetection::On { interval: 10 }))
            .and_then(|b| b.start_p2p_session(socket))
            .map_err(|e| e.to_string())?;
        sessions.push(session);
    }
    let deadline = Instant::now() + Duration::from_secs(30 + frames / 30);
    while sessions
        .iter()
        .any(|s| s.current_state() != SessionState::Running)
    {
        sessions.iter_mut().for_each(|s| s.poll_remote_clients());
        if Instant::now() > deadline {
            return Err("the peers did not connect within 30 s".into());
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    let mut games = [Game::new(), Game::new()];
    let mut reports = [PeerReport::default(), PeerReport::default()];
    let mut next_frame = Instant::now();
    let confirmed = |s: &P2PSession<Netplay>| u64::try_from(s.confirmed_frame()).unwrap_or(0);
    while sessions.iter().any(|s| confirmed(s) < frames) {
        if Instant::now() > deadline {
            return Err("the peers did not confirm every frame in time".into());
        }
        for me in 0..2 {
            let session = &mut sessions[me];
            session.poll_remote_clients();
            for event in session.events() {
                if let GgrsEvent::DesyncDetected { .. } = event {
                    reports[me].desyncs += 1;
                }
            }
            let frame = u64::try_from(session.current_frame()).unwrap_or(0);
            session
                .add_local_input(me, scripted_input(me, frame))
                .map_err(|e| e.to_string())?;
            let requests = match session.advance_frame() {
                Ok(requests) => requests,
                // Too far ahead of the other peer: wait for its inputs.
                Err(GgrsError::PredictionThreshold) => continue,
                Err(e) => return Err(e.to_string()),
            };
            reports[me].rollbacks +=
                games[me].handle_recording(requests, &mut reports[me].checksums, u64::MAX)?;
        }
        if link.latency.is_zero() {
            std::thread::sleep(Duration::from_micros(200));
        } else {
            next_frame += Duration::from_secs_f32(DT);
            std::thread::sleep(next_frame.saturating_duration_since(Instant::now()));
        }
    }
    for (report, overtaken) in reports.iter_mut().zip(&overtaking) {
        report.overtaken = overtaken.load(Ordering::Relaxed);
    }
    Ok(reports)
}
