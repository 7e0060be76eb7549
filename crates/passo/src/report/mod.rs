//! `passo report`: speed against error for every integrator and force
//! model, measured against closed-form solutions.

pub mod cases;
mod plot;

use crate::progress::Progress;
use anyhow::{Context, Result};
use cases::{Case, METHODS, Method, cases, methods_for, theoretical_order, world};
use passo_loop::FixedTimestep;
use passo_physics::glam::Vec2;
use passo_physics::{
    BodyDef, ForceForm, ForceModels, Integrator, QuadraticDrag, Spring, SurfaceFriction, World,
    WorldSettings,
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The time steps of the report, seconds: 1/30 to 1/960.
pub const DTS: [f64; 6] = [
    1.0 / 30.0,
    1.0 / 60.0,
    1.0 / 120.0,
    1.0 / 240.0,
    1.0 / 480.0,
    1.0 / 960.0,
];

/// Errors below `NOISE_FACTOR * f32::EPSILON * sqrt(steps + 1)` times the
/// solution's size are at the limit of `f32` arithmetic (rounding
/// accumulates like a random walk over the steps) and say nothing about the
/// method's order.
pub const NOISE_FACTOR: f64 = 8.0;

/// Options of `passo report`.
#[derive(clap::Args, Debug, Clone)]
pub struct ReportArgs {
    /// Directory for accuracy.csv, accuracy.md and work_precision.png.
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Bodies stepped together when measuring cost.
    #[arg(long, default_value_t = 20_000, value_parser = crate::count_in(1, 10_000_000))]
    pub cost_bodies: usize,
    /// Steps per cost measurement (the best of three is kept).
    #[arg(long, default_value_t = 50, value_parser = crate::count_in(1, 1_000_000))]
    pub cost_steps: usize,
    /// Steps of the long spring run that shows energy drift.
    #[arg(long, default_value_t = 1_000_000, value_parser = crate::count_in(1, 100_000_000))]
    pub long_steps: usize,
}

impl Default for ReportArgs {
    fn default() -> Self {
        Self {
            out: PathBuf::from("report"),
            cost_bodies: 20_000,
            cost_steps: 50,
            long_steps: 1_000_000,
        }
    }
}

/// One CSV row: a case, a method and a step.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Case name.
    pub case: &'static str,
    /// Method name.
    pub method: &'static str,
    /// Time step, seconds.
    pub dt: f64,
    /// Distance from the exact position at the end time, metres.
    pub error: f64,
    /// Relative change of total energy over the run (conservative cases).
    pub energy_drift: Option<f64>,
    /// Measured cost, nanoseconds per body-step (per case and method; the
    /// step's length does not change it).
    pub ns_per_body_step: f64,
    /// Steps to reach the end time.
    pub steps: usize,
    /// Size of the exact solution, metres (for relative errors).
    pub scale: f64,
}

impl Row {
    /// The run blew up: a non-finite error, or one larger than the
    /// solution itself by a factor of ten.
    pub fn unstable(&self) -> bool {
        !self.error.is_finite() || self.error > 10.0 * self.scale
    }

    /// The error is at the `f32` rounding floor.
    pub fn at_noise_floor(&self) -> bool {
        self.error <= self.noise_floor()
    }

    /// The size of error rounding alone can produce in this run, metres.
    pub fn noise_floor(&self) -> f64 {
        NOISE_FACTOR * f64::from(f32::EPSILON) * ((self.steps + 1) as f64).sqrt() * self.scale
    }

    /// Total cost of the run per body, nanoseconds.
    pub fn ns_per_body(&self) -> f64 {
        self.ns_per_body_step * self.steps as f64
    }
}

/// Everything the report measured.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// case × method × dt.
    pub rows: Vec<Row>,
    /// Energy drift of a spring over `long_steps` steps at 60 Hz, per method.
    pub long_drift: Vec<(&'static str, f64)>,
    /// Steps of the long run.
    pub long_steps: usize,
    /// Stability at hard settings.
    pub stability: Vec<Stability>,
    /// Jump apex with a variable step per frame against the fixed loop.
    pub apex: Vec<Apex>,
}

/// One stability experiment.
#[derive(Clone, Debug, PartialEq)]
pub struct Stability {
    /// What was run.
    pub name: &'static str,
    /// Stable or plain form.
    pub form: ForceForm,
    /// Speeds after each step.
    pub speeds: Vec<f32>,
    /// Whether the speed went up at some step (or the velocity reversed).
    pub unstable: bool,
}

/// The apex of the same jump at one frame rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Apex {
    /// Render frames per second.
    pub fps: u32,
    /// Apex with one variable step of `1 / fps` per frame, metres.
    pub variable: f32,
    /// Apex with the 60 Hz fixed loop fed frames of `1 / fps`, metres.
    pub fixed: f32,
}

/// Runs one case with one method and step: the error, the energy drift.
pub fn accuracy(case: &Case, method: &Method, dt: f64) -> (f64, Option<f64>, usize) {
    let mut w = world(case, method, 1, 0.0);
    let steps = (case.end_time / dt).round() as usize;
    let e0 = w.total_energy();
    for _ in 0..steps {
        w.step(dt as f32);
    }
    let body = w.bodies().next().expect("one body");
    // Against the exact solution at the simulated time: steps of the `f32`
    // step the world takes (1/60 as f32 is 5.2e-8 longer, relative, which
    // at 1/480 s was most of RK4's reported spring error), which may
    // differ from the end time when it is not a whole number of steps.
    let [x, y] = (case.exact)(steps as f64 * f64::from(dt as f32));
    let error = (f64::from(body.position.x) - x).hypot(f64::from(body.position.y) - y);
    let drift = case
        .conservative
        .then(|| (w.total_energy() - e0) / e0.abs());
    (error, drift, steps)
}

/// Nanoseconds per body-step of a method on a case, over many bodies (the
/// best of three runs, to shed noise from other work on the machine).
pub fn cost(case: &Case, method: &Method, dt: f64, bodies: usize, steps: usize) -> f64 {
    let mut w = world(
        case,
        method,
        bodies,
        passo_physics::constants::DEFAULT_MIN_SPEED,
    );
    w.step(dt as f32);
    (0..3)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..steps {
                w.step(dt as f32);
            }
            start.elapsed().as_nanos() as f64 / (bodies * steps) as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// The observed order of a method on a case: the slope of log(error)
/// against log(dt) between the two finest steps whose errors are above the
/// rounding floor, stable, and still falling as dt halves (the most
/// asymptotic pair the data has). `None` without such a pair.
pub fn observed_order(rows: &[Row], case: &str, method: &str) -> Option<f64> {
    let mut runs: Vec<&Row> = rows
        .iter()
        .filter(|r| r.case == case && r.method == method)
        .collect();
    runs.sort_by(|a, b| b.dt.total_cmp(&a.dt));
    let usable = |r: &Row| !r.unstable() && !r.at_noise_floor() && r.error > 0.0;
    runs.windows(2)
        .rfind(|pair| usable(pair[0]) && usable(pair[1]) && pair[0].error / pair[1].error > 1.5)
        .map(|pair| (pair[0].error / pair[1].error).ln() / (pair[0].dt / pair[1].dt).ln())
}

/// Energy drift of a unit-mass spring (w = 6 rad/s) over `steps` steps at
/// 60 Hz (w dt = 0.1) for each integrator.
pub fn long_drift(steps: usize) -> Vec<(&'static str, f64)> {
    Integrator::ALL
        .iter()
        .map(|&integrator| {
            let mut w = World::new(WorldSettings {
                forces: ForceModels {
                    spring: Some(Spring {
                        anchor: Vec2::ZERO,
                        stiffness: 36.0,
                    }),
                    ..ForceModels::none()
                },
                integrator,
                min_speed: 0.0,
                max_speed: f32::INFINITY,
                contacts: None,
                ..Default::default()
            })
            .expect("valid settings");
            w.add_body(BodyDef::point_mass(Vec2::new(1.0, 0.0)))
                .expect("valid body");
            let e0 = w.total_energy();
            for _ in 0..steps {
                w.step(1.0 / 60.0);
            }
            // A velocity that overflowed f32 was reset by the step's guard:
            // the energy grew without bound, whatever is left now (explicit
            // Euler read +3e36 from what the resets left).
            let drift = if w.stats().non_finite_resets > 0 {
                f64::INFINITY
            } else {
                (w.total_energy() - e0) / e0
            };
            (integrator.name(), drift)
        })
        .collect()
}

/// The two hard settings, each in the stable and the plain form:
/// quadratic drag with `k |v| dt / m = 50`, and friction with
/// `mu g dt > |v|`.
pub fn stability() -> Vec<Stability> {
    let mut out = Vec::new();
    for form in [ForceForm::Stable, ForceForm::Explicit] {
        // k = rho Cd A / 2 = 1, m = 1, v = 50, dt = 1: k v dt / m = 50.
        let drag = ForceModels {
            quadratic_drag: Some(QuadraticDrag { density: 2.0 }),
            ..ForceModels::none()
        };
        let def = BodyDef {
            velocity: Vec2::new(50.0, 0.0),
            drag_area: 1.0,
            ..Default::default()
        };
        out.push(run_stability(
            "quadratic drag, k|v|dt/m = 50",
            drag,
            def,
            form,
            1.0,
            30,
        ));
        // mu g dt = 0.5 * 9.81 * 0.5 = 2.45 m/s > |v| = 1 m/s.
        let friction = ForceModels {
            surface_friction: Some(SurfaceFriction { gravity: 9.81 }),
            ..ForceModels::none()
        };
        let def = BodyDef {
            velocity: Vec2::new(1.0, 0.0),
            friction: 0.5,
            ..Default::default()
        };
        out.push(run_stability(
            "friction, mu g dt = 2.45 m/s > |v| = 1 m/s",
            friction,
            def,
            form,
            0.5,
            10,
        ));
    }
    out
}

fn run_stability(
    name: &'static str,
    forces: ForceModels,
    def: BodyDef,
    form: ForceForm,
    dt: f32,
    steps: usize,
) -> Stability {
    let mut w = World::new(WorldSettings {
        forces,
        force_form: form,
        max_speed: f32::INFINITY,
        contacts: None,
        ..Default::default()
    })
    .expect("valid settings");
    let id = w.add_body(def).expect("valid body");
    let mut speeds = Vec::new();
    let mut unstable = false;
    let mut last = def.velocity;
    for _ in 0..steps {
        w.step(dt);
        let v = w.body(id).expect("body").velocity;
        unstable |= v.length() > last.length() || v.dot(def.velocity) < 0.0 || !v.is_finite();
        speeds.push(v.length());
        last = v;
    }
    Stability {
        name,
        form,
        speeds,
        unstable,
    }
}

/// Advances a world by one rendered frame, calling the second argument
/// after every physics step it takes.
type FrameFn = Box<dyn FnMut(&mut World, &mut dyn FnMut(&World))>;

/// A 5 m/s jump under gravity with semi-implicit Euler: the apex with one
/// variable step per frame and with the 60 Hz fixed loop, at 30, 60, 144
/// and 240 frames per second.
pub fn apex_table() -> Vec<Apex> {
    let apex = |mut frame: FrameFn| {
        let mut w = World::new(WorldSettings {
            min_speed: 0.0,
            contacts: None,
            ..Default::default()
        })
        .expect("valid settings");
        let id = w
            .add_body(BodyDef::point_mass(Vec2::ZERO))
            .expect("valid body");
        w.apply_impulse(id, Vec2::new(0.0, 5.0));
        let (mut top, mut falling) = (0.0f32, false);
        while !falling {
            frame(&mut w, &mut |w: &World| {
                let b = w.body(id).expect("body");
                top = top.max(b.position.y);
                falling |= b.velocity.y < 0.0;
            });
        }
        top
    };
    [30u32, 60, 144, 240]
        .iter()
        .map(|&fps| {
            let frame_time = Duration::from_nanos(1_000_000_000 / u64::from(fps));
            let variable = apex(Box::new(move |w, tick| {
                w.step(frame_time.as_secs_f32());
                tick(w);
            }));
            let mut timestep = FixedTimestep::from_hz(60.0).expect("60 Hz");
            let fixed = apex(Box::new(move |w, tick| {
                let frame = timestep.advance(frame_time);
                for _ in 0..frame.ticks {
                    w.step(frame.dt);
                    tick(w);
                }
            }));
            Apex {
                fps,
                variable,
                fixed,
            }
        })
        .collect()
}

/// Measures everything (with a progress bar on a terminal).
pub fn measure(args: &ReportArgs) -> Report {
    let cases = cases();
    let total: usize = cases
        .iter()
        .map(|c| methods_for(c).len() * DTS.len())
        .sum::<usize>()
        + 3;
    let mut progress = Progress::new("measuring", total as u64);
    let mut done = 0;
    let mut rows = Vec::new();
    for case in &cases {
        let scale = case.scale();
        for method in methods_for(case) {
            // The cost of a step does not depend on its length: measure it
            // once per case and method, at 60 Hz.
            let ns = cost(case, &method, 1.0 / 60.0, args.cost_bodies, args.cost_steps);
            for &dt in &DTS {
                let (error, energy_drift, steps) = accuracy(case, &method, dt);
                rows.push(Row {
                    case: case.name,
                    method: method.name,
                    dt,
                    error,
                    energy_drift,
                    ns_per_body_step: ns,
                    steps,
                    scale,
                });
                done += 1;
                progress.set(done);
            }
        }
    }
    let long_drift = long_drift(args.long_steps);
    progress.set(done + 1);
    let stability = stability();
    progress.set(done + 2);
    let apex = apex_table();
    progress.set(done + 3);
    progress.finish();
    Report {
        rows,
        long_drift,
        long_steps: args.long_steps,
        stability,
        apex,
    }
}

/// Writes `accuracy.csv`, `accuracy.md` and `work_precision.png`.
pub fn write(report: &Report, dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut csv = String::from("case,method,dt,error,energy_drift,ns_per_body_step\n");
    for r in &report.rows {
        let drift = r.energy_drift.map_or(String::new(), |d| format!("{d:e}"));
        writeln!(
            csv,
            "{},{},{},{:e},{},{:.3}",
            r.case, r.method, r.dt, r.error, drift, r.ns_per_body_step
        )?;
    }
    for (method, drift) in &report.long_drift {
        writeln!(
            csv,
            "spring_{}_steps,{method},{},,{drift:e},",
            report.long_steps,
            1.0 / 60.0
        )?;
    }
    let csv_path = dir.join("accuracy.csv");
    std::fs::write(&csv_path, csv).with_context(|| format!("writing {}", csv_path.display()))?;
    let md_path = dir.join("accuracy.md");
    std::fs::write(&md_path, markdown(report))
        .with_context(|| format!("writing {}", md_path.display()))?;
    plot::work_precision(report, &dir.join("work_precision.png"))?;
    Ok(())
}

/// Runs `passo report`.
pub fn run(args: &ReportArgs) -> Result<()> {
    // Before the measuring, which takes minutes: a directory that cannot
    // be made is an error at once.
    let dir = &args.out;
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let report = measure(args);
    write(&report, &args.out)?;
    eprintln!(
        "wrote {}/accuracy.csv, accuracy.md and work_precision.png ({} rows)",
        args.out.display(),
        report.rows.len()
    );
    Ok(())
}

fn fmt_dt(dt: f64) -> String {
    format!("1/{:.0}", 1.0 / dt)
}

/// The Markdown report: a table per case, orders, the cheapest method for
/// an error target, instabilities, drift, stability and the apex table.
pub fn markdown(report: &Report) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# Passo accuracy report\n");
    let _ = writeln!(
        md,
        "Error is the distance from the closed-form position at the end time (metres); \
         cost is nanoseconds per body-step, measured over many bodies at once. \
         `*` marks errors at the f32 rounding floor ({NOISE_FACTOR} × f32 epsilon × sqrt(steps) \
         of the solution's size), \
         `unstable` runs that blew up. Regenerate with `cargo run --release -- report --out DIR`.\n"
    );
    for case in cases() {
        let rows: Vec<&Row> = report.rows.iter().filter(|r| r.case == case.name).collect();
        let _ = writeln!(md, "## {}: {}\n", case.name, case.title);
        let methods = methods_for(&case);
        let _ = write!(md, "| dt |");
        for m in &methods {
            let _ = write!(md, " {} |", m.name);
        }
        let _ = write!(md, "\n|---|");
        for _ in &methods {
            let _ = write!(md, "---:|");
        }
        let _ = writeln!(md);
        for &dt in &DTS {
            let _ = write!(md, "| {} |", fmt_dt(dt));
            for m in &methods {
                let cell = rows
                    .iter()
                    .find(|r| r.method == m.name && r.dt == dt)
                    .map_or("–".to_owned(), |r| {
                        if r.unstable() {
                            "unstable".to_owned()
                        } else {
                            format!(
                                "{:.2e}{}",
                                r.error,
                                if r.at_noise_floor() { "*" } else { "" }
                            )
                        }
                    });
                let _ = write!(md, " {cell} |");
            }
            let _ = writeln!(md);
        }
        let _ = write!(md, "| ns/body-step |");
        for m in &methods {
            let ns = rows
                .iter()
                .find(|r| r.method == m.name)
                .map_or(f64::NAN, |r| r.ns_per_body_step);
            let _ = write!(md, " {ns:.1} |");
        }
        let _ = writeln!(md);
        if case.smooth {
            let _ = write!(md, "| observed order |");
            for m in &methods {
                let cell = observed_order(&report.rows, case.name, m.name)
                    .map_or("–".to_owned(), |o| {
                        format!("{o:.2} (theory {:.0})", theoretical_order(m))
                    });
                let _ = write!(md, " {cell} |");
            }
            let _ = writeln!(md);
        }
        let _ = writeln!(md);
        let _ = writeln!(md, "{} {}\n", case.note, reading(&case, &rows));
    }
    let _ = writeln!(
        md,
        "## Energy drift of a spring over {} steps (w dt = 0.1)\n",
        report.long_steps
    );
    let _ = writeln!(md, "| method | relative energy change |\n|---|---:|");
    for (m, d) in &report.long_drift {
        let _ = writeln!(md, "| {m} | {d:+.3e} |");
    }
    let _ = writeln!(
        md,
        "\nSemi-implicit Euler and Verlet are symplectic: their energy error stays bounded. \
         Explicit Euler multiplies the energy by 1 + w²dt² every step (inf: its velocity \
         overflowed f32, and the energy grew without bound); RK4 loses a little every step.\n"
    );
    let _ = writeln!(md, "## Stability at hard settings\n");
    let _ = writeln!(
        md,
        "| setting | form | speeds over the first steps | verdict |\n|---|---|---|---|"
    );
    for s in &report.stability {
        let speeds: Vec<String> = s.speeds.iter().take(5).map(|v| format!("{v:.3}")).collect();
        let _ = writeln!(
            md,
            "| {} | {:?} | {} … | {} |",
            s.name,
            s.form,
            speeds.join(", "),
            if s.unstable {
                "unstable (grows or reverses)"
            } else {
                "decays monotonically"
            }
        );
    }
    let _ = writeln!(
        md,
        "\n## Variable against fixed time step: apex of a 5 m/s jump (exact 1.2742 m)\n"
    );
    let _ = writeln!(
        md,
        "| frames per second | one variable step per frame | fixed 60 Hz loop |\n|---:|---:|---:|"
    );
    for a in &report.apex {
        let _ = writeln!(md, "| {} | {:.4} m | {:.4} m |", a.fps, a.variable, a.fixed);
    }
    let spread = |f: fn(&Apex) -> f32| {
        let v: Vec<f32> = report.apex.iter().map(f).collect();
        v.iter().copied().fold(f32::NEG_INFINITY, f32::max)
            - v.iter().copied().fold(f32::INFINITY, f32::min)
    };
    let _ = writeln!(
        md,
        "| spread | {:.4} m | {:.4} m |\n",
        spread(|a| a.variable),
        spread(|a| a.fixed)
    );
    md
}

/// A short reading of one case: which method is cheapest for an error
/// target, and where methods go unstable.
fn reading(case: &Case, rows: &[&Row]) -> String {
    let mut text = String::new();
    for target in [1e-2, 1e-4] {
        let goal = target * case.scale();
        let best = rows
            .iter()
            .filter(|r| !r.unstable() && r.error <= goal)
            .min_by(|a, b| a.ns_per_body().total_cmp(&b.ns_per_body()));
        let _ = match best {
            Some(r) => write!(
                text,
                "Cheapest to an error under {goal:.0e} m: {} at dt = {} ({:.0} ns per body for the run). ",
                r.method,
                fmt_dt(r.dt),
                r.ns_per_body()
            ),
            None => write!(
                text,
                "No method reaches an error under {goal:.0e} m at these steps. "
            ),
        };
    }
    for m in METHODS {
        let unstable: Vec<String> = rows
            .iter()
            .filter(|r| r.method == m.name && r.unstable())
            .map(|r| fmt_dt(r.dt))
            .collect();
        if !unstable.is_empty() {
            let _ = write!(
                text,
                "{} is unstable at dt = {}. ",
                m.name,
                unstable.join(", ")
            );
        }
    }
    text.trim_end().to_owned()
}
