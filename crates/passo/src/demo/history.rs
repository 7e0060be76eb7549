//! The panel's plot: what it shows for a scene (the scene table's
//! [`Plot`]), one sample per tick over the last ten seconds, and
//! closed-form reference lines.

use super::lanes::Lane;
use crate::scenes::Plot;
use passo_physics::{BodyId, BodyKind};
use std::collections::VecDeque;

/// Samples kept for the plot: 10 s at 60 Hz.
const HISTORY: usize = 600;

/// Plotted values over the last ten seconds.
#[derive(Clone, Debug)]
pub struct History {
    /// What is plotted.
    pub title: String,
    /// Simulated time of each sample, seconds.
    pub time: VecDeque<f32>,
    /// Named series, one value per sample.
    pub series: Vec<(String, VecDeque<f32>)>,
    /// Named horizontal reference lines (closed-form values).
    pub lines: Vec<(String, f32)>,
    /// The colour (sRGB) of each series and of the line of the same
    /// index: the body's own in the speed plot, so the legend matches
    /// the balls; empty for the energy plot, whose lanes take the panel's
    /// colours.
    pub colours: Vec<[u8; 4]>,
    /// The bodies of the speed plot, one per series.
    tracked: Vec<BodyId>,
    plot: Plot,
}

impl History {
    /// An empty plot of `plot` with one series per lane (energy) or per
    /// dynamic body of lane 0 (speeds).
    pub(crate) fn new(plot: Plot, lanes: &[Lane]) -> Self {
        let (mut colours, mut tracked) = (Vec::new(), Vec::new());
        let (title, series) = match plot {
            Plot::Energy => (
                "total energy (J)",
                lanes
                    .iter()
                    .map(|l| {
                        if l.label.is_empty() {
                            "energy".into()
                        } else {
                            l.label.clone()
                        }
                    })
                    .collect::<Vec<String>>(),
            ),
            Plot::TerminalSpeed => {
                let lane = &lanes[0];
                (
                    "speed (m/s); lines: terminal speed",
                    lane.bodies
                        .iter()
                        .filter(|b| {
                            lane.world
                                .body(b.id)
                                .is_some_and(|b| b.kind == BodyKind::Dynamic)
                        })
                        .map(|b| {
                            colours.push(b.colour.0);
                            tracked.push(b.id);
                            b.name.clone().unwrap_or_default()
                        })
                        .collect(),
                )
            }
        };
        Self {
            title: title.into(),
            time: VecDeque::new(),
            series: series.into_iter().map(|s| (s, VecDeque::new())).collect(),
            lines: Vec::new(),
            colours,
            tracked,
            plot,
        }
    }

    /// What is plotted.
    pub fn plot(&self) -> Plot {
        self.plot
    }

    /// Adds the sample of time `t`, seconds, read from the lanes.
    pub(crate) fn sample(&mut self, t: f32, lanes: &[Lane]) {
        let values: Vec<f32> = match self.plot {
            Plot::Energy => lanes
                .iter()
                .map(|l| l.world.total_energy() as f32)
                .collect(),
            // By id, so a body spawned or removed since does not shift
            // the series.
            Plot::TerminalSpeed => self
                .tracked
                .iter()
                .map(|&id| {
                    lanes[0]
                        .world
                        .body(id)
                        .map_or(f32::NAN, |b| b.velocity.length())
                })
                .collect(),
        };
        if self.time.len() == HISTORY {
            self.time.pop_front();
            for (_, s) in &mut self.series {
                s.pop_front();
            }
        }
        self.time.push_back(t);
        for ((_, s), v) in self.series.iter_mut().zip(&values) {
            s.push_back(*v);
        }
    }

    /// For the speed plot, the terminal speeds `sqrt(2 m g / (rho Cd A))`
    /// of lane 0's dynamic bodies under gravity `gravity` (m/s²) and air
    /// density `density` (kg/m³).
    pub(crate) fn update_lines(&mut self, lanes: &[Lane], gravity: f32, density: f32) {
        if self.plot != Plot::TerminalSpeed {
            return;
        }
        let (g, rho) = (gravity.abs(), density);
        // One line per series, in its colour; a speed with no bound (no
        // air) is infinite, and the plot leaves it out.
        self.lines = self
            .tracked
            .iter()
            .map(|&id| {
                let vt = lanes[0].world.body(id).map_or(f32::NAN, |b| {
                    (2.0 * b.mass * g / (rho * b.drag_area)).sqrt()
                });
                (format!("{:.1} m/s", vt), vt)
            })
            .collect();
    }
}
