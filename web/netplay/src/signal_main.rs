//! The signalling server the browser game's tabs meet through:
//! `passo-signal [ADDRESS]`, by default `127.0.0.1:3536` (the port the
//! page looks for). `0.0.0.0:3536` lets tabs on other machines of the
//! network in. It answers STUN on the same port, over UDP. See
//! `passo_netplay::signal`.

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    let address = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "127.0.0.1:3536".into());
    let listener = match std::net::TcpListener::bind(&address) {
        Ok(listener) => listener,
        Err(e) => {
            eprintln!("passo-signal: cannot listen on {address}: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let stun = match std::net::UdpSocket::bind(&address) {
        Ok(socket) => socket,
        Err(e) => {
            eprintln!("passo-signal: cannot answer STUN on UDP {address}: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    std::thread::spawn(move || passo_netplay::signal::stun(&stun));
    println!("signalling on ws://{address}/ and STUN on udp {address} (Ctrl-C stops it)");
    let e = passo_netplay::signal::serve(listener);
    eprintln!("passo-signal: {e}");
    std::process::ExitCode::FAILURE
}

#[cfg(target_arch = "wasm32")]
fn main() {}
