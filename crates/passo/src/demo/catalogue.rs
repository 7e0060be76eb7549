//! The demo's scene list: the showcase first, then every other built-in
//! scene and any extra file in `assets/scenes/`.

/// A scene the demo's list offers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Entry {
    /// A scene file, by name or path.
    File(String),
    /// The side-by-side integrator comparison (built in code).
    Integrators,
}

impl Entry {
    /// The entry for a `--scene` value.
    pub fn named(name: &str) -> Self {
        if name == crate::scenes::INTEGRATORS.0 {
            Self::Integrators
        } else {
            Self::File(name.to_owned())
        }
    }
}

/// The scene list, with the label each entry shows.
pub fn catalogue() -> Vec<(String, Entry)> {
    let showcase = [
        "playground",
        "platformer",
        "rain",
        "stack",
        "pyramid",
        "drag_race",
    ];
    let mut list: Vec<(String, Entry)> = showcase
        .iter()
        .map(|n| ((*n).to_owned(), Entry::File((*n).to_owned())))
        .collect();
    list.push((crate::scenes::INTEGRATORS.0.into(), Entry::Integrators));
    for name in crate::scenes::names() {
        if !showcase.contains(&name) {
            list.push((name.to_owned(), Entry::File(name.to_owned())));
        }
    }
    if let Some(dir) = crate::scenes::assets_dir()
        && let Ok(entries) = std::fs::read_dir(dir)
    {
        let mut extra: Vec<String> = entries
            .filter_map(|e| {
                let path = e.ok()?.path();
                let stem = path.file_stem()?.to_string_lossy().into_owned();
                (path.extension()? == "ron").then_some(stem)
            })
            .filter(|n| !list.iter().any(|(l, _)| l == n))
            .collect();
        extra.sort();
        list.extend(extra.into_iter().map(|n| (n.clone(), Entry::File(n))));
    }
    list
}
