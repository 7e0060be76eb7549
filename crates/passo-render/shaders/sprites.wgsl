// Instanced sprites: each is a quad that shows a rectangle of a texture
// (a tile of a tileset image), sampled at the nearest texel so pixel art
// stays sharp. Comes after common.wgsl (`Globals`, `linear_to_srgb`).
// Mirrors `SpriteInstance` (crates/passo-render/src/draw_list.rs) field
// for field; crates/passo-render/tests/shaders.rs compares the layouts.

// An sRGB texture: sampling gives linear light.
@group(1) @binding(0) var image: texture_2d<f32>;
@group(1) @binding(1) var nearest: sampler;

struct Instance {
    @location(0) centre: vec2<f32>,
    @location(1) half_extents: vec2<f32>,
    // the texture rectangle, 0 to 1, v down the image
    @location(2) uv_min: vec2<f32>,
    @location(3) uv_max: vec2<f32>,
};

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, instance: Instance) -> VsOut {
    let corner = QUAD[vertex];
    let world = instance.centre + corner * instance.half_extents;
    // 0 to 1 across the quad; the image's rows run down, the world's y up.
    let t = corner * 0.5 + vec2<f32>(0.5);
    var out: VsOut;
    out.clip = vec4<f32>((world - globals.centre) * globals.scale, 0.0, 1.0);
    out.uv = vec2<f32>(
        mix(instance.uv_min.x, instance.uv_max.x, t.x),
        mix(instance.uv_max.y, instance.uv_min.y, t.y),
    );
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    let c = textureSample(image, nearest, in.uv);
    if c.a <= 0.0 {
        discard;
    }
    if globals.encode_srgb == 1u {
        return vec4<f32>(linear_to_srgb(c.rgb), c.a);
    }
    return c;
}
