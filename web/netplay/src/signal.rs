//! A signalling server for the browser game: it introduces the tabs of a
//! room to each other, then they talk directly over WebRTC.
//!
//! It speaks `matchbox_socket`'s protocol (the one `matchbox_server`
//! speaks, JSON over a WebSocket): a tab connects to `ws://HOST:PORT/ROOM`
//! and is sent its id (`{"IdAssigned": ID}`); every tab already in the room
//! is told of it (`{"NewPeer": ID}`) and starts a WebRTC handshake, whose
//! offers, answers and ICE candidates the server passes on
//! (`{"Signal": {"receiver": ID, "data": ...}}` in, `{"Signal":
//! {"sender": ID, "data": ...}}` out); a tab that leaves is announced
//! (`{"PeerLeft": ID}`). One thread a connection, for a few tabs on one
//! machine or one network: `passo-signal` runs it, and `web/check` runs
//! one in-process for its netplay check.
//!
//! On the same port, over UDP, it answers STUN binding requests
//! ([`stun`]), which the tabs need before they can connect.

use serde_json::{Value, json};
use std::collections::BTreeMap;
use std::io;
use std::net::{IpAddr, SocketAddr, TcpListener, TcpStream, ToSocketAddrs, UdpSocket};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, SystemTime, UNIX_EPOCH};
use tungstenite::handshake::server::{Request, Response};
use tungstenite::{Error, Message, WebSocket};

/// The tabs of each room: their ids and where to send them messages.
type Rooms = Arc<Mutex<BTreeMap<String, BTreeMap<String, Sender<String>>>>>;

/// Listens on `address` (port 0: one the system picks) and serves
/// signalling (TCP) and STUN (UDP, the same port) on threads of its own
/// until the process ends. Returns the address it listens on.
pub fn spawn(address: impl ToSocketAddrs) -> io::Result<SocketAddr> {
    let listener = TcpListener::bind(address)?;
    let local = listener.local_addr()?;
    let stun_socket = UdpSocket::bind(local)?;
    std::thread::spawn(move || serve(listener));
    std::thread::spawn(move || stun(&stun_socket));
    Ok(local)
}

/// Answers STUN binding requests on `socket` (RFC 8489) with the address
/// each came from, until the socket fails. A browser asks a STUN server
/// its address as the network sees it while it gathers its ways of being
/// reached, and `matchbox_socket` waits for that gathering to finish:
/// with no STUN server it cannot start, and with one it cannot reach (a
/// machine off the internet) it waits for good. Tabs on one machine or
/// one network need no more than this one.
pub fn stun(socket: &UdpSocket) -> io::Error {
    let mut buffer = [0u8; 1500];
    loop {
        let (n, from) = match socket.recv_from(&mut buffer) {
            Ok(got) => got,
            // A reply to a tab already gone can report here: go on.
            Err(e) if e.kind() == io::ErrorKind::ConnectionReset => continue,
            Err(e) => return e,
        };
        if let Some(reply) = stun_reply(&buffer[..n], from) {
            let _ = socket.send_to(&reply, from);
        }
    }
}

/// The magic cookie every STUN message carries after its type and length.
const STUN_COOKIE: u32 = 0x2112_a442;

/// The success response to a STUN binding request from `from`: its
/// transaction id and an XOR-MAPPED-ADDRESS of `from`. `None` for anything
/// else.
fn stun_reply(request: &[u8], from: SocketAddr) -> Option<Vec<u8>> {
    let header = request.get(..20)?;
    let binding_request = header[..2] == [0x00, 0x01];
    if !binding_request || header[4..8] != STUN_COOKIE.to_be_bytes() {
        return None;
    }
    let cookie = STUN_COOKIE.to_be_bytes();
    let port = from.port() ^ (STUN_COOKIE >> 16) as u16;
    let (family, address): (u8, Vec<u8>) = match from.ip() {
        IpAddr::V4(ip) => (
            1,
            ip.octets().iter().zip(cookie).map(|(a, b)| a ^ b).collect(),
        ),
        IpAddr::V6(ip) => {
            // XORed with the cookie and then the transaction id.
            let key = cookie.iter().chain(&header[8..20]);
            (2, ip.octets().iter().zip(key).map(|(a, b)| a ^ b).collect())
        }
    };
    let value_length = 4 + address.len() as u16;
    let mut reply = Vec::with_capacity(24 + address.len());
    reply.extend_from_slice(&[0x01, 0x01]); // binding success response
    reply.extend_from_slice(&(4 + value_length).to_be_bytes());
    reply.extend_from_slice(&header[4..20]); // the cookie and transaction id
    reply.extend_from_slice(&[0x00, 0x20]); // XOR-MAPPED-ADDRESS
    reply.extend_from_slice(&value_length.to_be_bytes());
    reply.extend_from_slice(&[0, family]);
    reply.extend_from_slice(&port.to_be_bytes());
    reply.extend_from_slice(&address);
    Some(reply)
}

/// Serves signalling on `listener`, a thread for each connection, until
/// the listener fails.
pub fn serve(listener: TcpListener) -> io::Error {
    let rooms = Rooms::default();
    let ids = Arc::new(Ids::new());
    loop {
        match listener.accept() {
            Ok((stream, _)) => {
                let (rooms, ids) = (rooms.clone(), ids.clone());
                std::thread::spawn(move || {
                    // A tab that breaks the protocol or goes away mid-way
                    // is dropped; the others go on.
                    let _ = connection(stream, &rooms, &ids);
                });
            }
            // The listener itself failed (not one connection): stop.
            Err(e) if e.kind() != io::ErrorKind::ConnectionAborted => return e,
            Err(_) => {}
        }
    }
}

/// Ids in the form of the UUIDs the tabs expect, distinct within a run and
/// unlikely to repeat across runs.
struct Ids {
    seed: u64,
    next: AtomicU64,
}

impl Ids {
    fn new() -> Self {
        let now = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos() as u64);
        Self {
            seed: now ^ u64::from(std::process::id()).rotate_left(32),
            next: AtomicU64::new(1),
        }
    }

    fn next(&self) -> String {
        let n = self.next.fetch_add(1, Ordering::Relaxed);
        // Version 4, variant 1, like a random UUID.
        format!(
            "{:08x}-{:04x}-4{:03x}-8{:03x}-{:012x}",
            self.seed >> 32,
            (self.seed >> 16) & 0xffff,
            self.seed & 0xfff,
            (n >> 48) & 0xfff,
            n & 0xffff_ffff_ffff
        )
    }
}

/// One tab, from its handshake until it leaves.
fn connection(stream: TcpStream, rooms: &Rooms, ids: &Ids) -> Result<(), Error> {
    let mut room = String::new();
    let mut ws = tungstenite::accept_hdr(stream, |request: &Request, response: Response| {
        room = request.uri().path().trim_matches('/').to_owned();
        Ok(response)
    })
    .map_err(|e| match e {
        tungstenite::HandshakeError::Failure(e) => e,
        // A blocking stream never interrupts the handshake.
        tungstenite::HandshakeError::Interrupted(_) => Error::Io(io::ErrorKind::WouldBlock.into()),
    })?;
    // Reads wait this long, then the messages for the tab go out.
    ws.get_ref()
        .set_read_timeout(Some(Duration::from_millis(10)))?;
    let id = ids.next();
    let (sender, inbox) = channel();
    ws.send(Message::text(json!({ "IdAssigned": id }).to_string()))?;
    {
        let mut rooms = rooms.lock().unwrap_or_else(|e| e.into_inner());
        let peers = rooms.entry(room.clone()).or_default();
        let arrived = json!({ "NewPeer": id }).to_string();
        for other in peers.values() {
            let _ = other.send(arrived.clone());
        }
        peers.insert(id.clone(), sender);
    }
    let result = relay(&mut ws, &id, &room, rooms, &inbox);
    let mut rooms = rooms.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(peers) = rooms.get_mut(&room) {
        peers.remove(&id);
        let left = json!({ "PeerLeft": id }).to_string();
        for other in peers.values() {
            let _ = other.send(left.clone());
        }
        if peers.is_empty() {
            rooms.remove(&room);
        }
    }
    result
}

/// Passes the tab's signals on to their receivers, and the messages for it
/// to it, until it leaves.
fn relay(
    ws: &mut WebSocket<TcpStream>,
    id: &str,
    room: &str,
    rooms: &Rooms,
    inbox: &Receiver<String>,
) -> Result<(), Error> {
    loop {
        match ws.read() {
            Ok(Message::Text(text)) => {
                let request: Value = serde_json::from_str(text.as_str()).unwrap_or(Value::Null);
                // `"KeepAlive"` and anything unknown need no answer.
                if let Some(signal) = request.get("Signal")
                    && let Some(receiver) = signal.get("receiver").and_then(Value::as_str)
                {
                    let event = json!({ "Signal": { "sender": id, "data": signal["data"] } });
                    let rooms = rooms.lock().unwrap_or_else(|e| e.into_inner());
                    if let Some(to) = rooms.get(room).and_then(|peers| peers.get(receiver)) {
                        let _ = to.send(event.to_string());
                    }
                }
            }
            Ok(Message::Close(_)) | Err(Error::ConnectionClosed | Error::AlreadyClosed) => {
                return Ok(());
            }
            Ok(_) => {}
            Err(Error::Io(e))
                if matches!(
                    e.kind(),
                    io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
                ) => {}
            Err(e) => return Err(e),
        }
        while let Ok(message) = inbox.try_recv() {
            ws.send(Message::text(message))?;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::net::{Ipv4Addr, Ipv6Addr};

    /// A binding request with the transaction id of RFC 5769's samples.
    fn request() -> Vec<u8> {
        let mut r = vec![0x00, 0x01, 0x00, 0x00];
        r.extend_from_slice(&STUN_COOKIE.to_be_bytes());
        r.extend_from_slice(&[
            0xb7, 0xe7, 0xa7, 0x01, 0xbc, 0x34, 0xd6, 0x86, 0xfa, 0x87, 0xdf, 0xae,
        ]);
        r
    }

    #[test]
    fn stun_answers_with_the_xor_mapped_address_of_rfc_5769s_samples() {
        // RFC 5769, 2.2 and 2.3: 192.0.2.1 and 2001:db8:1234:5678:11:2233:4455:6677,
        // port 32853.
        let v4 = SocketAddr::from((Ipv4Addr::new(192, 0, 2, 1), 32853));
        let reply = stun_reply(&request(), v4).unwrap();
        assert_eq!(reply[..4], [0x01, 0x01, 0x00, 0x0c]);
        assert_eq!(reply[4..20], request()[4..20]);
        assert_eq!(
            reply[20..],
            [
                0x00, 0x20, 0x00, 0x08, 0x00, 0x01, 0xa1, 0x47, 0xe1, 0x12, 0xa6, 0x43
            ]
        );
        let ip: Ipv6Addr = "2001:db8:1234:5678:11:2233:4455:6677".parse().unwrap();
        let reply = stun_reply(&request(), SocketAddr::from((ip, 32853))).unwrap();
        assert_eq!(reply[..4], [0x01, 0x01, 0x00, 0x18]);
        assert_eq!(
            reply[20..],
            [
                0x00, 0x20, 0x00, 0x14, 0x00, 0x02, 0xa1, 0x47, 0x01, 0x13, 0xa9, 0xfa, 0xa5, 0xd3,
                0xf1, 0x79, 0xbc, 0x25, 0xf4, 0xb5, 0xbe, 0xd2, 0xb9, 0xd9
            ]
        );
    }

    #[test]
    fn stun_ignores_what_is_not_a_binding_request() {
        let from = SocketAddr::from((Ipv4Addr::LOCALHOST, 5000));
        assert!(stun_reply(&request()[..19], from).is_none(), "too short");
        let mut response = request();
        response[1] = 0x11;
        assert!(stun_reply(&response, from).is_none(), "not a request");
        let mut no_cookie = request();
        no_cookie[4] ^= 1;
        assert!(stun_reply(&no_cookie, from).is_none(), "no magic cookie");
    }

    #[test]
    fn stun_answers_over_udp_on_the_signalling_port() {
        let address = spawn("127.0.0.1:0").unwrap();
        let client = UdpSocket::bind("127.0.0.1:0").unwrap();
        client
            .set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
        client.send_to(&request(), address).unwrap();
        let mut buffer = [0u8; 64];
        let (n, _) = client.recv_from(&mut buffer).unwrap();
        let mine = client.local_addr().unwrap();
        assert_eq!(buffer[..n], stun_reply(&request(), mine).unwrap()[..]);
    }

    type Client = WebSocket<tungstenite::stream::MaybeTlsStream<TcpStream>>;

    fn join(address: SocketAddr, room: &str) -> Client {
        let (ws, _) = tungstenite::connect(format!("ws://{address}/{room}")).unwrap();
        if let tungstenite::stream::MaybeTlsStream::Plain(s) = ws.get_ref() {
            s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        }
        ws
    }

    fn next(ws: &mut Client) -> Value {
        loop {
            if let Message::Text(text) = ws.read().unwrap() {
                return serde_json::from_str(text.as_str()).unwrap();
            }
        }
    }

    #[test]
    fn a_room_introduces_its_tabs_and_passes_their_signals_on() {
        let address = spawn("127.0.0.1:0").unwrap();
        let mut first = join(address, "room");
        let first_id = next(&mut first)["IdAssigned"].as_str().unwrap().to_owned();
        let mut second = join(address, "room");
        let second_id = next(&mut second)["IdAssigned"].as_str().unwrap().to_owned();
        assert_ne!(first_id, second_id);
        // A tab in another room is not introduced.
        let mut elsewhere = join(address, "other");
        next(&mut elsewhere);
        // The first tab hears of the second, and only of it.
        assert_eq!(next(&mut first), json!({ "NewPeer": second_id }));
        let offer = json!({ "Offer": "sdp" });
        let signal = json!({ "Signal": { "receiver": second_id, "data": offer } });
        first.send(Message::text(signal.to_string())).unwrap();
        first.send(Message::text("\"KeepAlive\"")).unwrap();
        assert_eq!(
            next(&mut second),
            json!({ "Signal": { "sender": first_id, "data": offer } })
        );
        drop(second);
        assert_eq!(next(&mut first), json!({ "PeerLeft": second_id }));
        // The other room heard nothing: its next message is the first
        // tab's arrival there.
        let mut late = join(address, "other");
        let late_id = next(&mut late)["IdAssigned"].clone();
        assert_eq!(next(&mut elsewhere), json!({ "NewPeer": late_id }));
    }
}
