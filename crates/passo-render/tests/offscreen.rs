//! Off-screen rendering on the software adapter (Mesa lavapipe): pixels
//! land where the camera says.

use glam::Vec2;
use passo_render::{
    AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer, RgbaImage, wgpu,
};

const BACKGROUND: [u8; 4] = [20, 22, 28, 255];
const RED: [u8; 4] = [228, 108, 58, 255];
const BLUE: [u8; 4] = [58, 142, 228, 255];
const GREEN: [u8; 4] = [92, 184, 92, 255];

fn gpu() -> Gpu {
    Gpu::headless(AdapterChoice::Software).unwrap_or_else(|e| panic!("{e}"))
}

fn draw(gpu: &Gpu, target: &OffscreenTarget, camera: &Camera2D, list: &DrawList) -> RgbaImage {
    let mut renderer = Renderer::new(gpu, target.format());
    renderer.render(target.view(), target.size(), camera, list);
    target.read(gpu).unwrap()
}

fn at(image: &RgbaImage, p: Vec2) -> [u8; 4] {
    image.get(p.x as u32, p.y as u32).unwrap()
}

fn close(a: [u8; 4], b: [u8; 4], tolerance: u8) -> bool {
    a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= tolerance)
}

#[test]
fn bodies_appear_where_the_camera_projects_them() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 320, 240);
    let camera = Camera2D::fit(Vec2::new(-8.0, -6.0), Vec2::new(8.0, 6.0), target.size());
    let bodies = [
        (Vec2::new(-4.0, 2.0), RED, true),
        (Vec2::new(3.0, -1.5), BLUE, false),
        (Vec2::new(5.0, 4.0), GREEN, true),
    ];
    let mut list = DrawList::new(BACKGROUND);
    for (p, colour, round) in bodies {
        if round {
            list.circle(p, 0.8, colour);
        } else {
            list.rect(p, Vec2::new(1.0, 0.6), colour);
        }
    }
    let image = draw(&gpu, &target, &camera, &list);
    for (p, colour, _) in bodies {
        let px = camera.world_to_pixel(p, target.size());
        assert!(
            close(at(&image, px), colour, 1),
            "{p} at {px}: {:?}",
            at(&image, px)
        );
    }
    // Far from every body: the background.
    for p in [
        Vec2::new(0.0, 5.0),
        Vec2::new(-7.0, -5.0),
        Vec2::new(0.0, 0.0),
    ] {
        let px = camera.world_to_pixel(p, target.size());
        assert!(
            close(at(&image, px), BACKGROUND, 1),
            "{p}: {:?}",
            at(&image, px)
        );
    }
    // The circle's edge is where its radius says: 0.8 m = 16 px at 20 px/m,
    // with a 1.5 px outline inside it.
    let c = camera.world_to_pixel(Vec2::new(-4.0, 2.0), target.size());
    assert!(
        close(at(&image, c + Vec2::new(12.0, 0.0)), RED, 1),
        "inside the edge"
    );
    let rim = at(&image, c + Vec2::new(15.0, 0.0));
    // The outline is 0.35 of the fill in linear light: sRGB 142 for 228.
    assert!(rim[0].abs_diff(142) <= 4, "the outline is darker: {rim:?}");
    assert!(
        close(at(&image, c + Vec2::new(18.0, 0.0)), BACKGROUND, 1),
        "outside the edge"
    );
}

#[test]
fn a_moved_body_moves_its_pixels_by_the_projected_amount() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 200, 200);
    let camera = Camera2D {
        centre: Vec2::ZERO,
        height: 10.0, // 20 px per metre
    };
    let centroid = |p: Vec2| {
        let mut list = DrawList::new(BACKGROUND);
        list.rect(p, Vec2::splat(1.0), RED);
        let image = draw(&gpu, &target, &camera, &list);
        let (mut sum, mut n) = (Vec2::ZERO, 0.0);
        for y in 0..200 {
            for x in 0..200 {
                if close(image.get(x, y).unwrap(), RED, 1) {
                    sum += Vec2::new(x as f32, y as f32);
                    n += 1.0;
                }
            }
        }
        sum / n
    };
    let a = centroid(Vec2::new(-1.0, 0.5));
    let b = centroid(Vec2::new(1.5, -1.0));
    // 2.5 m right and 1.5 m down: 50 px right, 30 px down (y is flipped).
    assert!(
        (b - a - Vec2::new(50.0, 30.0)).length() < 0.01,
        "{a} -> {b}"
    );
}

#[test]
fn srgb_and_linear_targets_give_the_same_picture() {
    let gpu = gpu();
    let camera = Camera2D::fit(Vec2::splat(-2.0), Vec2::splat(2.0), (64, 64));
    let mut list = DrawList::new([90, 90, 90, 255]);
    list.circle(Vec2::ZERO, 1.0, [200, 120, 40, 255]);
    list.line(
        Vec2::new(-2.0, -1.5),
        Vec2::new(2.0, -1.5),
        3.0,
        [30, 200, 255, 255],
    );
    let srgb = OffscreenTarget::with_format(&gpu, 64, 64, wgpu::TextureFormat::Rgba8UnormSrgb);
    let linear = OffscreenTarget::with_format(&gpu, 64, 64, wgpu::TextureFormat::Rgba8Unorm);
    let a = draw(&gpu, &srgb, &camera, &list);
    let b = draw(&gpu, &linear, &camera, &list);
    // Solid areas agree to a unit of rounding; edges blend in different
    // spaces (linear light on sRGB targets), so they may differ more.
    for (p, want) in [
        (Vec2::ZERO, [200, 120, 40, 255]),
        (Vec2::new(1.8, 1.8), [90, 90, 90, 255]),
        (Vec2::new(0.0, -1.5), [30, 200, 255, 255]),
    ] {
        let px = camera.world_to_pixel(p, (64, 64));
        assert!(
            close(at(&a, px), want, 1),
            "sRGB target at {p}: {:?}",
            at(&a, px)
        );
        assert!(
            close(at(&b, px), want, 1),
            "linear target at {p}: {:?}",
            at(&b, px)
        );
    }
    let diff = a.difference(&b).unwrap();
    let mean = diff.iter().map(|&d| f64::from(d)).sum::<f64>() / diff.len() as f64;
    assert!(mean < 1.0, "mean difference {mean}");
}

#[test]
fn arrows_draw_their_shaft_and_head() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 200, 100);
    let camera = Camera2D {
        centre: Vec2::ZERO,
        height: 10.0,
    };
    let mut list = DrawList::new(BACKGROUND);
    list.arrow(Vec2::new(-4.0, 0.0), Vec2::new(4.0, 0.0), 3.0, GREEN);
    let image = draw(&gpu, &target, &camera, &list);
    let on = |p: Vec2| {
        close(
            at(&image, camera.world_to_pixel(p, target.size())),
            GREEN,
            2,
        )
    };
    assert!(on(Vec2::new(0.0, 0.0)) && on(Vec2::new(-3.5, 0.0)), "shaft");
    assert!(
        on(Vec2::new(3.75, 0.125)) && on(Vec2::new(3.75, -0.125)),
        "head strokes"
    );
    assert!(!on(Vec2::new(0.0, 1.0)), "nothing off the line");
}

#[test]
fn zero_sized_targets_and_empty_lists_are_fine() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 16, 16);
    let mut renderer = Renderer::new(&gpu, target.format());
    renderer.render(
        target.view(),
        (0, 0),
        &Camera2D::default(),
        &DrawList::new(RED),
    );
    let list = DrawList::new(BLUE);
    renderer.render(target.view(), target.size(), &Camera2D::default(), &list);
    let image = target.read(&gpu).unwrap();
    assert!(
        image
            .pixels
            .chunks_exact(4)
            .all(|p| close(p.try_into().unwrap(), BLUE, 1))
    );
}

#[test]
fn many_instances_grow_the_buffers() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 100, 100);
    let camera = Camera2D::fit(Vec2::ZERO, Vec2::splat(100.0), target.size());
    let mut renderer = Renderer::new(&gpu, target.format());
    let mut list = DrawList::new(BACKGROUND);
    for i in 0..5000 {
        list.circle(
            Vec2::new((i % 70) as f32 * 1.4 + 1.0, (i / 70) as f32 * 1.4 + 1.0),
            0.5,
            RED,
        );
    }
    renderer.render(target.view(), target.size(), &camera, &list);
    let image = target.read(&gpu).unwrap();
    // The last circle (row 71, column 29) was drawn (small: only its
    // outline colour shows).
    let p = camera.world_to_pixel(Vec2::new(29.0 * 1.4 + 1.0, 71.0 * 1.4 + 1.0), target.size());
    assert!(!close(at(&image, p), BACKGROUND, 10), "{:?}", at(&image, p));
}

#[test]
fn a_clip_keeps_the_shapes_inside_it_and_the_background_everywhere() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 320, 240);
    let camera = Camera2D::fit(Vec2::new(-8.0, -6.0), Vec2::new(8.0, 6.0), target.size());
    // A box over the whole target and a line across it, clipped to all but
    // a 100-pixel strip on the left (where a window's panel would be).
    let mut list = DrawList::new(BACKGROUND);
    list.rect(Vec2::ZERO, Vec2::new(20.0, 20.0), RED);
    list.line(Vec2::new(-20.0, 0.0), Vec2::new(20.0, 0.0), 9.0, GREEN);
    list.clip = Some([100, 0, 220, 240]);
    let image = draw(&gpu, &target, &camera, &list);
    for y in [5, 60, 200] {
        for x in [0, 50, 99] {
            assert_eq!(
                image.get(x, y),
                Some(BACKGROUND),
                "({x}, {y}) is left of the clip"
            );
        }
        for x in [100, 200, 319] {
            assert!(
                close(image.get(x, y).unwrap(), RED, 1),
                "({x}, {y}) is inside"
            );
        }
    }
    let mid = camera.world_to_pixel(Vec2::ZERO, target.size()).y as u32;
    assert_eq!(image.get(50, mid), Some(BACKGROUND), "the line is cut too");
    assert!(close(image.get(200, mid).unwrap(), GREEN, 1));

    // A clip reaching past the target is cut to it; one outside it, or of
    // no width, draws no shape, and the background is still cleared.
    for (clip, inside) in [
        ([300, 200, 1000, 1000], true),
        ([400, 0, 50, 50], false),
        ([10, 10, 0, 100], false),
    ] {
        list.clip = Some(clip);
        let image = draw(&gpu, &target, &camera, &list);
        let (corner, beside) = (image.get(319, 239).unwrap(), image.get(5, 5).unwrap());
        assert_eq!(close(corner, RED, 1), inside, "{clip:?}: {corner:?}");
        assert_eq!(beside, BACKGROUND, "{clip:?}");
    }
    // A size given larger than the target (against `render`'s contract)
    // with a clip: the scissor is cut to the target itself, where wgpu
    // panicked on a rectangle past it.
    list.clip = Some([300, 200, 100, 100]);
    let mut renderer = Renderer::new(&gpu, target.format());
    renderer.render(target.view(), (640, 480), &camera, &list);
    let image = target.read(&gpu).unwrap();
    assert_eq!(image.get(5, 5), Some(BACKGROUND));
    // Clearing the list draws on the whole target again.
    list.clear(BACKGROUND);
    assert_eq!(list.clip, None);
}

#[test]
fn shapes_far_larger_than_the_view_keep_every_pixel() {
    // A ground slab 100 km wide, its top at y = 0, in a view 1 mm high,
    // and a circle of radius 10^9 m centred in the default 20 m view.
    // Quads 10^8 times the view rasterised with pixels missing (half of
    // the slab's; the circle's centre pixel was background).
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 64, 48);
    let mut camera = Camera2D::default();
    for _ in 0..100 {
        camera.zoom_about(2.0, Vec2::ZERO);
    }
    assert_eq!(camera.height, 1e-3);
    let mut list = DrawList::new(BACKGROUND);
    list.rect(Vec2::new(0.0, -1.0), Vec2::new(5e4, 1.0), RED);
    let slab = draw(&gpu, &target, &camera, &list);
    // The top half shows the background, the bottom half the slab (the
    // rows next to y = 0 are its outline and edge).
    for x in [0, 20, 32, 63] {
        for y in [0, 10, 21] {
            assert_eq!(slab.get(x, y), Some(BACKGROUND), "({x}, {y})");
        }
        for y in [28, 40, 47] {
            assert!(close(slab.get(x, y).unwrap(), RED, 1), "({x}, {y})");
        }
    }
    list.clear(BACKGROUND);
    list.circle(Vec2::ZERO, 1e9, BLUE);
    let ball = draw(&gpu, &target, &Camera2D::default(), &list);
    let filled = (0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .filter(|&(x, y)| close(ball.get(x, y).unwrap(), BLUE, 1))
        .count();
    assert_eq!(filled, 64 * 48, "every pixel inside the circle");
}

#[test]
fn lines_far_longer_than_the_view_keep_their_place() {
    // A horizontal line 100 km long through a view 1 mm high, and a
    // diagonal from (-10^9, -10^9) m to (10^9, 10^9) m through the default
    // 20 m view: each must cross the whole view where it lies.
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 64, 48);
    let mut camera = Camera2D::default();
    for _ in 0..100 {
        camera.zoom_about(2.0, Vec2::ZERO);
    }
    let mut list = DrawList::new(BACKGROUND);
    list.line(Vec2::new(-5e4, 0.0), Vec2::new(5e4, 0.0), 4.0, RED);
    let flat = draw(&gpu, &target, &camera, &list);
    for x in [0, 1, 20, 32, 62, 63] {
        // Rows 23 and 24 straddle y = 0; the line is 4 pixels wide.
        for y in [23, 24] {
            assert!(close(flat.get(x, y).unwrap(), RED, 1), "({x}, {y})");
        }
        for y in [0, 10, 30, 47] {
            assert_eq!(flat.get(x, y), Some(BACKGROUND), "({x}, {y})");
        }
    }
    list.clear(BACKGROUND);
    list.line(Vec2::splat(-1e9), Vec2::splat(1e9), 4.0, BLUE);
    let camera = Camera2D::default();
    let diagonal = draw(&gpu, &target, &camera, &list);
    // The pixel on the diagonal in each row is the line's; a pixel ten
    // columns to its side is background.
    for y in [2u32, 10, 23, 24, 36, 45] {
        let world = camera.pixel_to_world(Vec2::new(32.0, y as f32 + 0.5), (64, 48));
        let x = camera.world_to_pixel(Vec2::splat(world.y), (64, 48)).x as u32;
        assert!(close(diagonal.get(x, y).unwrap(), BLUE, 1), "({x}, {y})");
        assert_eq!(
            diagonal.get(x + 10, y),
            Some(BACKGROUND),
            "({}, {y})",
            x + 10
        );
        assert_eq!(diagonal.get(x.saturating_sub(10), y), Some(BACKGROUND));
    }
}

#[test]
fn textures_that_cannot_be_copied_are_an_error_not_a_panic() {
    let gpu = gpu();
    let texture = |usage, sample_count| {
        gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: 8,
                height: 8,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage,
            view_formats: &[],
        })
    };
    let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
    let no_copy = passo_render::read_texture(&gpu, &texture(attachment, 1)).unwrap_err();
    assert!(no_copy.to_string().contains("COPY_SRC"), "{no_copy}");
    let copyable = attachment | wgpu::TextureUsages::COPY_SRC;
    let samples = passo_render::read_texture(&gpu, &texture(attachment, 4)).unwrap_err();
    assert!(samples.to_string().contains("multisampled"), "{samples}");
    assert!(passo_render::read_texture(&gpu, &texture(copyable, 1)).is_ok());
}

#[test]
fn a_camera_that_shows_nothing_and_an_oversized_target_are_safe() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 64, 48);
    let mut list = DrawList::new(BACKGROUND);
    list.rect(Vec2::ZERO, Vec2::new(100.0, 100.0), RED);
    // A NaN centre, a zero or NaN height: the background alone.
    for camera in [
        Camera2D {
            centre: Vec2::new(f32::NAN, 0.0),
            height: 10.0,
        },
        Camera2D {
            centre: Vec2::ZERO,
            height: 0.0,
        },
        Camera2D {
            centre: Vec2::ZERO,
            height: f32::NAN,
        },
    ] {
        assert!(!camera.is_usable());
        let image = draw(&gpu, &target, &camera, &list);
        assert_eq!(image.get(32, 24), Some(BACKGROUND), "{camera:?}");
    }
    // The same list through a usable camera covers the target.
    let image = draw(&gpu, &target, &Camera2D::default(), &list);
    assert!(close(image.get(32, 24).unwrap(), RED, 1));
    // A zoom about a NaN point zooms about the centre.
    let mut camera = Camera2D::default();
    camera.zoom_about(2.0, Vec2::new(f32::NAN, 1.0));
    assert_eq!((camera.centre, camera.height), (Vec2::ZERO, 10.0));
    // A side past the device's largest texture is lowered to it (wgpu
    // would otherwise refuse the texture and panic).
    let max = gpu.device.limits().max_texture_dimension_2d;
    let wide = OffscreenTarget::new(&gpu, u32::MAX, 2);
    assert_eq!(wide.size(), (max, 2));
    let image = draw(&gpu, &wide, &Camera2D::default(), &list);
    assert_eq!((image.width, image.height), (max, 2));
}

#[test]
fn a_target_larger_than_the_largest_buffer_is_read_in_bands() {
    // `OffscreenTarget::new` takes sides up to the largest texture (16 384
    // on lavapipe), but one read-back buffer of 16 384 × 4 200 pixels
    // (275 MB) is past the largest buffer (256 MiB there): `read` panicked
    // in wgpu. It now reads bands of rows, each in its own buffer.
    let gpu = gpu();
    let limits = gpu.device.limits();
    let width = limits.max_texture_dimension_2d;
    let row = u64::from(width) * 4;
    let height = u32::try_from(limits.max_buffer_size / row + 104)
        .unwrap_or(u32::MAX)
        .min(limits.max_texture_dimension_2d);
    let target = OffscreenTarget::new(&gpu, width, height);
    assert_eq!(target.size(), (width, height));
    let needs_bands = row * u64::from(height) > limits.max_buffer_size;
    // One pixel a metre: a red band along the top, one along the bottom.
    let (w, h) = (width as f32, height as f32);
    let camera = Camera2D::fit(Vec2::ZERO, Vec2::new(w, h), (width, height));
    let mut list = DrawList::new(BACKGROUND);
    // (Past the target's sides and bottom: no anti-aliased edge there.)
    list.rect(Vec2::new(0.5 * w, h - 25.0), Vec2::new(w, 25.0), RED);
    list.rect(Vec2::new(0.5 * w, 50.0), Vec2::new(w, 100.0), RED);
    let image = draw(&gpu, &target, &camera, &list);
    assert_eq!((image.width, image.height), (width, height));
    assert_eq!(image.pixels.len(), (row * u64::from(height)) as usize);
    for (y, colour) in [
        (10, RED),
        (40, RED),
        (60, BACKGROUND),
        (height / 2, BACKGROUND),
        (height - 170, BACKGROUND),
        (height - 130, RED),
        (height - 1, RED),
    ] {
        for x in [0, width / 2, width - 1] {
            let p = image.get(x, y).unwrap();
            assert!(
                close(p, colour, 1),
                "({x}, {y}) of {width} x {height} (bands: {needs_bands}): {p:?}"
            );
        }
    }
}

/// A 4 × 2 texel image of two 2 × 2 tiles: the left tile red over blue,
/// the right green with a transparent bottom row.
fn tileset() -> RgbaImage {
    const CLEAR: [u8; 4] = [0, 0, 0, 0];
    let rows = [[RED, RED, GREEN, GREEN], [BLUE, BLUE, CLEAR, CLEAR]];
    RgbaImage {
        width: 4,
        height: 2,
        pixels: rows.iter().flatten().flatten().copied().collect(),
    }
}

#[test]
fn sprites_show_their_part_of_the_texture_upright_and_sharp() {
    let gpu = gpu();
    // Both target formats: the texture is sRGB, so each gives the bytes.
    for format in [
        wgpu::TextureFormat::Rgba8UnormSrgb,
        wgpu::TextureFormat::Rgba8Unorm,
    ] {
        let target = OffscreenTarget::with_format(&gpu, 200, 100, format);
        let mut renderer = Renderer::new(&gpu, format);
        let texture = renderer.add_texture(&tileset()).unwrap();
        // 4 m × 2 m: 50 pixels a metre, y up, (0, 0) at the centre.
        let camera = Camera2D::fit(Vec2::new(-2.0, -1.0), Vec2::new(2.0, 1.0), target.size());
        let mut list = DrawList::new(BACKGROUND);
        // The left tile on a 1 m square at x = -1, the right one at x = 1.
        let half = Vec2::splat(0.5);
        list.sprite(
            texture,
            Vec2::new(-1.0, 0.0),
            half,
            Vec2::ZERO,
            Vec2::new(0.5, 1.0),
        );
        list.sprite(
            texture,
            Vec2::new(1.0, 0.0),
            half,
            Vec2::new(0.5, 0.0),
            Vec2::ONE,
        );
        // A box drawn over the left sprite: shapes come after sprites.
        list.rect(Vec2::new(-1.25, 0.25), Vec2::splat(0.1), BLUE);
        renderer.render(target.view(), target.size(), &camera, &list);
        let image = target.read(&gpu).unwrap();
        // The left sprite spans pixels 25..75 across and 25..75 down: its
        // top half (the image's top row) red, its bottom half blue, with
        // no blur at the texels' border (rows 49 and 50).
        assert_eq!(image.get(60, 30), Some(RED), "{format:?}");
        assert_eq!(image.get(60, 49), Some(RED), "{format:?}");
        assert_eq!(image.get(60, 50), Some(BLUE), "{format:?}");
        assert_eq!(image.get(30, 70), Some(BLUE), "{format:?}");
        // The box over it.
        assert_eq!(image.get(37, 37), Some(BLUE), "{format:?}");
        // The right sprite: green on top, and its transparent bottom half
        // shows the background.
        assert_eq!(image.get(150, 30), Some(GREEN), "{format:?}");
        assert_eq!(image.get(150, 70), Some(BACKGROUND), "{format:?}");
        // Outside both.
        assert_eq!(image.get(100, 50), Some(BACKGROUND), "{format:?}");
        assert_eq!(image.get(60, 80), Some(BACKGROUND), "{format:?}");
    }
}

#[test]
fn bad_textures_are_errors_and_unknown_ones_draw_nothing() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 40, 40);
    let mut renderer = Renderer::new(&gpu, target.format());
    let empty = RgbaImage {
        width: 0,
        height: 4,
        pixels: Vec::new(),
    };
    assert!(renderer.add_texture(&empty).is_err());
    let short = RgbaImage {
        width: 2,
        height: 2,
        pixels: vec![255; 12],
    };
    let message = renderer.add_texture(&short).unwrap_err().to_string();
    assert!(message.contains("16 bytes"), "{message}");
    let huge = RgbaImage {
        width: 1 << 20,
        height: 1,
        pixels: Vec::new(),
    };
    assert!(renderer.add_texture(&huge).is_err());
    // A texture id from another renderer, with no texture here: skipped.
    let mut other = Renderer::new(&gpu, target.format());
    let foreign = other.add_texture(&tileset()).unwrap();
    let mut list = DrawList::new(BACKGROUND);
    list.sprite(
        foreign,
        Vec2::ZERO,
        Vec2::splat(10.0),
        Vec2::ZERO,
        Vec2::ONE,
    );
    let camera = Camera2D::fit(Vec2::splat(-1.0), Vec2::splat(1.0), target.size());
    renderer.render(target.view(), target.size(), &camera, &list);
    let image = target.read(&gpu).unwrap();
    assert_eq!(image.get(20, 20), Some(BACKGROUND));
}

#[test]
fn capsules_are_round_at_their_ends_and_straight_along_their_sides() {
    let gpu = gpu();
    let target = OffscreenTarget::new(&gpu, 320, 240);
    // 20 px a metre, the origin at the centre.
    let camera = Camera2D::fit(Vec2::new(-8.0, -6.0), Vec2::new(8.0, 6.0), target.size());
    let mut list = DrawList::new(BACKGROUND);
    // Upright: 1.6 m wide, 4 m tall (radius 0.8 m); lying: 4 m by 1 m.
    let (upright, lying) = (Vec2::new(-4.0, 0.0), Vec2::new(3.0, 2.0));
    list.capsule(upright, Vec2::new(0.8, 2.0), RED);
    list.capsule(lying, Vec2::new(2.0, 0.5), BLUE);
    let image = draw(&gpu, &target, &camera, &list);
    let pixel = |p: Vec2| at(&image, camera.world_to_pixel(p, target.size()));
    for (centre, half, colour) in [
        (upright, Vec2::new(0.8, 2.0), RED),
        (lying, Vec2::new(2.0, 0.5), BLUE),
    ] {
        let r = half.min_element();
        let core = half - Vec2::splat(r);
        // Inside: the centre, along the straight sides, near each end.
        for p in [Vec2::ZERO, core, -core, core * Vec2::new(1.0, -1.0) * 0.5] {
            assert!(
                close(pixel(centre + p), colour, 1),
                "{colour:?} at {p}: {:?}",
                pixel(centre + p)
            );
        }
        // The bounding box's corners lie outside the round ends (a box
        // would fill them).
        for corner in [half, -half, half * Vec2::new(1.0, -1.0)] {
            let p = centre + corner * 0.97;
            assert!(
                close(pixel(p), BACKGROUND, 1),
                "{colour:?} corner {corner}: {:?}",
                pixel(p)
            );
        }
        // Just inside the round end on the long axis, 0.2 m from the tip.
        let tip = if half.y > half.x {
            Vec2::new(0.0, half.y - 0.2)
        } else {
            Vec2::new(half.x - 0.2, 0.0)
        };
        assert!(
            close(pixel(centre + tip), colour, 1),
            "{colour:?} tip: {:?}",
            pixel(centre + tip)
        );
    }
}
