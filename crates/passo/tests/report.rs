//! The accuracy report's own data: convergence orders match theory,
//! energy drift behaves as each integrator's theory says, the stable forms
//! survive the hard settings that break the plain ones, and the files are
//! written.

use passo::report::{self, ReportArgs, observed_order};
use std::sync::OnceLock;

fn data() -> &'static report::Report {
    static DATA: OnceLock<report::Report> = OnceLock::new();
    DATA.get_or_init(|| {
        // Few bodies for the cost column: costs are for benchmarks, the
        // errors are what the tests check.
        report::measure(&ReportArgs {
            cost_bodies: 50,
            cost_steps: 2,
            long_steps: 1_000_000,
            ..Default::default()
        })
    })
}

#[test]
fn observed_orders_match_theory_where_it_holds() {
    let expected = [
        (1.0, "projectile", "explicit_euler"),
        (1.0, "projectile", "semi_implicit_euler"),
        (1.0, "linear_drag", "explicit_euler"),
        (1.0, "linear_drag", "explicit_euler_plain"),
        (1.0, "linear_drag", "semi_implicit_euler"),
        (1.0, "linear_drag", "semi_implicit_euler_plain"),
        (2.0, "linear_drag", "velocity_verlet"),
        (1.0, "quadratic_drag_fall", "explicit_euler"),
        (1.0, "quadratic_drag_fall", "explicit_euler_plain"),
        (1.0, "quadratic_drag_fall", "semi_implicit_euler"),
        (1.0, "quadratic_drag_fall", "semi_implicit_euler_plain"),
        (1.0, "drag_coast", "explicit_euler"),
        (1.0, "drag_coast", "semi_implicit_euler"),
        (2.0, "drag_coast", "velocity_verlet"),
        (2.0, "spring", "velocity_verlet"),
        (4.0, "spring", "rk4"),
    ];
    let rows = &data().rows;
    for (theory, case, method) in expected {
        let order = observed_order(rows, case, method)
            .unwrap_or_else(|| panic!("no order for {case}/{method}"));
        assert!(
            (order - theory).abs() <= 0.2,
            "{case}/{method}: observed {order:.3}, theory {theory}"
        );
    }
    // Verlet and RK4 are exact on the projectile: their errors are rounding.
    for method in ["velocity_verlet", "rk4"] {
        for r in rows
            .iter()
            .filter(|r| r.case == "projectile" && r.method == method)
        {
            assert!(r.error < 5e-4, "{method} at dt {}: {}", r.dt, r.error);
        }
    }
}

#[test]
fn the_closed_form_is_taken_at_the_time_the_world_simulated() {
    // The world steps by dt as f32 (1/480 s is 3.2e-8 longer, relative);
    // the closed form at steps * dt in f64 put a bias of 5e-8 T |v| on
    // every error: RK4 on the spring at 1/480 s read 2.56e-6 m, where the
    // error at the time simulated is 7.7e-8 m.
    let rk4 = data()
        .rows
        .iter()
        .find(|r| r.case == "spring" && r.method == "rk4" && (r.dt - 1.0 / 480.0).abs() < 1e-12)
        .unwrap();
    assert!(rk4.error < 5e-7, "{}", rk4.error);
}

#[test]
fn energy_drift_is_bounded_for_semi_implicit_euler_grows_for_explicit_euler_and_decays_for_rk4() {
    let drift = |name: &str| {
        data()
            .long_drift
            .iter()
            .find(|(m, _)| *m == name)
            .unwrap()
            .1
    };
    // w dt = 0.1: symplectic Euler's energy oscillates by about w dt / 2.
    assert!(
        drift("semi_implicit_euler").abs() < 0.1,
        "{}",
        drift("semi_implicit_euler")
    );
    assert!(drift("velocity_verlet").abs() < 0.01);
    // Explicit Euler's velocity overflows f32 within 10^6 steps (at step
    // 8 558): the energy grew without bound, reported as infinite (it read
    // +3e36, what the non-finite guard's resets left).
    let explicit = drift("explicit_euler");
    assert_eq!(explicit, f64::INFINITY, "explicit Euler");
    // RK4 loses (w dt)^6 / 72 per step: 1.4 % over 10^6 steps.
    let rk4 = drift("rk4");
    assert!((-0.02..=-0.008).contains(&rk4), "rk4: {rk4}");
    // The per-case drift column: conservative cases only.
    for r in &data().rows {
        let conservative = matches!(
            r.case,
            "projectile" | "spring" | "kepler" | "pendulum_small" | "pendulum_large"
        );
        assert_eq!(
            r.energy_drift.is_some(),
            conservative,
            "{}/{}",
            r.case,
            r.method
        );
    }
}

#[test]
fn stable_forms_survive_the_hard_settings_that_break_the_plain_ones() {
    let s = &data().stability;
    let find = |prefix: &str, form| {
        s.iter()
            .find(|x| x.name.starts_with(prefix) && x.form == form)
            .unwrap()
    };
    use passo_physics::ForceForm::{Explicit, Stable};
    let drag = find("quadratic drag", Stable);
    assert!(!drag.unstable);
    assert!(
        drag.speeds.windows(2).all(|w| w[1] <= w[0]),
        "monotone: {:?}",
        drag.speeds
    );
    assert!(
        *drag.speeds.last().unwrap() < 0.05,
        "decays toward zero: {:?}",
        drag.speeds
    );
    assert!(find("quadratic drag", Explicit).unstable);
    let friction = find("friction", Stable);
    assert!(!friction.unstable);
    assert!(
        friction.speeds.iter().all(|&v| v == 0.0),
        "stops in one step: {:?}",
        friction.speeds
    );
    assert!(
        find("friction", Explicit).unstable,
        "the plain form reverses the velocity"
    );
}

#[test]
fn a_variable_step_changes_the_apex_the_fixed_loop_does_not() {
    let apex = &data().apex;
    let spread = |f: fn(&report::Apex) -> f32| {
        let v: Vec<f32> = apex.iter().map(f).collect();
        v.iter().copied().fold(f32::MIN, f32::max) - v.iter().copied().fold(f32::MAX, f32::min)
    };
    assert!(spread(|a| a.variable) > 0.05);
    assert_eq!(spread(|a| a.fixed), 0.0);
    assert_eq!(
        apex.iter().map(|a| a.fps).collect::<Vec<_>>(),
        [30, 60, 144, 240]
    );
}

#[test]
fn the_report_files_are_written() {
    let dir = std::env::temp_dir().join(format!("passo-report-{}", std::process::id()));
    report::write(data(), &dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("accuracy.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("case,method,dt,error,energy_drift,ns_per_body_step")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), data().rows.len() + 4);
    assert!(rows.iter().all(|r| r.len() == 6));
    // 10 cases; 6 steps each; 4 methods where no drag or friction acts
    // (6 cases), 6 where they do (4).
    assert_eq!(data().rows.len(), 6 * (6 * 4 + 4 * 6));
    let md = std::fs::read_to_string(dir.join("accuracy.md")).unwrap();
    for heading in [
        "## projectile",
        "## kepler",
        "## Energy drift",
        "## Stability",
        "## Variable against fixed",
    ] {
        assert!(md.contains(heading), "{heading}");
    }
    let png = passo_render::RgbaImage::load_png(dir.join("work_precision.png")).unwrap();
    assert_eq!((png.width, png.height), (1500, 1400));
    std::fs::remove_dir_all(dir).unwrap();
}
