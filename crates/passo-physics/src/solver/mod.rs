//! Solving contacts: the scalar and wide passes, colouring, regions, the substep buffers, shock propagation and continuous collision.

pub(crate) mod scalar;
pub(crate) mod lanes;
pub(crate) mod colouring;
pub(crate) mod crush;
pub(crate) mod motion;
pub(crate) mod regions;
pub(crate) mod shock;
pub(crate) mod continuous;
