//! Scenes rendered off-screen on the software adapter (Mesa lavapipe):
//! compared against reference pictures, and interpolation checked in pixels.
//!
//! Reference pictures live in `tests/reference/`. A difference beyond the
//! tolerance fails and writes the actual picture and a difference picture
//! (white where they differ) next to the test's output. A missing reference
//! fails too; to (re)create the references after an intended change, run
//! `PASSO_UPDATE_REFERENCES=1 cargo test -p passo-tests --test images`
//! and look at the pictures before committing them.

use passo::draw::{DrawOptions, LevelTiles, draw_world, draw_world_with_tiles};
use passo_physics::glam::Vec2;
use passo_physics::{BodyDef, ForceModels, Shape, World, WorldSettings};
use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer, RgbaImage};
use passo_scene::Scene;
use std::path::PathBuf;

/// Tolerance against a reference: the mean over pixels of the largest
/// channel difference, and its 99th percentile (0 to 255).
const MAX_MEAN: f64 = 1.0;
const MAX_P99: u8 = 16;

fn gpu() -> Gpu {
    Gpu::headless(AdapterChoice::Software).unwrap_or_else(|e| panic!("{e}"))
}

fn render_scene(gpu: &Gpu, name: &str, ticks: u32, vectors: bool) -> RgbaImage {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../assets/scenes/{name}.ron"));
    let scene = Scene::load(&path).unwrap();
    let mut built = scene.build().unwrap();
    let dt = passo_loop::FixedTimestep::from_hz(scene.file.rate_hz)
        .unwrap()
        .dt();
    for _ in 0..ticks {
        built.world.step(dt);
    }
    let target = OffscreenTarget::new(gpu, 320, 240);
    let camera = Camera2D::fit(built.camera.min, built.camera.max, target.size());
    let mut list = DrawList::default();
    let options = DrawOptions {
        velocity_vectors: vectors,
        force_vectors: vectors,
        contact_normals: vectors,
        ..Default::default()
    };
    let mut renderer = Renderer::new(gpu, target.format());
    let tiles = LevelTiles::load(&mut renderer, &built);
    draw_world_with_tiles(&mut list, &built.world, &built.bodies, &tiles, &options);
    renderer.render(target.view(), target.size(), &camera, &list);
    target.read(gpu).unwrap()
}

fn compare_with_reference(name: &str, actual: &RgbaImage) {
    let reference_path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("reference/{name}.png"));
    if std::env::var_os("PASSO_UPDATE_REFERENCES").is_some() {
        actual.save_png(&reference_path).unwrap();
        eprintln!("wrote {}", reference_path.display());
        return;
    }
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("images");
    std::fs::create_dir_all(&out_dir).unwrap();
    let actual_path = out_dir.join(format!("{name}.actual.png"));
    let reference = match RgbaImage::load_png(&reference_path) {
        Ok(image) => image,
        Err(e) => {
            actual.save_png(&actual_path).unwrap();
            panic!(
                "no reference picture for `{name}` ({e}). The actual picture is at {}. \
                 To create the references run \
                 `PASSO_UPDATE_REFERENCES=1 cargo test -p passo-tests --test images`.",
                actual_path.display()
            );
        }
    };
    let diff = actual
        .difference(&reference)
        .unwrap_or_else(|| panic!("{name}: size differs from the reference"));
    let mean = diff.iter().map(|&d| f64::from(d)).sum::<f64>() / diff.len() as f64;
    let mut sorted = diff.clone();
    sorted.sort_unstable();
    let p99 = sorted[(sorted.len() - 1) * 99 / 100];
    if mean > MAX_MEAN || p99 > MAX_P99 {
        actual.save_png(&actual_path).unwrap();
        let diff_path = out_dir.join(format!("{name}.diff.png"));
        RgbaImage {
            width: actual.width,
            height: actual.height,
            pixels: diff
                .iter()
                .flat_map(|&d| {
                    [
                        d.saturating_mul(8),
                        d.saturating_mul(8),
                        d.saturating_mul(8),
                        255,
                    ]
                })
                .collect(),
        }
        .save_png(&diff_path)
        .unwrap();
        panic!(
            "{name}: mean difference {mean:.3} (max {MAX_MEAN}), 99th percentile {p99} (max {MAX_P99}); \
             actual at {}, difference at {}",
            actual_path.display(),
            diff_path.display()
        );
    }
}

#[test]
fn scenes_match_their_reference_pictures() {
    let gpu = gpu();
    for (name, scene, ticks, vectors) in [
        ("pyramid_0", "pyramid", 0, false),
        ("rain_150", "rain", 150, false),
        ("playground_20_vectors", "playground", 20, true),
        ("projectile_45_vectors", "projectile", 45, true),
        ("platformer_0", "platformer", 0, false),
    ] {
        let image = render_scene(&gpu, scene, ticks, vectors);
        compare_with_reference(name, &image);
    }
}

/// The Tiled level's cells are drawn from its tileset image, texel for
/// pixel: its first 15 m seen in 480 pixels, a 0.5 m cell is 16 pixels, one
/// per texel of its 16-pixel tile, so every pixel of a cell is the
/// tile's texel (the background where the tile is transparent), and no
/// cell is a flat box.
#[test]
fn the_tiled_level_is_drawn_from_its_tileset_image_texel_for_pixel() {
    let gpu = gpu();
    let assets = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets");
    let built = Scene::load(&assets.join("scenes/platformer.ron"))
        .unwrap()
        .build()
        .unwrap();
    let tileset = RgbaImage::load_png(assets.join("levels/blocks.png")).unwrap();
    let target = OffscreenTarget::new(&gpu, 480, 240);
    let camera = Camera2D::fit(Vec2::ZERO, Vec2::new(15.0, 7.5), target.size());
    let mut renderer = Renderer::new(&gpu, target.format());
    let tiles = LevelTiles::load(&mut renderer, &built);
    assert_eq!(tiles.len(), built.art.tiles.len());
    assert!(!tiles.is_empty());
    let mut list = DrawList::default();
    draw_world_with_tiles(
        &mut list,
        &built.world,
        &built.bodies,
        &tiles,
        &DrawOptions::default(),
    );
    renderer.render(target.view(), target.size(), &camera, &list);
    let image = target.read(&gpu).unwrap();
    let mut checked = 0;
    for tile in &built.art.tiles {
        // The level goes on past the view (its slopes, from 15 m).
        if tile.centre.x > 15.0 {
            continue;
        }
        // The cell's top-left pixel, and its tile's top-left texel.
        let x0 = ((tile.centre.x - 0.25) * 32.0).round() as u32;
        let y0 = 240 - ((tile.centre.y + 0.25) * 32.0).round() as u32;
        let u0 = (tile.uv_min.x * 64.0).round() as u32;
        for j in 0..16 {
            for i in 0..16 {
                let texel = tileset.get(u0 + i, j).unwrap();
                let pixel = image.get(x0 + i, y0 + j).unwrap();
                if texel[3] == 0 {
                    continue; // seen through
                }
                let close = pixel.iter().zip(texel).all(|(a, b)| a.abs_diff(b) <= 1);
                assert!(
                    close,
                    "cell at {:?}, texel ({i}, {j}) of tile {u0}: pixel {pixel:?}, texel {texel:?}",
                    tile.centre
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 100 * 256, "{checked} pixels checked");
}

#[test]
fn interpolation_draws_the_previous_the_midpoint_and_the_current_position() {
    let gpu = gpu();
    let mut world = World::new(WorldSettings {
        forces: ForceModels::none(),
        interpolation: true,
        ..Default::default()
    })
    .unwrap();
    let id = world
        .add_body(BodyDef {
            position: Vec2::new(-2.0, 0.0),
            velocity: Vec2::new(4.0, 2.0),
            shape: Some(Shape::circle(0.5)),
            ..Default::default()
        })
        .unwrap();
    world.step(0.5); // from (-2, 0) to (0, 1)
    let target = OffscreenTarget::new(&gpu, 200, 200);
    let camera = Camera2D {
        centre: Vec2::ZERO,
        height: 10.0, // 20 px per metre
    };
    let mut renderer = Renderer::new(&gpu, target.format());
    let mut list = DrawList::default();
    for (alpha, want) in [
        (0.0, Vec2::new(-2.0, 0.0)),
        (0.5, Vec2::new(-1.0, 0.5)),
        (1.0, Vec2::new(0.0, 1.0)),
    ] {
        let options = DrawOptions {
            alpha,
            ..Default::default()
        };
        draw_world(&mut list, &world, &[], &options);
        renderer.render(target.view(), target.size(), &camera, &list);
        let image = target.read(&gpu).unwrap();
        // Centroid of the body's pixels (anything brighter than the background).
        let (mut sum, mut n) = (Vec2::ZERO, 0.0);
        for y in 0..200 {
            for x in 0..200 {
                let p = image.get(x, y).unwrap();
                if p[0] > 100 {
                    sum += Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    n += 1.0;
                }
            }
        }
        let centroid = sum / n;
        let expected = camera.world_to_pixel(want, target.size());
        assert!(
            (centroid - expected).length() < 0.1,
            "alpha {alpha}: body at {centroid}, expected {expected}"
        );
    }
    assert!(world.body(id).is_some());
}
