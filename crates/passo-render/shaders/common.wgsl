// What every pipeline's shader shares, put before each one's own source
// (`renderer.rs` joins them): the per-frame uniform and the sRGB encoding.
// `Globals` mirrors the Rust struct (crates/passo-render/src/renderer.rs)
// field for field; crates/passo-render/tests/shaders.rs compares them.

struct Globals {
    // world -> clip: clip = (world - centre) * scale
    centre: vec2<f32>,
    scale: vec2<f32>,
    // metres per pixel, for sizes measured in pixels
    pixel_size: f32,
    // 1 when the target stores bytes as they are (a *Unorm format) and the
    // shader must apply the sRGB transfer function itself; 0 for *Srgb
    // targets, which encode on write.
    encode_srgb: u32,
    _pad: vec2<f32>,
};

@group(0) @binding(0) var<uniform> globals: Globals;

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

// The two triangles of an instance's quad, corners from -1 to 1.
const QUAD = array<vec2<f32>, 6>(
    vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
    vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, 1.0), vec2<f32>(-1.0, 1.0),
);

// Anti-aliasing fringe, pixels.
const FRINGE_PX: f32 = 1.0;
