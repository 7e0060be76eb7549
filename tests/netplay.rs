//! Rollback netplay through GGRS: the example game of `passo-examples`
//! survives GGRS's sync test (save every frame, roll back, simulate again,
//! compare checksums), ends where a straight run ends, and a force model
//! that is not deterministic is caught; two peer-to-peer sessions over the
//! loopback interface roll back and agree, tick by tick, with a straight
//! run, also through a link of 80 ms latency and 5 % packet loss, and one
//! whose packets overtake each other; a peer sending input bits no key
//! makes ends the session with an error naming it.

use ggrs::{GgrsError, GgrsRequest, InputStatus, NonBlockingSocket};
use passo_examples::netplay::{
    Game, Link, LoopbackSocket, Netplay, check_inputs, p2p_loopback, scripted_input,
    straight_checksums, straight_run, sync_test,
};
use std::time::Duration;

#[test]
fn the_sync_test_passes_and_ends_where_a_straight_run_ends() {
    let frames = 1_000;
    let synced = sync_test(frames, 7, false).expect("no checksum mismatch");
    assert_eq!(synced, straight_run(frames));
}

#[test]
fn a_force_model_that_is_not_deterministic_is_caught() {
    // At the check distances the docs advise, the shortest and a longer.
    for distance in [2, 7] {
        match sync_test(60, distance, true) {
            Err(GgrsError::MismatchedChecksum { .. }) => {}
            other => panic!("distance {distance}: expected a checksum mismatch, got {other:?}"),
        }
    }
}

#[test]
fn queries_after_a_load_answer_as_when_the_state_was_saved() {
    // The game decides jumps with `is_standing`, which reads the contacts
    // of the last step: a load must bring them back.
    // Saved at the first frame from 300 on at which a player touches
    // something (the players jump and land as the script says).
    let mut game = Game::new();
    let mut saved = None;
    for frame in 0..400 {
        game.advance([scripted_input(0, frame), scripted_input(1, frame)]);
        if frame >= 300 && anyone_touching(&game) && saved.is_none() {
            saved = Some((game.world.snapshot(), game.tick, frame));
        }
    }
    let (snapshot, tick, at) = saved.expect("a player touches something after frame 300");
    let mut original = Game::new();
    for frame in 0..=at {
        original.advance([scripted_input(0, frame), scripted_input(1, frame)]);
    }
    game.world.restore_from(&snapshot).unwrap();
    game.tick = tick;
    for &player in &game.players {
        assert_eq!(
            game.world.contacts_of(player).collect::<Vec<_>>(),
            original.world.contacts_of(player).collect::<Vec<_>>()
        );
        assert_eq!(
            game.world.is_standing(player, 0.8),
            original.world.is_standing(player, 0.8)
        );
    }
    assert!(
        anyone_touching(&game),
        "a player touches something at frame {at}"
    );
}

/// Whether some player touches something after the last step.
fn anyone_touching(game: &Game) -> bool {
    game.players
        .iter()
        .any(|&p| game.world.contacts_of(p).next().is_some())
}

fn two_peers_agree_with_a_straight_run_tick_by_tick(frames: u64, link: Link) {
    let reports = p2p_loopback(frames, link).expect("the peers play");
    if !link.jitter.is_zero() {
        assert!(
            reports.iter().all(|r| r.overtaken > 10),
            "packets overtook each other: {:?}",
            reports.iter().map(|r| r.overtaken).collect::<Vec<_>>()
        );
    }
    let straight = straight_checksums(frames);
    for (peer, report) in reports.iter().enumerate() {
        assert_eq!(
            &report.checksums[..frames as usize],
            &straight[..],
            "peer {peer} differs from the straight run"
        );
        assert_eq!(report.desyncs, 0, "peer {peer} saw a desync");
    }
    assert!(
        reports.iter().any(|r| r.rollbacks > 0),
        "the peers predicted and rolled back: {:?}",
        reports.iter().map(|r| r.rollbacks).collect::<Vec<_>>()
    );
}

#[test]
fn two_peers_over_loopback_agree_with_a_straight_run_tick_by_tick() {
    two_peers_agree_with_a_straight_run_tick_by_tick(300, Link::default());
}

#[test]
fn two_peers_80_ms_apart_losing_5_percent_of_packets_agree_for_1000_ticks() {
    // Runs at 60 frames a second of wall time: about 17 s.
    let link = Link {
        latency: Duration::from_millis(80),
        loss_percent: 5,
        ..Link::default()
    };
    two_peers_agree_with_a_straight_run_tick_by_tick(1_000, link);
}

#[test]
fn two_peers_whose_packets_overtake_each_other_agree_for_300_ticks() {
    // 20-80 ms one way: a packet often arrives before one sent a frame or
    // two earlier. Runs at 60 frames a second of wall time: about 5 s.
    let link = Link {
        latency: Duration::from_millis(20),
        jitter: Duration::from_millis(60),
        loss_percent: 2,
    };
    two_peers_agree_with_a_straight_run_tick_by_tick(300, link);
}

#[test]
fn input_bits_no_key_makes_end_the_session_with_an_error_naming_the_peer() {
    for bad in [0b1000u8, 0x80, 0xff] {
        for player in 0..2 {
            let mut inputs = [(scripted_input(0, 0), InputStatus::Confirmed); 2];
            inputs[player].0 = bad;
            let mut game = Game::new();
            let error = game
                .handle_one::<Netplay>(GgrsRequest::AdvanceFrame {
                    inputs: inputs.to_vec(),
                })
                .unwrap_err();
            assert!(error.contains(&format!("player {player}")), "{error}");
            assert_eq!(game.tick, 0, "nothing was played");
        }
    }
    // Every input a key makes is played.
    for input in 0..=0b111 {
        assert_eq!(check_inputs(&[input, 0]), Ok(()));
    }
}

/// The peers listen on the loopback interface alone. Datagrams that do not
/// decode (noise, one cut short) are dropped; ones that happen to decode
/// (a run of zeros is a valid message) reach GGRS, which handles only
/// messages from its peers' addresses and, once synchronised, with their
/// magic number. Neither panics, nor does a datagram too long for the
/// buffer.
#[test]
fn the_peers_socket_listens_on_loopback_alone_and_drops_what_does_not_decode() {
    let mut socket = LoopbackSocket::bind().unwrap();
    let address = socket.local_addr().unwrap();
    assert!(address.ip().is_loopback(), "bound to {address}");
    let sender = std::net::UdpSocket::bind(("127.0.0.1", 0)).unwrap();
    let receive = |socket: &mut LoopbackSocket, datagram: &[u8]| {
        sender.send_to(datagram, address).unwrap();
        // Loopback delivery is quick but not instant: give it a moment.
        std::thread::sleep(Duration::from_millis(20));
        socket.receive_all_messages().len()
    };
    for noise in [&[][..], &[0xff; 3], &[7; 600]] {
        assert_eq!(receive(&mut socket, noise), 0, "{} bytes", noise.len());
    }
    assert!(receive(&mut socket, &[0; 8000]) <= 1);
}
