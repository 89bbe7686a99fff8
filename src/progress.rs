//! Progress of long work, as an observer: the sweeps and the engine say how much is done
//! (crank angles of a large scene, ladder rungs, map cells, optimiser evaluations); whoever
//! listens decides how to show it (the command line draws a bar on a terminal and nothing
//! otherwise). At the bottom of the layers so that the geometry and equilibrium sweeps can
//! report without knowing who listens.

/// Hears of work as it is done. Called from worker threads.
pub trait Progress: Sync {
    /// `total` units of work are about to start, described by `what`.
    fn start(&self, _what: &str, _total: u64) {}
    /// `n` more units are done.
    fn advance(&self, _n: u64) {}
    /// The work described last is done.
    fn finish(&self) {}
}

/// Shows nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {}
