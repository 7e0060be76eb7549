//! Solving contacts: the scalar and wide passes, colouring, regions, the substep buffers and continuous collision.

pub(crate) mod scalar;
pub(crate) mod lanes;
pub(crate) mod colouring;
pub(crate) mod crush;
pub(crate) mod motion;
pub(crate) mod regions;
pub(crate) mod continuous;
