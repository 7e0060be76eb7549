//! Writes the fuzz targets' seed corpora from the shipped files: the
//! scenes, the levels, snapshots of the built scenes in both forms, and an
//! ASCII map. Run by `fuzz/run.sh` before the targets.

use passo::demo::{Command, Input, Replay, run_replay};
use passo_physics::World;
use std::fs;
use std::path::Path;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let assets = root.join("../assets");
    let corpus = root.join("corpus");
    let put = |target: &str, name: &str, bytes: &[u8]| {
        let dir = corpus.join(target);
        fs::create_dir_all(&dir).expect("a corpus folder");
        fs::write(dir.join(name), bytes).expect("a seed");
    };
    for entry in fs::read_dir(assets.join("scenes")).expect("the scenes") {
        let path = entry.expect("a scene").path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = fs::read_to_string(&path).expect("a scene's text");
        put("scene", &name, text.as_bytes());
        let Ok(scene) = passo_scene::Scene::load(&path) else {
            continue;
        };
        let Ok(built) = scene.build() else {
            continue;
        };
        let world: &World = &built.world;
        if world.len() > 500 {
            continue;
        }
        let snapshot = world.snapshot();
        let timestep = passo_loop::FixedTimestep::from_hz(60.0).expect("60 Hz");
        let bytes = postcard::to_stdvec(&(&snapshot, &timestep)).expect("postcard");
        put("snapshot_postcard", &name, &bytes);
        let text = ron::to_string(&snapshot).expect("ron");
        put("snapshot_ron", &name, text.as_bytes());
    }
    for (target, file) in [("tmx", "first.tmx"), ("tmj", "first.tmj")] {
        let bytes = fs::read(assets.join("levels").join(file)).expect("a level");
        put(target, file, &bytes);
    }
    let set = br#"<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" name="t" tilewidth="16" tileheight="16" tilecount="2" columns="2">
 <tile id="0" type="solid"><properties><property name="friction" type="float" value="0.1"/></properties></tile>
 <tile id="1" type="one_way"/>
</tileset>"#;
    put("tsx", "set.tsx", set);
    put("ascii", "level.txt", b"....^...\n..--....\n#~~#####\n");
    put("ascii", "slopes.txt", b"......./##\\...\n.....rR####Ff.\n##############\n");
    for (name, replay) in replays() {
        put("replay", name, replay.to_ron().as_bytes());
    }
}

/// Short replays of two scenes, each with every kind of command.
fn replays() -> Vec<(&'static str, Replay)> {
    let right = Input {
        right: true,
        jump: true,
        ..Default::default()
    };
    let mut seeds = Vec::new();
    for scene in ["playground", "platformer"] {
        let mut replay = Replay {
            scene: scene.into(),
            ticks: 90,
            inputs: vec![(0, right), (40, Input::default())],
            commands: vec![
                (
                    0,
                    Command::Integrator(passo_physics::Integrator::VelocityVerlet),
                ),
                (
                    10,
                    Command::Spawn {
                        at: [2.0, 6.0],
                        round: true,
                    },
                ),
                (
                    12,
                    Command::Fling {
                        index: 0,
                        generation: 0,
                        velocity: [3.0, 4.0],
                    },
                ),
                (20, Command::Rate(120.0)),
                (30, Command::Reset),
                (60, Command::RainCount(100)),
            ],
            final_hash: 0,
        };
        replay.final_hash = run_replay(&replay).expect("a seed replay plays");
        seeds.push((scene, replay));
    }
    seeds
}
