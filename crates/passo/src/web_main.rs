//! The demo in a browser: built for `wasm32-unknown-unknown` by
//! `web/build.sh`, which runs `wasm-bindgen` on it and writes the page.
//! Natively it only says so.

#[cfg(target_arch = "wasm32")]
fn main() {
    passo::demo::web::start();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    eprintln!(
        "passo-web is the demo for a browser: build it with `bash web/build.sh` \
         (natively, run `cargo run --release`)"
    );
    std::process::exit(2);
}
