//! Scenes (to come).
