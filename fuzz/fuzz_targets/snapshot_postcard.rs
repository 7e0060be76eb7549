//! Snapshots in postcard (the binary form `passo snapshot` writes: the
//! world and the loop): decoded, checked, restored and stepped.
#![no_main]

use libfuzzer_sys::fuzz_target;
use passo_loop::FixedTimestep;
use passo_physics::{World, WorldSnapshot};

fuzz_target!(|data: &[u8]| {
    let Ok(((world, timestep), _rest)) =
        postcard::take_from_bytes::<(WorldSnapshot, FixedTimestep)>(data)
    else {
        return;
    };
    let _ = timestep.validate();
    if let Ok(mut world) = World::from_snapshot(world) {
        world.step(1.0 / 60.0);
    }
});
