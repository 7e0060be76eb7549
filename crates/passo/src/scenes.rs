//! Finding scenes: the ones built into the binary, files in
//! `assets/scenes/`, or any path.

use anyhow::{Context, Result, bail};
use passo_scene::Scene;
use std::path::{Path, PathBuf};

/// What the demo plots while a scene runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Plot {
    /// Total energy of each world.
    #[default]
    Energy,
    /// Speed of each dynamic body, with its terminal speed
    /// `sqrt(2 m g / (rho Cd A))` as a line.
    TerminalSpeed,
}

/// A scene compiled into the binary.
#[derive(Clone, Copy, Debug)]
pub struct BuiltIn {
    /// The name the commands and the demo take.
    pub name: &'static str,
    /// The scene file's RON text.
    pub text: &'static str,
    /// What the demo plots. Default [`Plot::Energy`].
    pub plot: Plot,
}

impl BuiltIn {
    const fn new(name: &'static str, text: &'static str) -> Self {
        Self {
            name,
            text,
            plot: Plot::Energy,
        }
    }

    const fn plotting(self, plot: Plot) -> Self {
        Self { plot, ..self }
    }
}

/// The scenes in `assets/scenes/`, compiled into the binary so it runs from
/// anywhere, in menu order. A test checks that every file there is listed.
pub const BUILTIN: &[BuiltIn] = &[
    BuiltIn::new(
        "playground",
        include_str!("../../../assets/scenes/playground.ron"),
    ),
    BuiltIn::new("rain", include_str!("../../../assets/scenes/rain.ron")),
    BuiltIn::new("stack", include_str!("../../../assets/scenes/stack.ron")),
    BuiltIn::new(
        "pyramid",
        include_str!("../../../assets/scenes/pyramid.ron"),
    ),
    BuiltIn::new(
        "drag_race",
        include_str!("../../../assets/scenes/drag_race.ron"),
    )
    .plotting(Plot::TerminalSpeed),
    BuiltIn::new(
        "tunnelling",
        include_str!("../../../assets/scenes/tunnelling.ron"),
    ),
    BuiltIn::new(
        "projectile",
        include_str!("../../../assets/scenes/projectile.ron"),
    ),
    BuiltIn::new(
        "drag_fall",
        include_str!("../../../assets/scenes/drag_fall.ron"),
    ),
    BuiltIn::new(
        "friction_slide",
        include_str!("../../../assets/scenes/friction_slide.ron"),
    ),
    BuiltIn::new("spring", include_str!("../../../assets/scenes/spring.ron")),
    BuiltIn::new("orbit", include_str!("../../../assets/scenes/orbit.ron")),
    BuiltIn::new(
        "confined",
        include_str!("../../../assets/scenes/confined.ron"),
    ),
    BuiltIn::new(
        "platformer",
        include_str!("../../../assets/scenes/platformer.ron"),
    ),
    BuiltIn::new("joints", include_str!("../../../assets/scenes/joints.ron")),
    BuiltIn::new("water", include_str!("../../../assets/scenes/water.ron")),
];

/// The files the built-in scenes' levels read (`assets/levels/`), at the
/// paths the built-in scenes name them by: the web demo, which has no
/// disk, hands them to [`passo_scene::embed_files`]. A test checks that
/// every file there is listed.
pub const LEVEL_FILES: &[(&str, &[u8])] = &[
    (
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/levels/first.tmx"),
        include_bytes!("../../../assets/levels/first.tmx"),
    ),
    (
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/levels/first.tmj"),
        include_bytes!("../../../assets/levels/first.tmj"),
    ),
    (
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/levels/blocks.png"
        ),
        include_bytes!("../../../assets/levels/blocks.png"),
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
    if is_path(path) {
        return Scene::load(path).with_context(|| format!("loading scene {}", path.display()));
    }
    if let Some(dir) = assets_dir() {
        let file = dir.join(format!("{name_or_path}.ron"));
        if file.is_file() {
            return Scene::load(&file).with_context(|| format!("loading scene {}", file.display()));
        }
    }
    match BUILTIN.iter().find(|b| b.name == name_or_path) {
        // A built-in scene's level map is read from the source tree's
        // assets, where its file was.
        Some(b) => Ok(Scene::parse(b.text, &built_in_path(b.name))?),
        None if name_or_path == INTEGRATORS.0 => bail!(
            "`{}` is built in code for the demo, not a scene file: \
             run it with `passo demo --scene {}`",
            INTEGRATORS.0,
            INTEGRATORS.0
        ),
        None => bail!(
            "no scene named `{name_or_path}`: give a path to a .ron file or one of: {}",
            names().join(", ")
        ),
    }
}

/// Where the built-in scene `name` was when the binary was built: its
/// name in messages, and where a level map it names is looked for.
fn built_in_path(name: &str) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
    dir.join(format!("{name}.ron")).display().to_string()
}

/// Whether [`load`] reads its argument as a path rather than a name.
fn is_path(path: &Path) -> bool {
    path.extension().is_some_and(|e| e == "ron") || path.components().count() > 1
}

/// The demo's comparison of the integrators, built in code (one world
/// per integrator side by side): its name and what `passo scenes` says of
/// it. The headless commands take scene files only.
pub const INTEGRATORS: (&str, &str) = (
    "integrators",
    "One spring under each integrator side by side (the demo only: built in code, not a file)",
);

/// Names of the built-in scenes, in menu order.
pub fn names() -> Vec<&'static str> {
    BUILTIN.iter().map(|b| b.name).collect()
}

/// What the demo plots for a scene given as [`load`] takes it: the table's
/// choice for the built-in scene of that name (a path by its file name,
/// so `assets/scenes/drag_race.ron` plots as `drag_race`), else
/// [`Plot::Energy`].
pub fn plot(name_or_path: &str) -> Plot {
    let path = Path::new(name_or_path);
    let name = if is_path(path) {
        path.file_stem()
            .map_or(name_or_path.into(), |s| s.to_string_lossy())
    } else {
        name_or_path.into()
    };
    BUILTIN
        .iter()
        .find(|b| b.name == name)
        .map_or(Plot::Energy, |b| b.plot)
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
        for b in BUILTIN {
            Scene::parse(b.text, b.name).unwrap();
        }
    }

    #[test]
    fn every_level_file_is_embedded_with_its_bytes() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/levels");
        let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path().canonicalize().unwrap())
            .collect();
        files.sort();
        let mut embedded: Vec<std::path::PathBuf> = LEVEL_FILES
            .iter()
            .map(|(path, bytes)| {
                let path = Path::new(path).canonicalize().unwrap();
                assert_eq!(std::fs::read(&path).unwrap(), *bytes, "{}", path.display());
                path
            })
            .collect();
        embedded.sort();
        assert_eq!(files, embedded);
    }

    #[test]
    fn the_drag_race_plots_terminal_speeds_by_name_or_path() {
        assert_eq!(plot("drag_race"), Plot::TerminalSpeed);
        assert_eq!(plot("assets/scenes/drag_race.ron"), Plot::TerminalSpeed);
        assert_eq!(plot("rain"), Plot::Energy);
        assert_eq!(plot("elsewhere/custom.ron"), Plot::Energy);
    }

    #[test]
    fn unknown_names_list_the_choices() {
        let err = load("nope").unwrap_err().to_string();
        assert!(err.contains("no scene named `nope`"), "{err}");
        assert!(err.contains("playground, rain"), "{err}");
    }
}
