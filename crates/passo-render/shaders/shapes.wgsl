// Instanced shapes: every circle, box and capsule is a quad whose fragment shader
// evaluates the shape's signed distance, giving an anti-aliased edge and an
// outline at any zoom. Comes after common.wgsl (`Globals`,
// `linear_to_srgb`). Mirrors `ShapeInstance`
// (crates/passo-render/src/draw_list.rs) field for field;
// crates/passo-render/tests/shaders.rs compares the layouts.

struct Instance {
    @location(0) centre: vec2<f32>,
    @location(1) half_extents: vec2<f32>,
    // linear RGB, straight alpha
    @location(2) fill: vec4<f32>,
    @location(3) outline: vec4<f32>,
    // 0 = circle (radius in half_extents.x), 1 = box, 2 = capsule (radius
    // the smaller half extent)
    @location(4) kind: u32,
};

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    // metres from the shape's centre
    @location(0) local: vec2<f32>,
    @location(1) @interpolate(flat) half_extents: vec2<f32>,
    @location(2) @interpolate(flat) fill: vec4<f32>,
    @location(3) @interpolate(flat) outline: vec4<f32>,
    @location(4) @interpolate(flat) kind: u32,
};

// Outline width, pixels.
const OUTLINE_PX: f32 = 1.5;

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, instance: Instance) -> VsOut {
    // Grow the quad by the fringe so the anti-aliased edge is not clipped.
    let grown = instance.half_extents + vec2<f32>(globals.pixel_size * (FRINGE_PX + 0.5));
    var local = QUAD[vertex] * grown;
    var clip = (instance.centre + local - globals.centre) * globals.scale;
    // A quad far larger than the view (10^8 times its height) rasterised
    // with pixels missing: one reaching past the view is cut to just
    // outside it (clip coordinates within +-2), and its local coordinates
    // follow. Quads inside that range are left exactly as they were.
    if (any(abs(clip) > vec2<f32>(2.0))) {
        clip = clamp(clip, vec2<f32>(-2.0), vec2<f32>(2.0));
        local = clip / globals.scale + globals.centre - instance.centre;
    }
    var out: VsOut;
    out.clip = vec4<f32>(clip, 0.0, 1.0);
    out.local = local;
    out.half_extents = instance.half_extents;
    out.fill = instance.fill;
    out.outline = instance.outline;
    out.kind = instance.kind;
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    // Signed distance to the edge, metres (negative inside).
    var d: f32;
    if in.kind == 0u {
        d = length(in.local) - in.half_extents.x;
    } else {
        // A box (radius 0), or a capsule: the box of its straight part
        // grown by its radius.
        var radius = 0.0;
        if in.kind == 2u {
            radius = min(in.half_extents.x, in.half_extents.y);
        }
        let q = abs(in.local) - (in.half_extents - vec2<f32>(radius));
        d = length(max(q, vec2<f32>(0.0))) + min(max(q.x, q.y), 0.0) - radius;
    }
    let px = d / globals.pixel_size;
    let coverage = clamp(0.5 - px, 0.0, 1.0);
    // 0 on the outline band, 1 inside it.
    let inner = clamp(-px - OUTLINE_PX + 0.5, 0.0, 1.0);
    let rgb = mix(in.outline.rgb, in.fill.rgb, inner);
    let alpha = mix(in.outline.a, in.fill.a, inner) * coverage;
    if alpha <= 0.0 {
        discard;
    }
    if globals.encode_srgb == 1u {
        return vec4<f32>(linear_to_srgb(rgb), alpha);
    }
    return vec4<f32>(rgb, alpha);
}
