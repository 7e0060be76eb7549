// Instanced line segments (debug vectors, contact normals, arrow shafts
// and heads): each is a quad around the segment whose fragment shader
// evaluates the distance to the segment, for an anti-aliased line of a
// width in pixels at any zoom. Comes after common.wgsl (`Globals`,
// `linear_to_srgb`). Mirrors `LineInstance`
// (crates/passo-render/src/draw_list.rs) field for field;
// crates/passo-render/tests/shaders.rs compares the layouts.

struct Instance {
    @location(0) start: vec2<f32>,
    @location(1) end: vec2<f32>,
    // linear RGB, straight alpha
    @location(2) colour: vec4<f32>,
    // full width, pixels
    @location(3) width: f32,
};

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    // world position of the fragment
    @location(0) world: vec2<f32>,
    @location(1) @interpolate(flat) start: vec2<f32>,
    @location(2) @interpolate(flat) end: vec2<f32>,
    @location(3) @interpolate(flat) colour: vec4<f32>,
    @location(4) @interpolate(flat) half_width: f32,
};


@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, instance: Instance) -> VsOut {
    let seg = instance.end - instance.start;
    let len = length(seg);
    var dir = vec2<f32>(1.0, 0.0);
    if len > 0.0 {
        dir = seg / len;
    }
    let normal = vec2<f32>(-dir.y, dir.x);
    let half_width = 0.5 * instance.width * globals.pixel_size;
    let pad = half_width + (FRINGE_PX + 0.5) * globals.pixel_size;
    let c = QUAD[vertex];
    // x: -1 at the start, +1 at the end (both extended by the pad); y: across.
    let along = select(instance.start - dir * pad, instance.end + dir * pad, c.x > 0.0);
    let world = along + normal * (c.y * pad);
    var out: VsOut;
    out.clip = vec4<f32>((world - globals.centre) * globals.scale, 0.0, 1.0);
    out.world = world;
    out.start = instance.start;
    out.end = instance.end;
    out.colour = instance.colour;
    out.half_width = half_width;
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    // Distance to the segment (a capsule of radius half_width), metres.
    let seg = in.end - in.start;
    let len2 = dot(seg, seg);
    var t = 0.0;
    if len2 > 0.0 {
        t = clamp(dot(in.world - in.start, seg) / len2, 0.0, 1.0);
    }
    let d = length(in.world - (in.start + seg * t)) - in.half_width;
    let coverage = clamp(0.5 - d / globals.pixel_size, 0.0, 1.0);
    let alpha = in.colour.a * coverage;
    if alpha <= 0.0 {
        discard;
    }
    if globals.encode_srgb == 1u {
        return vec4<f32>(linear_to_srgb(in.colour.rgb), alpha);
    }
    return vec4<f32>(in.colour.rgb, alpha);
}
