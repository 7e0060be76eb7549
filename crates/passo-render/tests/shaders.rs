//! Every shader parses and validates (naga; no GPU needed).

#[test]
fn every_shader_in_the_shaders_directory_validates() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders");
    let mut checked = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "wgsl") {
            continue;
        }
        let source = std::fs::read_to_string(&path).unwrap();
        let module = naga::front::wgsl::parse_str(&source)
            .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.emit_to_string(&source)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::empty(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.emit_to_string(&source)));
        for entry in ["vs_main", "fs_main"] {
            assert!(
                module.entry_points.iter().any(|e| e.name == entry),
                "{} lacks {entry}",
                path.display()
            );
        }
        checked.push(path.file_name().unwrap().to_string_lossy().into_owned());
    }
    checked.sort();
    assert_eq!(checked, ["lines.wgsl", "shapes.wgsl"]);
    // The built-in copies are the files.
    assert_eq!(
        passo_render::SHAPES_WGSL,
        std::fs::read_to_string(dir.join("shapes.wgsl")).unwrap()
    );
    assert_eq!(
        passo_render::LINES_WGSL,
        std::fs::read_to_string(dir.join("lines.wgsl")).unwrap()
    );
}
