//! The stability suite's table: every hard case of
//! `passo_benches::stability` in Passo and, with the `box2d` feature, in
//! Box2D v3 (rotation fixed), one after the other in one run.
//!
//! Run: `cargo run --release -p passo-benches --features box2d --bin stability [CASE ...]`
//! (no case: all of them). It prints a Markdown table, the one in
//! BENCHMARKS.md, "Stability on hard cases".

use passo_benches::stability::{HEADER, Passo, cases, row, run};

fn main() {
    let wanted: Vec<String> = std::env::args().skip(1).collect();
    let cases: Vec<_> = cases()
        .into_iter()
        .filter(|c| wanted.is_empty() || wanted.iter().any(|w| w == c.name))
        .collect();
    if cases.is_empty() {
        let names: Vec<_> = passo_benches::stability::cases()
            .iter()
            .map(|c| c.name)
            .collect();
        eprintln!("no such case; the cases are: {}", names.join(" "));
        std::process::exit(2);
    }
    println!("{HEADER}");
    for case in &cases {
        let passo = run(case, &mut Passo(case.world.clone()));
        println!("{}", row(case, "Passo", &passo));
        #[cfg(feature = "box2d")]
        {
            let mut engine = passo_benches::stability::Box2dEngine {
                box2d: passo_benches::box2d::copy(&case.world, false),
                template: case.world.clone(),
            };
            let box2d = run(case, &mut engine);
            println!("{}", row(case, "Box2D v3", &box2d));
        }
    }
    println!();
    for case in &cases {
        println!("- `{}`: {}.", case.name, case.what);
    }
}
