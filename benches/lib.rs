//! Criterion benchmarks of Passo: `cargo bench -p passo-benches`.
