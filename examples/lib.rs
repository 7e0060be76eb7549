//! Examples of Passo; run one with `cargo run -p passo-examples --example NAME`.
