//! Finding scenes: the ones built into the binary, files in
//! `assets/scenes/`, or any path.

use anyhow::{Context, Result, bail};
use passo_scene::Scene;
use std::path::{Path, PathBuf};

/// The scenes in `assets/scenes/`, compiled into the binary so it runs from
/// anywhere. A test checks that every file there is listed.
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "playground",
        include_str!("../../../assets/scenes/playground.ron"),
    ),
    ("rain", include_str!("../../../assets/scenes/rain.ron")),
    ("stack", include_str!("../../../assets/scenes/stack.ron")),
    (
        "pyramid",
        include_str!("../../../assets/scenes/pyramid.ron"),
    ),
    (
        "drag_race",
        include_str!("../../../assets/scenes/drag_race.ron"),
    ),
    (
        "tunnelling",
        include_str!("../../../assets/scenes/tunnelling.ron"),
    ),
    (
        "projectile",
        include_str!("../../../assets/scenes/projectile.ron"),
    ),
    (
        "drag_fall",
        include_str!("../../../assets/scenes/drag_fall.ron"),
    ),
    (
        "friction_slide",
        include_str!("../../../assets/scenes/friction_slide.ron"),
    ),
    ("spring", include_str!("../../../assets/scenes/spring.ron")),
    ("orbit", include_str!("../../../assets/scenes/orbit.ron")),
    (
        "confined",
        include_str!("../../../assets/scenes/confined.ron"),
    ),
];

/// The scenes directory next to the working directory, if there is one.
pub fn assets_dir() -> Option<PathBuf> {
    let dir = Path::new("assets/scenes");
    dir.is_dir().then(|| dir.to_path_buf())
}

/// Loads a scene from a path to a `.ron` file, or by name: a file
/// `assets/scenes/NAME.ron` under the working directory wins over the
/// built-in scene of that name, so edited scenes take effect without a
/// rebuild.
pub fn load(name_or_path: &str) -> Result<Scene> {
    let path = Path::new(name_or_path);
    if path.extension().is_some_and(|e| e == "ron") || path.components().count() > 1 {
        return Scene::load(path).with_context(|| format!("loading scene {}", path.display()));
    }
    if let Some(dir) = assets_dir() {
        let file = dir.join(format!("{name_or_path}.ron"));
        if file.is_file() {
            return Scene::load(&file).with_context(|| format!("loading scene {}", file.display()));
        }
    }
    match BUILTIN.iter().find(|(n, _)| *n == name_or_path) {
        Some((name, text)) => Ok(Scene::parse(text, &format!("{name}.ron (built in)"))?),
        None => bail!(
            "no scene named `{name_or_path}`: give a path to a .ron file or one of: {}",
            names().join(", ")
        ),
    }
}

/// Names of the built-in scenes, in menu order.
pub fn names() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_file_is_built_in_and_parses() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| {
                let p = e.unwrap().path();
                (p.extension()? == "ron")
                    .then(|| p.file_stem().unwrap().to_string_lossy().into_owned())
            })
            .collect();
        files.sort();
        let mut built_in: Vec<String> = names().iter().map(|s| s.to_string()).collect();
        built_in.sort();
        assert_eq!(files, built_in);
        for (name, text) in BUILTIN {
            Scene::parse(text, name).unwrap();
        }
    }

    #[test]
    fn unknown_names_list_the_choices() {
        let err = load("nope").unwrap_err().to_string();
        assert!(err.contains("no scene named `nope`"), "{err}");
        assert!(err.contains("playground, rain"), "{err}");
    }
}
