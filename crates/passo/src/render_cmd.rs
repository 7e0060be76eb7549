//! `passo render`: simulate a scene headlessly and write a picture.

use crate::draw::{DrawOptions, LevelTiles, draw_world_with_tiles};
use anyhow::{Context, Result};
use passo_loop::FixedTimestep;
use passo_render::{AdapterChoice, Camera2D, DrawList, Gpu, OffscreenTarget, Renderer};
use std::path::PathBuf;

/// Options of `passo render`.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Scene name (see `passo scenes`) or path to a .ron file.
    pub scene: String,
    /// Fixed ticks to simulate before taking the picture.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=100_000_000))]
    pub ticks: u64,
    /// The PNG file to write (its name ends in `.png`).
    #[arg(long, value_parser = png_path)]
    pub out: PathBuf,
    /// Picture size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Draw velocity arrows, model forces and contact normals.
    #[arg(long)]
    pub vectors: bool,
    /// Render on the software adapter (Mesa lavapipe) even if a GPU exists.
    /// `PASSO_ADAPTER=software` does the same.
    #[arg(long)]
    pub software: bool,
}

/// Parses `WIDTHxHEIGHT` with both between 1 and 8192.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, like 1280x720, got `{text}`"))?;
    let dim = |s: &str| -> Result<u32, String> {
        let v: u32 = s
            .trim()
            .parse()
            .map_err(|_| format!("`{s}` is not a whole number of pixels"))?;
        if (1..=8192).contains(&v) {
            Ok(v)
        } else {
            Err(format!("sizes must be 1 to 8192 pixels, got {v}"))
        }
    };
    Ok((dim(w)?, dim(h)?))
}

/// A path for a picture (`passo render --out`, `passo demo
/// --screenshot`): it must end in `.png`, the one format written, so that
/// nothing is written as PNG under another format's name.
pub fn png_path(text: &str) -> Result<PathBuf, String> {
    let path = output_path(text)?;
    match path.extension() {
        Some(e) if e.eq_ignore_ascii_case("png") => Ok(path),
        _ => Err(format!("must name a .png file, got {text}")),
    }
}

/// A path a command writes when its work is done (a picture, a snapshot,
/// a replay): its directory must exist, checked before the work begins,
/// so that a whole run or session is not lost to a mistyped directory at
/// the end.
pub fn output_path(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(format!(
            "the directory {} of {text} does not exist",
            dir.display()
        )),
        _ => Ok(path),
    }
}

/// Runs `passo render`.
pub fn run(args: &RenderArgs) -> Result<()> {
    let scene = crate::scenes::load(&args.scene)?;
    let mut built = scene.build()?;
    let dt = FixedTimestep::from_hz(scene.file.rate_hz)?.dt();
    let mut progress = crate::progress::Progress::new("simulating", args.ticks);
    for tick in 1..=args.ticks {
        built.step(dt);
        progress.set(tick);
    }
    progress.finish();
    let choice = if args.software {
        AdapterChoice::Software
    } else {
        AdapterChoice::from_env()?
    };
    let gpu = Gpu::headless(choice)?;
    log::info!("rendering on {}", gpu.adapter_summary());
    let target = OffscreenTarget::new(&gpu, args.size.0, args.size.1);
    let mut renderer = Renderer::new(&gpu, target.format());
    let camera = Camera2D::fit(built.camera.min, built.camera.max, target.size());
    let mut list = DrawList::default();
    let options = DrawOptions {
        velocity_vectors: args.vectors,
        force_vectors: args.vectors,
        contact_normals: args.vectors,
        ..Default::default()
    };
    let tiles = LevelTiles::load(&mut renderer, &built);
    draw_world_with_tiles(&mut list, &built.world, &built.bodies, &tiles, &options);
    renderer.render(target.view(), target.size(), &camera, &list);
    let image = target.read(&gpu)?;
    image
        .save_png(&args.out)
        .with_context(|| format!("writing {}", args.out.display()))?;
    eprintln!(
        "{}: {} ticks, {}x{} picture written to {}",
        scene.file.name,
        args.ticks,
        args.size.0,
        args.size.1,
        args.out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_parse_or_explain() {
        assert_eq!(parse_size("1280x720"), Ok((1280, 720)));
        assert_eq!(parse_size("64X48"), Ok((64, 48)));
        assert!(parse_size("1280").unwrap_err().contains("WIDTHxHEIGHT"));
        assert!(parse_size("0x10").unwrap_err().contains("1 to 8192"));
        assert!(
            parse_size("axb")
                .unwrap_err()
                .contains("not a whole number")
        );
    }
}
