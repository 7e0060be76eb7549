//! The physics in Bevy's diagnostics: read them from the
//! [`DiagnosticsStore`](bevy::diagnostic::DiagnosticsStore), or print them
//! with Bevy's `LogDiagnosticsPlugin`.

use bevy::diagnostic::{Diagnostic, DiagnosticPath, Diagnostics, RegisterDiagnostic};
use bevy::ecs::system::SystemParam;
use bevy::platform::time::Instant;
use bevy::prelude::App;
use passo_physics::World;

/// Wall-clock milliseconds `World::step` took in the last tick.
pub const STEP_TIME: DiagnosticPath = DiagnosticPath::const_new("passo/step_time");
/// Bodies in the world, of every kind.
pub const BODIES: DiagnosticPath = DiagnosticPath::const_new("passo/bodies");
/// Dynamic bodies that are awake (not sleeping).
pub const AWAKE_BODIES: DiagnosticPath = DiagnosticPath::const_new("passo/awake_bodies");
/// Contacts the solver worked on in the last tick.
pub const CONTACTS: DiagnosticPath = DiagnosticPath::const_new("passo/contacts");

pub(crate) fn register(app: &mut App) {
    app.register_diagnostic(Diagnostic::new(STEP_TIME).with_suffix(" ms"))
        .register_diagnostic(Diagnostic::new(BODIES))
        .register_diagnostic(Diagnostic::new(AWAKE_BODIES))
        .register_diagnostic(Diagnostic::new(CONTACTS));
}

/// Measures a tick.
#[derive(SystemParam)]
pub(crate) struct StepDiagnostics<'w, 's> {
    diagnostics: Diagnostics<'w, 's>,
}

impl StepDiagnostics<'_, '_> {
    pub(crate) fn start(&self) -> Instant {
        Instant::now()
    }

    pub(crate) fn finish(&mut self, started: Instant, world: &World) {
        let ms = started.elapsed().as_secs_f64() * 1000.0;
        self.diagnostics.add_measurement(&STEP_TIME, || ms);
        self.diagnostics
            .add_measurement(&BODIES, || world.len() as f64);
        self.diagnostics.add_measurement(&AWAKE_BODIES, || {
            world.dynamic_len().saturating_sub(world.sleeping_len()) as f64
        });
        self.diagnostics
            .add_measurement(&CONTACTS, || world.solved_contacts() as f64);
    }
}
