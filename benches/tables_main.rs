//! Prints the tables of BENCHMARKS.md that the code decides to the bit
//! (`passo_benches::tables`), or, with `--write`, puts them into
//! BENCHMARKS.md between their markers.
//!
//! Run: `cargo run --release -p passo-benches --bin tables [-- --write]`

use passo_benches::tables::{all, benchmarks_md, replace, write_flag};

fn main() {
    let write = write_flag();
    let tables = all();
    if !write {
        for table in &tables {
            println!(
                "<!-- table: {} -->\n{}<!-- /table -->\n",
                table.name, table.markdown
            );
        }
        return;
    }
    let path = benchmarks_md();
    let mut doc = match std::fs::read_to_string(&path) {
        Ok(doc) => doc,
        Err(e) => {
            eprintln!("cannot read {}: {e}", path.display());
            std::process::exit(1);
        }
    };
    for table in &tables {
        doc = match replace(&doc, table.name, &table.markdown) {
            Ok(doc) => doc,
            Err(e) => {
                eprintln!("{}: {e}", path.display());
                std::process::exit(1);
            }
        };
    }
    if let Err(e) = std::fs::write(&path, doc) {
        eprintln!("cannot write {}: {e}", path.display());
        std::process::exit(1);
    }
    eprintln!("wrote {} tables into {}", tables.len(), path.display());
}
