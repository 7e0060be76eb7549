//! `passo bench integration` and `passo bench scaling`: the point-mass
//! step against this machine's memory bandwidth and against a bare loop,
//! and the step's cost over growing worlds.

use super::args::{IntegrationBenchArgs, ScalingBenchArgs};
use anyhow::Result;
use glam::Vec2;
use passo_benches::{rain_strip, time_steps};
use std::time::Instant;

/// Bytes the integration kernel moves per body-step: it reads position,
/// velocity, force (8 bytes each), inverse mass and drag area (4 each), and
/// writes position and velocity (8 each) and the cleared force (8).
pub const INTEGRATION_BYTES: f64 = 64.0;

/// Best-of-five memory bandwidth of a plain copy over `bytes` bytes, bytes
/// per second (counting what is read and what is written).
pub fn copy_bandwidth(bytes: usize) -> f64 {
    let src = vec![1u8; bytes];
    let mut dst = vec![0u8; bytes];
    let reps = (200_000_000 / bytes.max(1)).clamp(3, 10_000);
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                dst.copy_from_slice(std::hint::black_box(&src));
                std::hint::black_box(&mut dst);
            }
            2.0 * bytes as f64 * reps as f64 / start.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max)
}

/// Best-of-five bandwidth of the STREAM triad `a = b + s c` over three f32
/// arrays of `len` elements, bytes per second.
pub fn triad_bandwidth(len: usize) -> f64 {
    let b = vec![1.0f32; len];
    let c = vec![2.0f32; len];
    let mut a = vec![0.0f32; len];
    let reps = (50_000_000 / len.max(1)).clamp(3, 10_000);
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                for ((a, b), c) in a.iter_mut().zip(std::hint::black_box(&b)).zip(&c) {
                    *a = b + 3.0 * c;
                }
                std::hint::black_box(&mut a);
            }
            12.0 * len as f64 * reps as f64 / start.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max)
}

/// Nanoseconds per body-step of `n` point masses under gravity and
/// quadratic drag (the best of five timed runs), on the calling thread
/// alone or (`parallel`) on the thread pool for large worlds.
pub fn integration_ns(n: usize, parallel: bool) -> f64 {
    let mut world = passo_physics::World::new(passo_physics::WorldSettings {
        forces: passo_physics::ForceModels {
            quadratic_drag: Some(passo_physics::QuadraticDrag::default()),
            ..Default::default()
        },
        ..Default::default()
    })
    .expect("valid settings");
    for i in 0..n {
        let def = passo_physics::BodyDef {
            position: Vec2::new((i % 1000) as f32, (i / 1000) as f32),
            velocity: Vec2::new(3.0, 1.0),
            ..Default::default()
        };
        world.add_body(def).expect("valid body");
    }
    world.set_parallel(parallel);
    let steps = (20_000_000 / n.max(1)).clamp(5, 20_000);
    world.step(1.0 / 60.0);
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..steps {
                world.step(1.0 / 60.0);
            }
            start.elapsed().as_nanos() as f64 / (n * steps) as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// Nanoseconds per body-step of a bare structure-of-arrays loop doing the
/// arithmetic of [`integration_ns`]'s step (gravity, the accumulated force,
/// stable quadratic drag, the non-finite guard and subnormal flush, the
/// world's default speed limits, the position, the force cleared) on `n`
/// bodies, best of five: what the step would cost with nothing around the
/// arithmetic.
pub fn bare_soa_ns(n: usize) -> f64 {
    let (mut px, mut py) = (vec![0.0f32; n], vec![0.0f32; n]);
    let (mut vx, mut vy) = (vec![3.0f32; n], vec![1.0f32; n]);
    let (mut fx, mut fy) = (vec![0.0f32; n], vec![0.0f32; n]);
    let inv_mass = vec![1.0f32; n];
    let drag_area = vec![passo_physics::constants::DEFAULT_DRAG_AREA; n];
    let (g, dt) = (-9.81f32, 1.0f32 / 60.0);
    let (min, max) = (
        passo_physics::constants::DEFAULT_MIN_SPEED,
        passo_physics::constants::DEFAULT_MAX_SPEED,
    );
    let half_rho = 0.5 * passo_physics::QuadraticDrag::default().density;
    let steps = (20_000_000 / n.max(1)).clamp(5, 20_000);
    let mut step = || {
        // Equal lengths, so the compiler drops the bounds checks and can
        // vectorise the loop.
        let (px, py, vx, vy) = (&mut px[..n], &mut py[..n], &mut vx[..n], &mut vy[..n]);
        let (fx, fy, inv_mass, drag_area) =
            (&mut fx[..n], &mut fy[..n], &inv_mass[..n], &drag_area[..n]);
        for i in 0..n {
            let im = inv_mass[i];
            let mut x = vx[i] + fx[i] * im * dt;
            let mut y = vy[i] + (g + fy[i] * im) * dt;
            let k = half_rho * drag_area[i] * im;
            let scale = 1.0 / (1.0 + k * (x * x + y * y).sqrt() * dt);
            x *= scale;
            y *= scale;
            let finite = (x * x + y * y).is_finite();
            let flush = |c: f32| if c.abs() < f32::MIN_POSITIVE { 0.0 } else { c };
            x = if finite { flush(x) } else { 0.0 };
            y = if finite { flush(y) } else { 0.0 };
            // The speed limits: clamp to the maximum, snap below the minimum.
            let s2 = x * x + y * y;
            let clamp = if s2 > max * max { max / s2.sqrt() } else { 1.0 };
            let keep = if s2 < min * min { 0.0 } else { clamp };
            x *= keep;
            y *= keep;
            vx[i] = x;
            vy[i] = y;
            px[i] += x * dt;
            py[i] += y * dt;
            fx[i] = 0.0;
            fy[i] = 0.0;
        }
        std::hint::black_box((px, py));
    };
    step();
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..steps {
                step();
            }
            start.elapsed().as_nanos() as f64 / (n * steps) as f64
        })
        .fold(f64::INFINITY, f64::min)
}

pub(super) fn integration(args: &IntegrationBenchArgs) -> Result<()> {
    // One thread against one thread: the copy and triad loops run on the
    // calling thread, and so does the kernel for the fraction; the last
    // column is the same step with the thread pool (large worlds only).
    println!(
        "| bodies | ns per body-step | bare SoA loop, ns | step / bare loop | kernel bandwidth | copy bandwidth | triad bandwidth | fraction of copy | ns per body-step, thread pool |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in &args.sizes {
        // The step and the bare loop timed in turn, three times each, the
        // best of each kept: a slow spell of a shared machine then rarely
        // falls on one of the two alone and skews the ratio.
        let (ns, bare) = (0..3)
            .map(|_| (integration_ns(n, false), bare_soa_ns(n)))
            .fold((f64::INFINITY, f64::INFINITY), |(a, b), (x, y)| {
                (a.min(x), b.min(y))
            });
        let kernel = INTEGRATION_BYTES / ns; // bytes per ns = GB/s
        let copy = copy_bandwidth(n * 32) / 1e9;
        let triad = triad_bandwidth(n * 8) / 1e9;
        let pooled = integration_ns(n, true);
        println!(
            "| {n} | {ns:.2} | {bare:.2} | {:.2}× | {kernel:.1} GB/s | {copy:.1} GB/s | {triad:.1} GB/s | {:.0} % | {pooled:.2} |",
            ns / bare,
            100.0 * kernel / copy
        );
    }
    Ok(())
}

/// The exponent `k` of the least-squares fit `cost = c n^k`, or `None`
/// when the points do not span two sizes (no line fits one point).
pub fn fitted_exponent(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    (sxx > 0.0).then(|| sxy / sxx)
}

pub(super) fn scaling(args: &ScalingBenchArgs) -> Result<()> {
    println!("| bodies | ms per step | µs per body-step |");
    println!("|---:|---:|---:|");
    let mut points = Vec::new();
    for &n in &args.sizes {
        let mut world = rain_strip(n);
        let warm = args.ticks / 3;
        for _ in 0..warm {
            world.step(1.0 / 60.0);
        }
        let t = time_steps(args.ticks - warm, || world.step(1.0 / 60.0));
        println!(
            "| {n} | {:.2} | {:.3} |",
            t.mean_ms,
            t.mean_ms * 1e3 / n as f64
        );
        points.push((n as f64, t.mean_ms));
    }
    match fitted_exponent(&points) {
        Some(k) => println!("\nfitted exponent of ms per step against bodies: {k:.3}"),
        None => println!("\nno exponent fitted: give two sizes or more (--sizes)"),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::fitted_exponent;

    #[test]
    fn the_exponent_fits_a_power_law_and_needs_two_sizes() {
        let linear = [(1e3, 2.0), (1e4, 20.0), (1e5, 200.0)];
        assert!((fitted_exponent(&linear).unwrap() - 1.0).abs() < 1e-12);
        let square = [(10.0, 1.0), (20.0, 4.0)];
        assert!((fitted_exponent(&square).unwrap() - 2.0).abs() < 1e-12);
        // One size (or one twice): `passo bench scaling` printed NaN.
        assert_eq!(fitted_exponent(&[(1e3, 2.0)]), None);
        assert_eq!(fitted_exponent(&[(1e3, 2.0), (1e3, 2.1)]), None);
        assert_eq!(fitted_exponent(&[]), None);
    }
}
