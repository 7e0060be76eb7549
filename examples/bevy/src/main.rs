//! The platformer level (`assets/levels/first.tmx`) in a Bevy window,
//! with the Passo plugin: the level loaded by a command, the player a
//! character mover, the lift driven along its path, sprites for the
//! boxes and Passo's gizmo drawing over everything.
//!
//! ```text
//! cd examples/bevy && cargo run --release
//! ```
//!
//! A / D or the arrow keys walk, Space jumps, F1 turns the gizmos off
//! and on. `--autopilot` walks right and jumps by itself; `--frames N`
//! runs N frames and exits, printing where the player is;
//! `--screenshot FILE` saves frame N as a PNG first; `--check` then reads
//! the PNG back and fails unless the player's sprite is drawn where the
//! physics and the camera put it.

use bevy::camera::ScalingMode;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use bevy::transform::TransformSystems;
use passo_bevy::prelude::*;
use passo_bevy::{PassoDebugDraw, PassoDebugDrawPlugin};

const WALK: f32 = 4.0;
const JUMP: f32 = 6.5;
const GRAVITY: f32 = 20.0;
const PLAYER: Vec2 = Vec2::new(0.4, 0.9);

/// What the command line asked for.
#[derive(Resource, Clone, Debug, Default)]
struct Args {
    autopilot: bool,
    frames: Option<u32>,
    screenshot: Option<String>,
    check: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args::default();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--autopilot" => args.autopilot = true,
            "--check" => args.check = true,
            "--frames" => {
                let n = it.next().and_then(|v| v.parse().ok());
                args.frames = Some(n.ok_or("--frames needs a number of frames")?);
            }
            "--screenshot" => {
                args.screenshot = Some(it.next().ok_or("--screenshot needs a file")?);
            }
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if args.screenshot.is_some() && args.frames.is_none() {
        return Err("--screenshot needs --frames N: the frame to save".into());
    }
    if args.check && args.screenshot.is_none() {
        return Err("--check needs --screenshot FILE: the picture to check".into());
    }
    Ok(args)
}

/// The player's own state: its vertical speed.
#[derive(Component, Default)]
struct Player {
    fall: f32,
    jumps: u32,
}

/// A jump key pressed since the last tick. Keys are read every frame, in
/// `Update`: a frame may run no tick, and a press read only in
/// `FixedUpdate` would then be lost.
#[derive(Resource, Default)]
struct JumpPressed(bool);

fn latch_jump(keys: Res<ButtonInput<KeyCode>>, mut jump: ResMut<JumpPressed>) {
    if keys.just_pressed(KeyCode::Space) {
        jump.0 = true;
    }
}

fn main() -> AppExit {
    let args = match parse_args() {
        Ok(args) => args,
        Err(error) => {
            eprintln!("{error}");
            return AppExit::error();
        }
    };
    App::new()
        .add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: "Passo in Bevy: platformer".into(),
                resolution: (1280, 720).into(),
                ..default()
            }),
            ..default()
        }))
        .add_plugins((PassoPlugin::default().with_rate(60.0), PassoDebugDrawPlugin))
        .insert_resource(args)
        .insert_resource(ClearColor(Color::srgb(0.08, 0.09, 0.12)))
        .add_systems(Startup, setup)
        .init_resource::<JumpPressed>()
        .add_systems(FixedUpdate, control.before(PassoSystems::Prepare))
        .add_systems(
            Update,
            (
                dress_level.run_if(resource_added::<PassoLevel>),
                latch_jump,
                toggle_gizmos,
            ),
        )
        .add_systems(
            PostUpdate,
            (
                // The camera follows where the player is drawn this frame.
                follow
                    .after(PassoSystems::Interpolate)
                    .before(TransformSystems::Propagate),
                // The screenshot's check reads where this frame draws.
                finish.after(TransformSystems::Propagate),
            ),
        )
        .run()
}

fn setup(mut commands: Commands) {
    commands.spawn((
        Camera2d,
        Projection::Orthographic(OrthographicProjection {
            scaling_mode: ScalingMode::FixedVertical {
                viewport_height: 9.0,
            },
            ..OrthographicProjection::default_2d()
        }),
        Transform::from_xyz(8.0, 4.0, 0.0),
    ));
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenes/platformer.ron"
    );
    commands.queue(LoadScene::file(scene));
}

/// Once the level is loaded: sprites for its tiles and boxes, and the
/// player at its spawn point.
fn dress_level(
    mut commands: Commands,
    level: Res<PassoLevel>,
    world: Res<PassoWorld>,
    bodies: Query<(Entity, &Collider, &SceneColour)>,
) {
    for &id in &level.cell_bodies {
        let Some(body) = world.body(id) else { continue };
        let Some(shape) = body.shape else { continue };
        if let passo_bevy::passo_physics::Shape::Box { half_extents } = shape {
            let size = Vec2::new(half_extents.x, half_extents.y) * 2.0;
            commands.spawn((
                Sprite::from_color(Color::srgb(0.32, 0.36, 0.44), size),
                Transform::from_xyz(body.position.x, body.position.y, -1.0),
            ));
        }
    }
    for (entity, collider, colour) in &bodies {
        if let passo_bevy::passo_physics::Shape::Box { .. } = collider.0 {
            let [r, g, b, a] = colour.0;
            commands.entity(entity).insert(Sprite::from_color(
                Color::srgba_u8(r, g, b, a),
                collider.half_extents() * 2.0,
            ));
        }
    }
    let start = level.spawn("player").unwrap_or(Vec2::new(1.0, 3.0));
    let mover = CharacterMover::default();
    commands.spawn((
        Player::default(),
        RigidBody::Kinematic,
        Collider::rectangle(PLAYER.x, PLAYER.y),
        Mover {
            settings: mover,
            velocity: Vec2::ZERO,
        },
        Sprite::from_color(Color::srgb(0.95, 0.45, 0.35), PLAYER),
        TransformInterpolation,
        Transform::from_xyz(start.x, start.y + PLAYER.y / 2.0 + mover.skin, 1.0),
    ));
}

/// Each tick: keys (or the autopilot) to the mover's velocity.
fn control(
    keys: Res<ButtonInput<KeyCode>>,
    mut jump_pressed: ResMut<JumpPressed>,
    args: Res<Args>,
    world: Res<PassoWorld>,
    mut players: Query<(&mut Player, &mut Mover, &MoverOutcome)>,
) {
    let dt = 1.0 / 60.0;
    let tick = world.stats().steps;
    for (mut player, mut mover, outcome) in &mut players {
        let (walk, jump) = if args.autopilot {
            (1.0, tick % 70 == 20)
        } else {
            let right = keys.any_pressed([KeyCode::KeyD, KeyCode::ArrowRight]);
            let left = keys.any_pressed([KeyCode::KeyA, KeyCode::ArrowLeft]);
            (f32::from(right) - f32::from(left), jump_pressed.0)
        };
        jump_pressed.0 = false;
        let on_ground = outcome.outcome.on_ground;
        player.fall = if on_ground && jump {
            player.jumps += 1;
            JUMP
        } else if on_ground {
            -1.0
        } else if outcome.outcome.on_ceiling && player.fall > 0.0 {
            0.0
        } else {
            player.fall - GRAVITY * dt
        };
        mover.velocity = Vec2::new(WALK * walk, player.fall);
    }
}

fn toggle_gizmos(keys: Res<ButtonInput<KeyCode>>, mut style: ResMut<PassoDebugDraw>) {
    if keys.just_pressed(KeyCode::F1) {
        style.enabled = !style.enabled;
    }
}

/// The camera follows the player inside the level's edges.
fn follow(
    level: Option<Res<PassoLevel>>,
    players: Query<&Transform, (With<Player>, Without<Camera2d>)>,
    mut camera: Query<&mut Transform, With<Camera2d>>,
) {
    let (Some(level), Ok(player), Ok(mut camera)) = (level, players.single(), camera.single_mut())
    else {
        return;
    };
    let half = Vec2::new(8.0, 4.5);
    let min = level.camera_min + half;
    let max = (level.camera_max - half).max(min);
    let at = player.translation.truncate().clamp(min, max);
    camera.translation.x = at.x;
    camera.translation.y = at.y;
}

/// Where the player's sprite was when the screenshot was asked for, in
/// window pixels (origin top-left): its centre.
#[derive(Resource, Clone, Copy, Debug)]
struct Expected(Vec2);

/// `--frames N`: saves frame N if asked, then exits once it is written.
#[allow(clippy::too_many_arguments)]
fn finish(
    mut commands: Commands,
    args: Res<Args>,
    mut frame: Local<u32>,
    world: Res<PassoWorld>,
    players: Query<(&Position, &Player, &MoverOutcome, &GlobalTransform)>,
    camera: Query<(&Camera, &GlobalTransform), With<Camera2d>>,
    expected: Option<Res<Expected>>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(frames) = args.frames else { return };
    *frame += 1;
    if *frame == frames
        && let Some(path) = &args.screenshot
    {
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(path.clone()));
        // Where this frame draws the player, through the camera.
        if let (Ok((camera, view)), Ok((_, _, _, transform))) = (camera.single(), players.single())
            && let Ok(at) = camera.world_to_viewport(view, transform.translation())
        {
            commands.insert_resource(Expected(at));
        }
    }
    let saved = args
        .screenshot
        .as_ref()
        .is_none_or(|path| std::path::Path::new(path).exists());
    // The screenshot is written a few frames after it is asked for.
    if *frame >= frames && (saved || *frame > frames + 300) {
        for (at, player, outcome, _) in &players {
            println!(
                "frames {} ticks {} player ({:.2}, {:.2}) on_ground {} jumps {}",
                *frame,
                world.stats().steps,
                at.0.x,
                at.0.y,
                outcome.outcome.on_ground,
                player.jumps
            );
        }
        let mut ok = saved;
        if args.check
            && let Some(path) = &args.screenshot
        {
            match check_picture(path, expected.as_deref().copied()) {
                Ok(report) => println!("{report}"),
                Err(error) => {
                    eprintln!("check failed: {error}");
                    ok = false;
                }
            }
        }
        exit.write(if ok {
            AppExit::Success
        } else {
            AppExit::error()
        });
    }
}

/// The player's sprite colour covers most of the box it should fill in
/// the screenshot (a margin of 6 px inside it, for a frame of motion),
/// and little of the same box moved a body width to the side.
fn check_picture(path: &str, expected: Option<Expected>) -> Result<String, String> {
    let Expected(centre) = expected.ok_or("the player was not on screen")?;
    let picture = image::open(path).map_err(|e| e.to_string())?.to_rgba8();
    // 720 px show 9 m: 80 px a metre.
    let scale = picture.height() as f32 / 9.0;
    let half = PLAYER * scale / 2.0 - Vec2::splat(6.0);
    let share = |centre: Vec2| {
        let (mut inside, mut hits) = (0u32, 0u32);
        for y in (centre.y - half.y) as i64..(centre.y + half.y) as i64 {
            for x in (centre.x - half.x) as i64..(centre.x + half.x) as i64 {
                let (Ok(x), Ok(y)) = (u32::try_from(x), u32::try_from(y)) else {
                    continue;
                };
                let Some(pixel) = picture.get_pixel_checked(x, y) else {
                    continue;
                };
                inside += 1;
                let [r, g, b, _] = pixel.0;
                // The sprite's sRGB colour, (242, 115, 89), within 24.
                if r.abs_diff(242) < 24 && g.abs_diff(115) < 24 && b.abs_diff(89) < 24 {
                    hits += 1;
                }
            }
        }
        f64::from(hits) / f64::from(inside.max(1))
    };
    let on = share(centre);
    let beside = share(centre + Vec2::new(PLAYER.x * scale * 2.0, 0.0));
    let report = format!(
        "player drawn at ({:.0}, {:.0}) px: {:.0} % of its box in its colour, {:.0} % beside it",
        centre.x,
        centre.y,
        on * 100.0,
        beside * 100.0
    );
    if on > 0.6 && beside < 0.2 {
        Ok(report)
    } else {
        Err(report)
    }
}
