//! Quasi-static equilibrium of the disc.
