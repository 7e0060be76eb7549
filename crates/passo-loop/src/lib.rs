//! Fixed-timestep loop (filled in below).
