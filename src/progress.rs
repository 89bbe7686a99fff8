//! Progress of long work, as an observer: the sweeps and the engine say how much is done
//! (crank angles of a large scene, ladder rungs, map cells, optimiser evaluations); whoever
//! listens decides how to show it (the command line draws a bar on a terminal and nothing
//! otherwise). At the bottom of the layers so that the geometry and equilibrium sweeps can
//! report without knowing who listens.

/// Hears of work as it is done. Called from worker threads.
pub trait Progress: Sync {
    /// `n` more units are done.
    fn advance(&self, _n: u64) {}
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

    /// A phase like `new` whose units each take long (a design, a sample): a display may
    /// show the rate.
    pub fn slow(what: impl Into<String>, unit: &'static str, total: u64) -> Phase {
        Phase {
            slow_units: true,
            ..Phase::new(what, unit, total)
        }
    }
}

/// Forwards to `inner` the units a piece of work reports, and on `close` the rest of the
/// `budget` it did not use, so that work whose count is only bounded beforehand (an optimiser
/// stops before its budget) still ends its listener's count at 100 %.
pub struct Budget<'a> {
    inner: &'a dyn Progress,
    budget: u64,
    done: std::sync::atomic::AtomicU64,
}

impl<'a> Budget<'a> {
    /// A budget of `budget` units on `inner`.
    pub fn new(inner: &'a dyn Progress, budget: u64) -> Budget<'a> {
        Budget {
            inner,
            budget,
            done: std::sync::atomic::AtomicU64::new(0),
        }
    }

    /// The work is done: the units of the budget it did not report count as done.
    pub fn close(&self) {
        let done = self.done.load(std::sync::atomic::Ordering::Relaxed);
        if done < self.budget {
            self.inner.advance(self.budget - done);
        }
    }
}

impl Progress for Budget<'_> {
    fn advance(&self, n: u64) {
        self.done.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
        self.inner.advance(n);
    }
}

/// Shows nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {}
