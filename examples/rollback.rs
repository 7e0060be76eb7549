//! Rollback netplay through GGRS, as a sync test: every frame GGRS saves
//! the game, rolls back seven frames and simulates them again, and compares
//! the checksums. A game that is not deterministic fails at once. Then two
//! peer-to-peer sessions play over the loopback interface, through a
//! simulated link of 80 ms latency and 5 % packet loss.
//!
//! `cargo run --release -p passo-examples --example rollback`

use passo_examples::netplay::{Link, p2p_loopback, straight_checksums, straight_run, sync_test};
use std::time::Duration;

fn main() {
    let frames = 1_000;
    match sync_test(frames, 7, false) {
        Ok(checksum) => {
            println!("{frames} frames, rolled back 7 every frame: no mismatch");
            println!(
                "checksum {checksum:032x}, straight run {:032x}",
                straight_run(frames)
            );
        }
        Err(e) => {
            eprintln!("sync test failed: {e}");
            std::process::exit(1);
        }
    }
    match sync_test(100, 7, true) {
        Err(e) => println!("with a force model that reads a global counter: caught ({e})"),
        Ok(_) => println!("with a force model that reads a global counter: not caught"),
    }
    // Two peers over the loopback interface, each with its own session,
    // through a network 80 ms away that loses 5 % of its packets.
    let frames = 1_000;
    let link = Link {
        latency: Duration::from_millis(80),
        loss_percent: 5,
        ..Link::default()
    };
    println!("two peers, {frames} frames at 60 Hz over a link of 80 ms and 5 % loss...");
    match p2p_loopback(frames, link) {
        Ok(reports) => {
            let straight = straight_checksums(frames);
            for (peer, report) in reports.iter().enumerate() {
                let agree = report.checksums[..frames as usize] == straight[..];
                println!(
                    "peer {peer}: {} rollbacks, {} desyncs, every tick as the straight run: {agree}",
                    report.rollbacks, report.desyncs
                );
            }
        }
        Err(e) => {
            eprintln!("peer-to-peer run failed: {e}");
            std::process::exit(1);
        }
    }
}
