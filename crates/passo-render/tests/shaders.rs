//! Every shader parses and validates, and every struct the renderer shares
//! with a shader has the same layout on both sides (naga; no GPU needed):
//! `Globals` in Rust and in each WGSL file, and each instance struct
//! against its shader's vertex inputs and the vertex buffer layout the
//! renderer builds.

use naga::{AddressSpace, Binding, ResourceBinding, ScalarKind, TypeInner};
use passo_render::wgpu::{VertexBufferLayout, VertexFormat, VertexStepMode};
use passo_render::{
    Globals, LINES_WGSL, LineInstance, SHAPES_WGSL, SPRITES_WGSL, ShapeInstance, SpriteInstance,
};
use std::mem::{offset_of, size_of};

/// The Rust struct's listed fields, checked to cover the whole struct with
/// no gap (so a field left out of the list fails the test).
macro_rules! rust_struct {
    ($t:ident { $($field:ident),* $(,)? }) => {{
        let fields: Vec<(Field, usize)> = vec![$(
            field_of(
                stringify!($field),
                offset_of!($t, $field),
                |x: &$t| &x.$field,
            )
        ),*];
        let mut end = 0;
        for ((name, offset, _, _), size) in &fields {
            assert_eq!(
                *offset as usize, end,
                "{}::{name} does not follow the field before it: list every field",
                stringify!($t)
            );
            end += size;
        }
        assert_eq!(end, size_of::<$t>(), "{}: list every field", stringify!($t));
        RustStruct {
            fields: fields.into_iter().map(|(f, _)| f).collect(),
            size: size_of::<$t>(),
        }
    }};
}

#[test]
fn every_shader_in_the_shaders_directory_validates() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let common = std::fs::read_to_string(dir.join("common.wgsl")).unwrap();
    let mut checked = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.extension().is_none_or(|e| e != "wgsl") || name == "common.wgsl" {
            continue;
        }
        // Each pipeline's source is the common part, then its own.
        let source = common.clone() + &std::fs::read_to_string(&path).unwrap();
        let module = parse(&path.display().to_string(), &source);
        for entry in ["vs_main", "fs_main"] {
            assert!(
                module.entry_points.iter().any(|e| e.name == entry),
                "{} lacks {entry}",
                path.display()
            );
        }
        checked.push(name);
    }
    checked.sort();
    assert_eq!(checked, ["lines.wgsl", "shapes.wgsl", "sprites.wgsl"]);
    // The sources built into the renderer are those files.
    for (file, built_in) in [
        ("shapes.wgsl", SHAPES_WGSL),
        ("lines.wgsl", LINES_WGSL),
        ("sprites.wgsl", SPRITES_WGSL),
    ] {
        let own = std::fs::read_to_string(dir.join(file)).unwrap();
        assert_eq!(built_in, common.clone() + &own, "{file}");
    }
}

#[test]
fn globals_match_in_rust_and_in_every_shader() {
    let rust = rust_struct!(Globals {
        centre,
        scale,
        pixel_size,
        encode_srgb,
        _pad
    });
    for (file, source) in [
        ("shapes.wgsl", SHAPES_WGSL),
        ("lines.wgsl", LINES_WGSL),
        ("sprites.wgsl", SPRITES_WGSL),
    ] {
        let module = parse(file, source);
        let (members, span) = uniform_struct(&module, 0, 0)
            .unwrap_or_else(|| panic!("{file} has no uniform struct at @group(0) @binding(0)"));
        assert_eq!(
            members, rust.fields,
            "{file}: `Globals` members (name, offset, type) differ from the Rust struct"
        );
        assert_eq!(
            span as usize, rust.size,
            "{file}: `Globals` is {span} bytes, the Rust struct {} bytes",
            rust.size
        );
    }
}

#[test]
fn shape_instances_match_the_shader_and_the_vertex_layout() {
    let rust = rust_struct!(ShapeInstance {
        centre,
        half_extents,
        fill,
        outline,
        kind,
        _pad
    });
    check_instances(
        "shapes.wgsl",
        SHAPES_WGSL,
        &rust,
        size_of::<ShapeInstance>(),
        &ShapeInstance::LAYOUT,
    );
}

#[test]
fn line_instances_match_the_shader_and_the_vertex_layout() {
    let rust = rust_struct!(LineInstance {
        start,
        end,
        colour,
        width,
        _pad
    });
    check_instances(
        "lines.wgsl",
        LINES_WGSL,
        &rust,
        size_of::<LineInstance>(),
        &LineInstance::LAYOUT,
    );
}

#[test]
fn sprite_instances_match_the_shader_and_the_vertex_layout() {
    let rust = rust_struct!(SpriteInstance {
        centre,
        half_extents,
        uv_min,
        uv_max
    });
    check_instances(
        "sprites.wgsl",
        SPRITES_WGSL,
        &rust,
        size_of::<SpriteInstance>(),
        &SpriteInstance::LAYOUT,
    );
}

/// A field as a shader sees it: name, byte offset, scalar kind, components.
type Field = (String, u32, ScalarKind, u32);

/// A Rust struct's fields in order and its size.
struct RustStruct {
    fields: Vec<Field>,
    size: usize,
}

/// A Rust field's type as WGSL sees it.
trait GpuType {
    const KIND: ScalarKind;
    const COMPONENTS: u32;
}

impl GpuType for f32 {
    const KIND: ScalarKind = ScalarKind::Float;
    const COMPONENTS: u32 = 1;
}

impl GpuType for u32 {
    const KIND: ScalarKind = ScalarKind::Uint;
    const COMPONENTS: u32 = 1;
}

impl<T: GpuType, const N: usize> GpuType for [T; N] {
    const KIND: ScalarKind = T::KIND;
    const COMPONENTS: u32 = N as u32 * T::COMPONENTS;
}

/// A field of type `F` (found through `get`) and its size.
fn field_of<T, F: GpuType>(name: &str, offset: usize, _get: fn(&T) -> &F) -> (Field, usize) {
    (
        (name.to_owned(), offset as u32, F::KIND, F::COMPONENTS),
        size_of::<F>(),
    )
}

fn parse(name: &str, source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    module
}

/// A scalar or vector type's kind and component count (32-bit only).
fn kind_of(module: &naga::Module, ty: naga::Handle<naga::Type>) -> (ScalarKind, u32) {
    let (scalar, components) = match module.types[ty].inner {
        TypeInner::Scalar(scalar) => (scalar, 1),
        TypeInner::Vector { size, scalar } => (scalar, size as u32),
        ref other => panic!("a shared struct holds a {other:?}: only scalars and vectors"),
    };
    assert_eq!(scalar.width, 4, "only 32-bit scalars are shared");
    (scalar.kind, components)
}

/// The members and size of the struct bound as a uniform at
/// `@group(group) @binding(binding)`.
fn uniform_struct(module: &naga::Module, group: u32, binding: u32) -> Option<(Vec<Field>, u32)> {
    let var = module.global_variables.iter().find_map(|(_, v)| {
        (v.space == AddressSpace::Uniform && v.binding == Some(ResourceBinding { group, binding }))
            .then_some(v)
    })?;
    let TypeInner::Struct { members, span } = &module.types[var.ty].inner else {
        return None;
    };
    let fields = members
        .iter()
        .map(|m| {
            let (kind, components) = kind_of(module, m.ty);
            (
                m.name.clone().unwrap_or_default(),
                m.offset,
                kind,
                components,
            )
        })
        .collect();
    Some((fields, *span))
}

/// `vs_main`'s inputs at a `@location`: name, location, kind, components.
fn vertex_inputs(module: &naga::Module) -> Vec<(String, u32, ScalarKind, u32)> {
    let vs = module
        .entry_points
        .iter()
        .find(|e| e.name == "vs_main")
        .expect("vs_main");
    let mut inputs = Vec::new();
    let mut add = |name: &Option<String>, ty, binding: &Option<Binding>| {
        if let Some(Binding::Location { location, .. }) = binding {
            let (kind, components) = kind_of(module, ty);
            inputs.push((
                name.clone().unwrap_or_default(),
                *location,
                kind,
                components,
            ));
        }
    };
    for arg in &vs.function.arguments {
        match &module.types[arg.ty].inner {
            TypeInner::Struct { members, .. } => {
                for m in members {
                    add(&m.name, m.ty, &m.binding);
                }
            }
            _ => add(&arg.name, arg.ty, &arg.binding),
        }
    }
    inputs
}

/// A vertex format's scalar kind and component count.
fn format_kind(format: VertexFormat) -> (ScalarKind, u32) {
    use VertexFormat as F;
    match format {
        F::Float32 => (ScalarKind::Float, 1),
        F::Float32x2 => (ScalarKind::Float, 2),
        F::Float32x3 => (ScalarKind::Float, 3),
        F::Float32x4 => (ScalarKind::Float, 4),
        F::Uint32 => (ScalarKind::Uint, 1),
        F::Uint32x2 => (ScalarKind::Uint, 2),
        F::Uint32x3 => (ScalarKind::Uint, 3),
        F::Uint32x4 => (ScalarKind::Uint, 4),
        F::Sint32 => (ScalarKind::Sint, 1),
        F::Sint32x2 => (ScalarKind::Sint, 2),
        F::Sint32x3 => (ScalarKind::Sint, 3),
        F::Sint32x4 => (ScalarKind::Sint, 4),
        other => panic!("vertex format {other:?} is not handled by this test"),
    }
}

/// Every `@location` input of the shader's `vs_main` is a field of the Rust
/// struct of the same name and type, read by an attribute of the renderer's
/// layout at that location, that field's offset and a format of that type;
/// every attribute feeds an input; every field but padding is read; the
/// layout steps once per instance over the whole struct.
fn check_instances(
    file: &str,
    source: &str,
    rust: &RustStruct,
    size: usize,
    layout: &VertexBufferLayout<'static>,
) {
    let module = parse(file, source);
    assert_eq!(layout.array_stride as usize, size, "{file}: stride");
    assert_eq!(layout.step_mode, VertexStepMode::Instance, "{file}");
    let inputs = vertex_inputs(&module);
    for (name, location, kind, components) in &inputs {
        let (_, offset, rust_kind, rust_components) = rust
            .fields
            .iter()
            .find(|(n, ..)| n == name)
            .unwrap_or_else(|| panic!("{file}: input `{name}` is not a field of the Rust struct"));
        assert_eq!(
            (kind, components),
            (rust_kind, rust_components),
            "{file}: `{name}` has another type in Rust"
        );
        let attribute = layout
            .attributes
            .iter()
            .find(|a| a.shader_location == *location)
            .unwrap_or_else(|| panic!("{file}: no attribute feeds @location({location}) `{name}`"));
        assert_eq!(
            attribute.offset, *offset as u64,
            "{file}: the attribute of `{name}` is not at the field's offset"
        );
        assert_eq!(
            format_kind(attribute.format),
            (*kind, *components),
            "{file}: the attribute of `{name}` has format {:?}",
            attribute.format
        );
    }
    for attribute in layout.attributes {
        assert!(
            inputs.iter().any(|i| i.1 == attribute.shader_location),
            "{file}: attribute at location {} feeds no input",
            attribute.shader_location
        );
    }
    for (name, ..) in &rust.fields {
        assert!(
            name.starts_with('_') || inputs.iter().any(|i| &i.0 == name),
            "{file}: Rust field `{name}` is not read by the shader"
        );
    }
}
