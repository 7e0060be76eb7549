//! Renderer (to come).
