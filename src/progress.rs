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
    /// A listener for one phase of a command (the scenes, the studies, a map, the ladder):
    /// the phase ends when the listener is dropped. By default nobody listens.
    fn phase(&self, _phase: &Phase) -> Box<dyn Progress + '_> {
        Box::new(Silent)
    }
}

/// One phase of a command's work, as a listener may show it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Phase {
    /// What is done ("solving the scenes").
    pub what: String,
    /// What is counted ("crank angles").
    pub unit: &'static str,
    /// How many units the phase has.
    pub total: u64,
    /// Below this many units the phase ends before it is worth showing.
    pub worth_showing: u64,
    /// Each unit takes long: a display may show the rate.
    pub slow_units: bool,
}

impl Phase {
    /// A phase of `total` units worth showing however short.
    pub fn new(what: impl Into<String>, unit: &'static str, total: u64) -> Phase {
        Phase {
            what: what.into(),
            unit,
            total,
            worth_showing: 0,
            slow_units: false,
        }
    }
}

/// Shows nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {}
