//! The options of `passo bench` and of each of its measurements.

/// Options of `passo bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchWhat,
}

/// What to measure.
#[derive(clap::Subcommand, Debug)]
pub enum BenchWhat {
    /// Off-screen frames per second for growing numbers of instances.
    Render(RenderBenchArgs),
    /// Collision scenes: rain of circles into a box, and pyramids.
    Physics(PhysicsBenchArgs),
    /// Integration alone (gravity + quadratic drag) against this machine's
    /// memory bandwidth.
    Integration(IntegrationBenchArgs),
    /// Step cost over growing sizes of a rain strip 20 rows deep (the
    /// same neighbourhood for every body), with the fitted exponent of cost
    /// against size.
    Scaling(ScalingBenchArgs),
    /// What a settled scene costs with sleeping on and off.
    Sleep(SleepBenchArgs),
    /// Ray casts per second against a settled rain, unfiltered and
    /// filtered, with and without a step between batches.
    Queries(QueriesBenchArgs),
    /// A rain with kinematic platforms sweeping through it.
    Platforms(PlatformsBenchArgs),
    /// A rain in a box drawn on a 1000 × 1000 tile map, against the same
    /// rain in a box of three static boxes.
    Tiles(TilesBenchArgs),
    /// A rain onto hilly ground of 1000 segments (a chain), against the
    /// same ground of 1000 boxes.
    Slopes(TilesBenchArgs),
    /// Scenes that make work grow faster than the bodies: circles spawned
    /// on one spot, and fast circles in a closed box.
    Extreme(ExtremeBenchArgs),
    /// A long run of a busy scene: no NaN, and no memory growth.
    Soak(SoakBenchArgs),
    /// Saving and restoring snapshots into reused buffers, against a step.
    Rollback(RollbackBenchArgs),
}

/// Options of `passo bench rollback`.
#[derive(clap::Args, Debug)]
pub struct RollbackBenchArgs {
    /// Rain sizes, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000", value_parser = crate::count_in(1, 1_000_000))]
    pub rain: Vec<usize>,
    /// Repetitions timed.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub repeats: u32,
}

/// Options of `passo bench soak`.
#[derive(clap::Args, Debug)]
pub struct SoakBenchArgs {
    /// Ticks to run at 60 Hz.
    #[arg(long, default_value_t = 1_000_000, value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    pub ticks: u64,
    /// Circles in the rain.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub bodies: u32,
}

/// Options of `passo bench extreme`.
#[derive(clap::Args, Debug)]
pub struct ExtremeBenchArgs {
    /// Circles spawned on one spot.
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub spawn: u32,
    /// Fast circles (100 to 500 m/s) in a closed 60 m × 30 m box.
    #[arg(long, default_value_t = 5_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub fast: u32,
    /// Circles in the rain stepped at 1 Hz.
    #[arg(long, default_value_t = 2_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub rain: u32,
    /// Ticks to run each 60 Hz scene.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
    /// Ticks to run the 1 Hz rain.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub slow_ticks: u32,
}

/// Options of `passo bench queries`.
#[derive(clap::Args, Debug)]
pub struct QueriesBenchArgs {
    /// Rain size (bodies).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bodies: u32,
    /// Rays per batch.
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    pub rays: u32,
}

/// Options of `passo bench tiles`.
#[derive(clap::Args, Debug)]
pub struct TilesBenchArgs {
    /// Rain size (bodies).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bodies: u32,
    /// Ticks to run at 60 Hz, each world in turn, this many rounds.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
    /// Rounds: the two worlds run alternately, so both meet the same
    /// machine.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub rounds: u32,
}

/// Options of `passo bench platforms`.
#[derive(clap::Args, Debug)]
pub struct PlatformsBenchArgs {
    /// Rain size (bodies).
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bodies: u32,
    /// Kinematic platforms.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(0..=10_000))]
    pub platforms: u32,
    /// Each platform's length, metres (0.3 m thick).
    #[arg(long, default_value_t = 4.0, value_parser = platform_length)]
    pub length: f32,
    /// Ticks to run at 60 Hz.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
    /// Sweep the platforms above where the rain lands instead of through
    /// the pile (what the platforms cost, without what they stir up).
    #[arg(long)]
    pub above: bool,
}

/// Options of `passo bench sleep`.
#[derive(clap::Args, Debug)]
pub struct SleepBenchArgs {
    /// Rain sizes (bodies), comma separated.
    #[arg(long, value_delimiter = ',', default_value = "10000", value_parser = crate::count_in(1, 1_000_000))]
    pub rain: Vec<usize>,
    /// Pyramid base widths, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "50", value_parser = crate::count_in(1, 2_000))]
    pub pyramid: Vec<usize>,
    /// Simulated seconds to let each scene settle first.
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u32).range(0..=3_600))]
    pub settle: u32,
    /// Ticks timed after settling, each way.
    #[arg(long, default_value_t = 120, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
}

/// Options of `passo bench integration`.
#[derive(clap::Args, Debug)]
pub struct IntegrationBenchArgs {
    /// Body counts, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1000,10000,100000,1000000",
        value_parser = crate::count_in(1, 100_000_000)
    )]
    pub sizes: Vec<usize>,
}

/// Options of `passo bench scaling`.
#[derive(clap::Args, Debug)]
pub struct ScalingBenchArgs {
    /// Rain sizes, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1000,2000,5000,10000,20000,50000,100000",
        value_parser = crate::count_in(1, 10_000_000)
    )]
    pub sizes: Vec<usize>,
    /// Ticks per size; the mean of the last two thirds is kept.
    #[arg(long, default_value_t = 180, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
}

/// Options of `passo bench physics`.
#[derive(clap::Args, Debug)]
pub struct PhysicsBenchArgs {
    /// Rain sizes (bodies), comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000,50000", value_parser = crate::count_in(1, 1_000_000))]
    pub rain: Vec<usize>,
    /// Pyramid base widths, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "20", value_parser = crate::count_in(1, 2_000))]
    pub pyramid: Vec<usize>,
    /// Ticks to run each scene at 60 Hz.
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub ticks: u32,
}

/// Options of `passo bench render`.
#[derive(clap::Args, Debug)]
pub struct RenderBenchArgs {
    /// Instance counts to measure, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000,100000", value_parser = crate::count_in(1, 10_000_000))]
    pub instances: Vec<usize>,
    /// Frames to time per count (after 3 warm-up frames).
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: u32,
    /// Picture size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = crate::render_cmd::parse_size)]
    pub size: (u32, u32),
    /// Use the software adapter (Mesa lavapipe).
    #[arg(long)]
    pub software: bool,
}

/// A platform length in metres for `passo bench platforms`: a finite
/// number from 0.1 to 1 000 (a platform is a body; the scene spans a few
/// dozen metres).
fn platform_length(text: &str) -> Result<f32, String> {
    let length: f32 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of metres"))?;
    if !(0.1..=1000.0).contains(&length) {
        return Err(format!("{text} is not in 0.1..=1000 (metres)"));
    }
    Ok(length)
}
