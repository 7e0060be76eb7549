//! Every shipped scene loads, runs only the stages it declares, and
//! survives a round trip through a file; no text makes the loader panic.

use passo_physics::{Integrator, Stage};
use passo_scene::{Scene, scene_from_world};
use passo_tests::assert_finite;
use proptest::prelude::*;
use std::path::PathBuf;

fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes")
}

fn load(name: &str) -> Scene {
    Scene::load(&scenes_dir().join(format!("{name}.ron"))).unwrap()
}

fn scene_texts() -> Vec<(String, String)> {
    let mut texts: Vec<_> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    texts.sort();
    texts
}

#[test]
fn every_shipped_scene_loads_and_runs() {
    let texts = scene_texts();
    let names: Vec<_> = texts
        .iter()
        .map(|(p, _)| p.rsplit('/').next().unwrap().to_owned())
        .collect();
    for needed in [
        "projectile",
        "drag_fall",
        "friction_slide",
        "spring",
        "rain",
        "pyramid",
        "stack",
        "playground",
        "tunnelling",
        "confined",
    ] {
        assert!(
            names.contains(&format!("{needed}.ron")),
            "missing {needed}.ron"
        );
    }
    for (path, text) in texts {
        let scene = Scene::parse(&text, &path).unwrap_or_else(|e| panic!("{e}"));
        let mut built = scene.build().unwrap();
        let dt = (1.0 / scene.file.rate_hz) as f32;
        for _ in 0..30 {
            built.world.step(dt);
        }
        assert_finite(&built.world);
        assert_eq!(built.bodies.len(), built.world.len(), "{path}");
    }
}

#[test]
fn a_world_runs_only_the_stages_its_scene_declares() {
    use Stage::*;
    let semi = Integrate(Integrator::SemiImplicitEuler);
    let cases = [
        ("spring", vec![Spring, semi, SpeedLimits]),
        ("friction_slide", vec![SurfaceFriction, semi, SpeedLimits]),
        (
            "drag_race",
            vec![Gravity, QuadraticDrag, semi, Contacts, SpeedLimits],
        ),
        ("projectile", vec![Gravity, semi, Contacts, SpeedLimits]),
        (
            "drag_fall",
            vec![Gravity, QuadraticDrag, semi, Contacts, SpeedLimits],
        ),
        (
            "orbit",
            vec![CentralGravity, Integrate(Integrator::Rk4), SpeedLimits],
        ),
        ("tunnelling", vec![semi, Contacts, SpeedLimits]),
    ];
    for (name, want) in cases {
        let mut built = load(name).build().unwrap();
        assert_eq!(built.world.active_stages(), want, "{name}");
        built.world.step(1.0 / 60.0);
        assert_eq!(
            built.world.has_contact_state(),
            want.contains(&Contacts),
            "{name}: contact storage exists only where contacts run"
        );
    }
}

#[test]
fn a_running_world_saved_as_a_scene_loads_back_to_the_same_state() {
    for name in ["rain", "playground", "drag_fall", "orbit"] {
        let scene = load(name);
        let mut built = scene.build().unwrap();
        for _ in 0..45 {
            built.world.step(1.0 / 60.0);
        }
        let saved = scene_from_world(&built.world, &scene.file, &built.bodies);
        let text = Scene {
            file: saved,
            source: "saved".into(),
        }
        .to_ron();
        let reloaded = Scene::parse(&text, "saved.ron").unwrap().build().unwrap();
        assert_eq!(
            reloaded.world.state_hash(),
            built.world.state_hash(),
            "{name}"
        );
        assert_eq!(reloaded.world.settings(), built.world.settings(), "{name}");
        for (a, b) in built.world.bodies().zip(reloaded.world.bodies()) {
            assert_eq!(
                (a.position, a.velocity, a.mass),
                (b.position, b.velocity, b.mass)
            );
            assert_eq!(
                (a.shape, a.friction, a.restitution),
                (b.shape, b.friction, b.restitution)
            );
        }
        assert_eq!(reloaded.bodies.len(), built.bodies.len());
        for (a, b) in built.bodies.iter().zip(&reloaded.bodies) {
            assert_eq!((&a.name, a.colour), (&b.name, b.colour));
        }
    }
}

/// Mutations of real scene text: a byte replaced, removed or inserted.
fn mutated() -> impl Strategy<Value = String> {
    let texts: Vec<String> = scene_texts().into_iter().map(|(_, t)| t).collect();
    let alphabet =
        b"(),:[]\"#.-+0123456789eEinfNaSomeBxCircleDynamicStatic \n_abcdfghjklmnpqrstuvwxyz";
    (
        0..texts.len(),
        prop::collection::vec(
            (
                any::<prop::sample::Index>(),
                0u8..3,
                any::<prop::sample::Index>(),
            ),
            1..6,
        ),
    )
        .prop_map(move |(which, edits)| {
            let mut bytes = texts[which].clone().into_bytes();
            for (at, kind, pick) in edits {
                let c = alphabet[pick.index(alphabet.len())];
                if bytes.is_empty() {
                    bytes.push(c);
                    continue;
                }
                let i = at.index(bytes.len());
                match kind {
                    0 => bytes[i] = c,
                    1 => {
                        bytes.remove(i);
                    }
                    _ => bytes.insert(i, c),
                }
            }
            String::from_utf8_lossy(&bytes).into_owned()
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scene_text_gives_a_scene_or_an_error_never_a_panic(text in mutated()) {
        if let Ok(scene) = Scene::parse(&text, "fuzz.ron") {
            // A scene that parses and validates must also build and step.
            let mut built = scene.build().expect("validated scenes build");
            if built.world.len() <= 3000 {
                built.world.step((1.0 / scene.file.rate_hz) as f32);
                assert_finite(&built.world);
            }
        }
    }

    #[test]
    fn random_text_gives_an_error_never_a_panic(text in "\\PC{0,200}") {
        let _ = Scene::parse(&text, "fuzz.ron");
    }

    #[test]
    fn random_ron_shaped_text_gives_an_error_never_a_panic(
        text in "\\(name: \"[a-z]{0,4}\", (bodies|generators|forces|collisions|camera|rate_hz): [\\[\\]()0-9.,: a-zA-Z\"#-]{0,60}\\)"
    ) {
        if let Ok(scene) = Scene::parse(&text, "fuzz.ron") {
            let _ = scene.build().expect("validated scenes build");
        }
    }
}
