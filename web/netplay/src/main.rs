//! The netplay game in a browser tab: built for `wasm32-unknown-unknown`
//! by `web/build.sh`. Natively it only says so.

#[cfg(target_arch = "wasm32")]
fn main() {
    passo_netplay::browser::start();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    eprintln!(
        "passo-netplay runs in a browser: `bash web/netplay.sh` builds it and serves it \
         (natively, `cargo run --release -p passo-examples --example rollback` plays it over UDP)"
    );
    std::process::exit(2);
}
