//! The demo's panel (egui): scenes, loop controls, force sliders, stats,
//! a live plot and the controls' help.

use super::catalogue::Entry;
use super::controls::Knobs;
use super::history::History;
use super::replay::{Command, Replay};
use super::sim::Sim;
use crate::draw::BACKGROUND;
use egui::{Color32, Slider, Stroke};
use passo_physics::Integrator;
use passo_render::Camera2D;
use std::time::Duration;

/// Debug drawing switches.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ViewOptions {
    /// Velocity arrows.
    pub velocities: bool,
    /// Force-model arrows.
    pub forces: bool,
    /// Contact normals.
    pub contacts: bool,
    /// Sleeping bodies drawn darker.
    pub sleeping: bool,
}

/// What the panel asked for this frame.
#[derive(Clone, Debug, Default)]
pub(crate) struct Actions {
    /// Open another scene.
    pub switch_to: Option<Entry>,
    /// Commands for the simulation (recorded in replays).
    pub commands: Vec<Command>,
    /// Start recording a replay.
    pub record: bool,
    /// Stop recording and save the replay.
    pub stop_recording: bool,
    /// Play the last saved replay.
    pub replay_last: bool,
}

/// What the panel shows but does not change.
pub(crate) struct PanelInput<'a> {
    pub catalogue: &'a [(String, Entry)],
    pub current: &'a Entry,
    pub fps: f64,
    pub message: Option<&'a str>,
    /// A replay was saved this session.
    pub last_replay: bool,
}

const RATES: [f64; 5] = [30.0, 60.0, 64.0, 120.0, 240.0];

/// The left panel. Returns its width in points.
pub(crate) fn panel(
    ui: &mut egui::Ui,
    sim: &mut Sim,
    view: &mut ViewOptions,
    input: &PanelInput<'_>,
    actions: &mut Actions,
) -> f32 {
    // No fill: the scene's background shows through, and the scene is
    // clipped to the right of the panel (`DrawList::clip`). On a software
    // adapter filling the panel's pixels again cost a large share of a
    // frame (BENCHMARKS.md, Off-screen rendering, has the timing).
    let frame = egui::Frame::side_top_panel(ui.style()).fill(Color32::TRANSPARENT);
    // What lies behind the panel, told to egui without painting it, so the
    // scroll area fades its edges into the scene's background.
    let [r, g, b, _] = BACKGROUND;
    let behind = egui::Frame::NONE.fill(Color32::from_rgb(r, g, b));
    let behind = egui::UiStackInfo::new(egui::UiKind::Frame).with_frame(behind);
    let response = egui::Panel::left("passo panel")
        .frame(frame)
        .default_size(300.0)
        .show(ui, |ui| {
            ui.scope_builder(egui::UiBuilder::new().ui_stack_info(behind), |ui| {
                panel_contents(ui, sim, view, input, actions);
            });
        });
    response.response.rect.width()
}

/// The panel's sections. The plot comes right after the scene, so it is
/// whole in a window of any height; the rest are sections that fold, in a
/// scroll area whose bar is always drawn (egui's default bars float and
/// show only under the pointer, so a cut-off panel looked complete).
fn panel_contents(
    ui: &mut egui::Ui,
    sim: &mut Sim,
    view: &mut ViewOptions,
    input: &PanelInput<'_>,
    actions: &mut Actions,
) {
    ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
    let bar = egui::scroll_area::ScrollBarVisibility::AlwaysVisible;
    egui::ScrollArea::vertical()
        .scroll_bar_visibility(bar)
        .show(ui, |ui| {
            scene_section(ui, sim, input, actions);
            plot(ui, sim);
            section(ui, "Loop", true, |ui| loop_section(ui, sim, actions));
            section(ui, "Rewind", true, |ui| rewind_section(ui, sim));
            section(ui, "Forces", true, |ui| forces_section(ui, sim, actions));
            section(ui, "Stats", true, |ui| stats_section(ui, sim, input.fps));
            section(ui, "Draw", true, |ui| {
                ui.horizontal_wrapped(|ui| {
                    ui.checkbox(&mut view.velocities, "velocities");
                    ui.checkbox(&mut view.forces, "forces");
                    ui.checkbox(&mut view.contacts, "contacts");
                    ui.checkbox(&mut view.sleeping, "dim sleeping");
                });
            });
            section(ui, "Controls", false, help);
        });
}

/// A section of the panel that folds under its heading.
fn section(ui: &mut egui::Ui, title: &str, open: bool, contents: impl FnOnce(&mut egui::Ui)) {
    egui::CollapsingHeader::new(egui::RichText::new(title).strong())
        .default_open(open)
        .show(ui, contents);
}

fn scene_section(ui: &mut egui::Ui, sim: &mut Sim, input: &PanelInput<'_>, actions: &mut Actions) {
    ui.heading("Passo");
    let current_label = input
        .catalogue
        .iter()
        .find(|(_, e)| e == input.current)
        .map_or("?", |(l, _)| l.as_str());
    egui::ComboBox::from_label("scene")
        .selected_text(current_label)
        .show_ui(ui, |ui| {
            for (label, entry) in input.catalogue {
                if ui.selectable_label(entry == input.current, label).clicked()
                    && entry != input.current
                {
                    actions.switch_to = Some(entry.clone());
                }
            }
        });
    ui.label(egui::RichText::new(&sim.scene.description).italics());
    if let Some(count) = sim.scene.rain_count() {
        let mut n = count;
        let response = ui.add(
            Slider::new(&mut n, 100..=Replay::MAX_RAIN_COUNT)
                .logarithmic(true)
                .text("bodies"),
        );
        if response.drag_stopped() || (response.changed() && !response.dragged()) {
            actions.commands.push(Command::RainCount(n));
        }
    }
    ui.horizontal(|ui| {
        if sim.session.is_recording() {
            ui.colored_label(Color32::from_rgb(240, 90, 90), "recording");
            actions.stop_recording |= ui.button("stop and save").clicked();
        } else {
            let record = egui::Button::new(
                egui::RichText::new("record").color(Color32::from_rgb(240, 90, 90)),
            );
            actions.record |= ui.add(record).clicked();
            actions.replay_last |= ui
                .add_enabled(input.last_replay, egui::Button::new("replay last"))
                .clicked();
        }
    });
    if let Some((played, total, result, recorded)) = sim.session.playback_status() {
        let text = match result {
            None => format!("replaying: tick {played} of {total}"),
            Some(h) if h == recorded => {
                format!("replay done: {total} ticks, same final state ({h:016x})")
            }
            Some(h) => format!(
                "replay done: final state {h:016x} differs from the recorded {recorded:016x}"
            ),
        };
        ui.label(text);
    }
    if let Some(message) = input.message {
        ui.colored_label(Color32::from_rgb(240, 120, 120), message);
    }
}

/// The timeline of kept states: drag back to rewind, step with the
/// arrows, resume from any point (which discards the states after it).
fn rewind_section(ui: &mut egui::Ui, sim: &mut Sim) {
    let kept = sim.scene.rewindable();
    let scrubbing = sim.scene.scrubbing();
    // Scrubbing keeps the present as the newest state; before, the present
    // is one past the kept ones.
    let newest = if scrubbing.is_some() {
        kept.saturating_sub(1)
    } else {
        kept
    };
    let dt = sim.session.timestep.dt();
    ui.label(format!(
        "{} ticks kept ({:.1} s), {:.1} MB",
        newest,
        newest as f32 * dt,
        sim.scene.rewind_bytes() as f64 / 1e6
    ));
    if !sim.can_rewind() {
        ui.label("off while recording or replaying");
        return;
    }
    let mut at = scrubbing.unwrap_or(newest);
    let before = at;
    ui.add_enabled(newest > 0, Slider::new(&mut at, 0..=newest).text("tick"));
    ui.horizontal(|ui| {
        if ui
            .add_enabled(at > 0, egui::Button::new("< back"))
            .clicked()
        {
            at -= 1;
        }
        if ui
            .add_enabled(at < newest, egui::Button::new("on >"))
            .clicked()
        {
            at += 1;
        }
        if ui
            .add_enabled(scrubbing.is_some(), egui::Button::new("resume here"))
            .clicked()
        {
            sim.resume_from_timeline();
        }
    });
    if at != before {
        sim.scrub_to(at);
    }
    if scrubbing.is_some() {
        ui.label("held on the timeline: resume to run on from here (the later states go)");
    }
}

fn loop_section(ui: &mut egui::Ui, sim: &mut Sim, actions: &mut Actions) {
    ui.horizontal(|ui| {
        let paused = sim.session.timestep.is_paused();
        if ui.button(if paused { "resume" } else { "pause" }).clicked() {
            if paused {
                sim.session.timestep.resume();
            } else {
                sim.session.timestep.pause();
            }
        }
        if ui.add_enabled(paused, egui::Button::new("step")).clicked() {
            sim.session.timestep.step_once();
        }
        if ui.button("reset").clicked() {
            actions.commands.push(Command::Reset);
        }
    });
    let mut scale = sim.session.timestep.time_scale();
    if ui
        .add(
            Slider::new(&mut scale, 0.05..=4.0)
                .logarithmic(true)
                .text("time scale"),
        )
        .changed()
    {
        let _ = sim.session.timestep.set_time_scale(scale);
    }
    let mut hz = sim.session.timestep.hz();
    egui::ComboBox::from_label("fixed rate")
        .selected_text(format!("{hz:.0} Hz"))
        .show_ui(ui, |ui| {
            for rate in RATES {
                ui.selectable_value(&mut hz, rate, format!("{rate:.0} Hz"));
            }
        });
    if (hz - sim.session.timestep.hz()).abs() > 1e-6 {
        actions.commands.push(Command::Rate(hz));
    }
    let mut interpolation = sim.scene.interpolation();
    if ui
        .checkbox(&mut interpolation, "interpolate drawing")
        .changed()
    {
        sim.scene.set_interpolation(interpolation);
    }
    if !sim.scene.fixed_integrators {
        let mut integrator = sim.scene.integrator();
        egui::ComboBox::from_label("integrator")
            .selected_text(integrator.name())
            .show_ui(ui, |ui| {
                for i in Integrator::ALL {
                    ui.selectable_value(&mut integrator, i, i.name());
                }
            });
        if integrator != sim.scene.integrator() {
            actions.commands.push(Command::Integrator(integrator));
        }
    }
}

fn forces_section(ui: &mut egui::Ui, sim: &Sim, actions: &mut Actions) {
    let mut k = sim.session.knobs;
    let mut changed = false;
    changed |= ui
        .add(Slider::new(&mut k.gravity, -30.0..=0.0).text("gravity (m/s²)"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut k.density, 0.0..=5.0).text("air density (kg/m³)"))
        .changed();
    ui.horizontal(|ui| {
        changed |= ui.checkbox(&mut k.wind, "wind").changed();
        changed |= ui
            .add(Slider::new(&mut k.wind_speed, -30.0..=30.0).text("m/s"))
            .changed();
    });
    changed |= ui
        .add(Slider::new(&mut k.min_speed, 0.0..=0.5).text("min speed (m/s)"))
        .changed();
    changed |= ui
        .add(
            Slider::new(&mut k.max_speed, Knobs::MAX_SPEED_RANGE)
                .logarithmic(true)
                .text("max speed (m/s)"),
        )
        .changed();
    let friction = ui
        .add(Slider::new(&mut k.friction, 0.0..=1.5).text("friction μ"))
        .changed();
    let drag = ui
        .add(
            Slider::new(&mut k.drag_scale, 0.1..=20.0)
                .logarithmic(true)
                .text("drag area ×"),
        )
        .changed();
    let restitution = ui
        .add(Slider::new(&mut k.restitution, 0.0..=1.0).text("restitution"))
        .changed();
    if sim.scene.has_contacts() {
        changed |= ui
            .checkbox(&mut k.continuous, "continuous collision")
            .changed();
        changed |= ui
            .checkbox(&mut k.sleeping, "sleeping")
            .on_hover_text(
                "islands at rest for 0.5 s sleep: not solved until something reaches them",
            )
            .changed();
    }
    if changed || friction || drag || restitution {
        actions.commands.push(Command::Knobs {
            knobs: k,
            friction,
            restitution,
            drag,
        });
    }
}

fn stats_section(ui: &mut egui::Ui, sim: &Sim, fps: f64) {
    let s = sim.session.stats;
    egui::Grid::new("stats").num_columns(2).show(ui, |ui| {
        let mut row = |name: &str, value: String| {
            ui.label(name);
            ui.label(value);
            ui.end_row();
        };
        row("frames per second", format!("{fps:.0}"));
        row("ticks this frame", s.ticks.to_string());
        row("dropped time", format_duration(s.dropped));
        row(
            "dropped in all",
            format_duration(sim.session.timestep.dropped_total()),
        );
        row("step time", format!("{:.2} ms", s.step_ms));
        row("bodies", sim.scene.body_count().to_string());
        let (sleeping, solved, contacts) = sim.scene.sleep_counts();
        row("sleeping bodies", sleeping.to_string());
        row("contacts solved", format!("{solved} of {contacts}"));
        row("total energy", format!("{:.2} J", sim.scene.energy()));
        row("tick", sim.session.timestep.tick().to_string());
    });
}

fn format_duration(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

/// Series colours of the plot.
const SERIES: [Color32; 6] = [
    Color32::from_rgb(228, 108, 58),
    Color32::from_rgb(92, 184, 92),
    Color32::from_rgb(58, 142, 228),
    Color32::from_rgb(163, 92, 214),
    Color32::from_rgb(228, 184, 58),
    Color32::from_rgb(58, 200, 192),
];

/// The colour of series `i` (and of its reference line): the body's own
/// when the plot follows bodies, else the panel's palette.
fn series_colour(h: &History, i: usize) -> Color32 {
    h.colours
        .get(i)
        .map_or(SERIES[i % SERIES.len()], |&[r, g, b, _]| {
            Color32::from_rgb(r, g, b)
        })
}

/// The smallest and largest finite values, or infinities when none is.
fn finite_range(values: impl Iterator<Item = f32>) -> (f32, f32) {
    values
        .filter(|v| v.is_finite())
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        })
}

/// The series that run away from the rest (explicit Euler's energy, which
/// grows without bound): their span is more than ten times the median
/// span of three or more series. The plot's range leaves them out, so the
/// others stay readable, and they leave through the top.
fn runaway_series(h: &History) -> Vec<bool> {
    let spans: Vec<f32> = h
        .series
        .iter()
        .map(|(_, s)| {
            let (lo, hi) = finite_range(s.iter().copied());
            if lo.is_finite() { hi - lo } else { 0.0 }
        })
        .collect();
    if spans.len() < 3 {
        return vec![false; spans.len()];
    }
    let mut sorted = spans.clone();
    sorted.sort_by(f32::total_cmp);
    let median = sorted[sorted.len() / 2];
    spans.iter().map(|&span| span > 10.0 * median).collect()
}

/// A line chart of the history, drawn with egui's painter.
fn plot(ui: &mut egui::Ui, sim: &Sim) {
    let h = &sim.scene.history;
    ui.label(&h.title);
    let (rect, _) = ui.allocate_exact_size(
        egui::vec2(ui.available_width(), 130.0),
        egui::Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(20));
    let runaway = runaway_series(h);
    let values = h
        .series
        .iter()
        .enumerate()
        .filter(|(i, _)| !runaway[*i])
        .flat_map(|(_, (_, s))| s.iter().copied())
        .chain(h.lines.iter().map(|(_, v)| *v));
    let (mut lo, mut hi) = finite_range(values);
    if !lo.is_finite() || h.time.len() < 2 {
        return;
    }
    if hi - lo < 1e-6 {
        hi += 0.5;
        lo -= 0.5;
    }
    let (t0, t1) = (h.time[0], h.time[h.time.len() - 1].max(h.time[0] + 1e-6));
    let to_screen = |t: f32, v: f32| {
        egui::pos2(
            rect.left() + (t - t0) / (t1 - t0) * rect.width(),
            rect.bottom() - (v - lo) / (hi - lo) * rect.height(),
        )
    };
    for (i, (_, v)) in h.lines.iter().enumerate() {
        if !v.is_finite() {
            continue;
        }
        let colour = series_colour(h, i).gamma_multiply(0.6);
        painter.line_segment(
            [to_screen(t0, *v), to_screen(t1, *v)],
            Stroke::new(1.0, colour),
        );
    }
    for (i, (_, series)) in h.series.iter().enumerate() {
        let points: Vec<egui::Pos2> = h
            .time
            .iter()
            .zip(series)
            .filter(|(_, v)| v.is_finite())
            .map(|(t, v)| to_screen(*t, *v))
            .collect();
        painter.add(egui::Shape::line(
            points,
            Stroke::new(1.5, series_colour(h, i)),
        ));
    }
    painter.text(
        rect.left_top(),
        egui::Align2::LEFT_TOP,
        format!("{hi:.3}"),
        egui::FontId::monospace(10.0),
        Color32::GRAY,
    );
    painter.text(
        rect.left_bottom(),
        egui::Align2::LEFT_BOTTOM,
        format!("{lo:.3}"),
        egui::FontId::monospace(10.0),
        Color32::GRAY,
    );
    ui.horizontal_wrapped(|ui| {
        for (i, (name, _)) in h.series.iter().enumerate() {
            if runaway[i] {
                ui.colored_label(series_colour(h, i), format!("{name} (off the top)"));
            } else {
                ui.colored_label(series_colour(h, i), name);
            }
        }
    });
}

fn help(ui: &mut egui::Ui) {
    for line in [
        "A / D or the left / right arrows: walk (Shift: run)",
        "Space: jump (when standing)",
        "G (hold): glide, W: wind on/off",
        "P: pause, N: single step, R: reset",
        "Backspace (hold): rewind (up to 10 s); or drag the timeline",
        "left click: spawn (Shift: box)",
        "left drag on a body: pull it (a target joint)",
        "right drag: pan, wheel: zoom, F: fit",
        "V: velocity arrows",
    ] {
        ui.label(line);
    }
}

/// Names of side-by-side lanes, under each lane, and a marker at the
/// edge of the scene for each lane's body that left the view (explicit
/// Euler's spring swings ever wider), with how far beyond the edge it is.
/// `scene_left` is where the scene starts, right of the panel, in points.
pub(crate) fn lane_labels(
    ui: &mut egui::Ui,
    sim: &Sim,
    camera: &Camera2D,
    size: (u32, u32),
    pixels_per_point: f32,
    scene_left: f32,
) {
    if sim.scene.lanes.len() < 2 {
        return;
    }
    let painter = ui.ctx().layer_painter(egui::LayerId::new(
        egui::Order::Foreground,
        egui::Id::unique("lane labels"),
    ));
    for (i, lane) in sim.scene.lanes.iter().enumerate() {
        let below = lane.offset + glam::Vec2::new(0.0, -2.2);
        let px = camera.world_to_pixel(below, size) / pixels_per_point;
        painter.text(
            egui::pos2(px.x, px.y),
            egui::Align2::CENTER_TOP,
            &lane.label,
            egui::FontId::proportional(15.0),
            SERIES[i % SERIES.len()],
        );
    }
    const MARGIN: f32 = 16.0;
    let view = egui::Rect::from_min_max(
        egui::pos2(scene_left + MARGIN, MARGIN),
        egui::pos2(
            size.0 as f32 / pixels_per_point - MARGIN,
            size.1 as f32 / pixels_per_point - MARGIN,
        ),
    );
    let metres_per_point = camera.height / size.1.max(1) as f32 * pixels_per_point;
    for (i, lane) in sim.scene.lanes.iter().enumerate() {
        let colour = SERIES[i % SERIES.len()];
        let dynamic = lane
            .world
            .bodies()
            .filter(|b| b.kind == passo_physics::BodyKind::Dynamic);
        for body in dynamic {
            let px = camera.world_to_pixel(body.position + lane.offset, size) / pixels_per_point;
            let Some((at, out)) = edge_marker(egui::pos2(px.x, px.y), view) else {
                continue;
            };
            let (side, tip) = (out.rot90() * 7.0, at + out * 9.0);
            painter.add(egui::Shape::convex_polygon(
                vec![tip, at - out * 3.0 + side, at - out * 3.0 - side],
                colour,
                Stroke::NONE,
            ));
            let beyond = (egui::pos2(px.x, px.y) - at).length() * metres_per_point;
            painter.text(
                at - out * 10.0,
                egui::Align2::CENTER_CENTER,
                format!("{beyond:.0} m"),
                egui::FontId::proportional(13.0),
                colour,
            );
        }
    }
}

/// Where to mark a point `p` that lies outside `view`: the nearest point of
/// `view` and the unit direction from it towards `p`; `None` inside.
fn edge_marker(p: egui::Pos2, view: egui::Rect) -> Option<(egui::Pos2, egui::Vec2)> {
    if view.contains(p) || !p.x.is_finite() || !p.y.is_finite() {
        return None;
    }
    let at = view.clamp(p);
    Some((at, (p - at).normalized()))
}

#[cfg(test)]
mod glyph_tests {
    use egui::epaint::text::{FontDefinitions, FontFamily, FontId, Fonts, TextOptions};

    /// Every non-ASCII character in the demo's string literals is in the
    /// fonts the demo ships (egui's defaults): a missing one draws as an
    /// empty box (the record and rewind buttons once did).
    #[test]
    fn every_symbol_the_demo_shows_is_in_the_fonts() {
        let mut fonts = Fonts::new(TextOptions::default(), FontDefinitions::default());
        let font = FontId::new(14.0, FontFamily::Proportional);
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/demo");
        let mut missing = Vec::new();
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let source = std::fs::read_to_string(&path).unwrap();
            let code = &source[..source.find("#[cfg(test)]").unwrap_or(source.len())];
            for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
                // The text between quotes: the string literals.
                for literal in line.split('"').skip(1).step_by(2) {
                    for c in literal.chars().filter(|c| !c.is_ascii()) {
                        if !fonts.has_glyph(&font, c) {
                            missing.push((path.file_name().unwrap().to_owned(), c));
                        }
                    }
                }
            }
        }
        assert!(missing.is_empty(), "not in the fonts: {missing:?}");
    }
}

#[cfg(test)]
mod plot_tests {
    use super::*;

    #[test]
    fn a_point_off_the_view_is_marked_at_the_nearest_edge_facing_it() {
        let view = egui::Rect::from_min_max(egui::pos2(300.0, 0.0), egui::pos2(1000.0, 600.0));
        assert_eq!(edge_marker(egui::pos2(500.0, 300.0), view), None);
        assert_eq!(
            edge_marker(egui::pos2(500.0, -200.0), view),
            Some((egui::pos2(500.0, 0.0), egui::vec2(0.0, -1.0)))
        );
        assert_eq!(
            edge_marker(egui::pos2(1400.0, 300.0), view),
            Some((egui::pos2(1000.0, 300.0), egui::vec2(1.0, 0.0)))
        );
        // Past a corner: at the corner, pointing along the diagonal.
        let (at, out) = edge_marker(egui::pos2(1100.0, 700.0), view).unwrap();
        assert_eq!(at, egui::pos2(1000.0, 600.0));
        assert!((out - egui::vec2(1.0, 1.0).normalized()).length() < 1e-6);
        assert_eq!(edge_marker(egui::pos2(f32::NAN, 0.0), view), None);
    }
    use crate::demo::{Entry, load};

    /// Ten seconds of the integrators' springs: explicit Euler's energy
    /// runs away and leaves the plot's range; the other three set it.
    #[test]
    fn only_explicit_euler_runs_off_the_integrators_plot() {
        let mut sim = load(&Entry::Integrators).unwrap();
        let names: Vec<String> = sim
            .scene
            .history
            .series
            .iter()
            .map(|(n, _)| n.clone())
            .collect();
        assert_eq!(names.len(), 4, "{names:?}");
        for _ in 0..600 {
            sim.session.timestep.advance_ticks(1);
            sim.tick();
        }
        let runaway = runaway_series(&sim.scene.history);
        let off: Vec<&String> = names
            .iter()
            .zip(&runaway)
            .filter(|(_, r)| **r)
            .map(|(n, _)| n)
            .collect();
        assert_eq!(off.len(), 1, "{names:?} {runaway:?}");
        assert!(off[0].to_lowercase().contains("explicit"), "{off:?}");
    }

    /// The drag race's speeds all stay on the plot, each in its ball's
    /// colour.
    #[test]
    fn the_drag_race_plots_every_ball_in_its_own_colour() {
        let mut sim = load(&Entry::File("drag_race".into())).unwrap();
        for _ in 0..300 {
            sim.session.timestep.advance_ticks(1);
            sim.tick();
        }
        let h = &sim.scene.history;
        assert_eq!(h.series.len(), 6);
        assert!(runaway_series(h).iter().all(|r| !r));
        let lane = &sim.scene.lanes[0];
        for (i, (name, _)) in h.series.iter().enumerate() {
            let body = lane
                .bodies
                .iter()
                .find(|b| b.name.as_deref() == Some(name))
                .unwrap();
            let [r, g, b, _] = body.colour.0;
            assert_eq!(series_colour(h, i), Color32::from_rgb(r, g, b), "{name}");
            let speed = lane.world.body(body.id).unwrap().velocity.length();
            assert_eq!(h.series[i].1.back(), Some(&speed), "{name}");
        }
        // The terminal-speed lines match the series, one each.
        assert_eq!(h.lines.len(), 6);
    }
}
