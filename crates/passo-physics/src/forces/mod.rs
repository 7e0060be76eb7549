//! Force models and the integrators that turn forces into motion.

pub(crate) mod models;
pub(crate) mod integrator;
pub(crate) mod kernel;
pub(crate) mod zones;
