//! The engine's progress, heard by a Python callable `progress(fraction, phase)`: each phase of
//! a command counts its units; the callable is called with the phase's fraction done and its
//! name at most every [`INTERVAL`] (the GIL taken only then), the end of a phase (1.0)
//! included. An exception it raises stops nothing (the engine cannot be
//! interrupted) but is raised once the run is over.

use cycloid::progress::{Phase, Progress};
use pyo3::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// The shortest time between two calls of the callable.
pub(crate) const INTERVAL: Duration = Duration::from_millis(250);

/// The listener of one run; silent without a callable.
pub(crate) struct Sink {
    callback: Option<Py<PyAny>>,
    /// When a call was last found due, before taking the GIL.
    looked: Mutex<Option<Instant>>,
    /// When the callable was last called (the GIL held).
    last: Mutex<Option<Instant>>,
    /// The first exception the callable raised.
    error: Mutex<Option<PyErr>>,
}

impl Sink {
    pub(crate) fn new(callback: Option<Py<PyAny>>) -> Sink {
        Sink {
            callback,
            looked: Mutex::new(None),
            last: Mutex::new(None),
            error: Mutex::new(None),
        }
    }

    /// Call the callable with (`fraction`, `what`) unless it was called less than
    /// [`INTERVAL`] ago: a cheap look without the GIL, then again once it is held (a thread
    /// may wait for the GIL while another calls), so that the calls themselves are spaced.
    fn report(&self, fraction: f64, what: &str) {
        let Some(callback) = &self.callback else {
            return;
        };
        let due = |last: &Mutex<Option<Instant>>| {
            let mut last = last.lock().unwrap_or_else(|p| p.into_inner());
            let now = Instant::now();
            if last.is_some_and(|t| now.duration_since(t) < INTERVAL) {
                return false;
            }
            *last = Some(now);
            true
        };
        if !due(&self.looked) {
            return;
        }
        Python::attach(|py| {
            if !due(&self.last) {
                return;
            }
            if let Err(e) = callback.call1(py, (fraction.clamp(0.0, 1.0), what)) {
                let mut error = self.error.lock().unwrap_or_else(|p| p.into_inner());
                error.get_or_insert(e);
            }
        });
    }

    /// After the run: the callable's first exception, if it raised one.
    pub(crate) fn finish(self, _py: Python<'_>) -> PyResult<()> {
        match self.error.into_inner().unwrap_or_else(|p| p.into_inner()) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl Progress for Sink {
    fn phase(&self, phase: &Phase) -> Box<dyn Progress + '_> {
        Box::new(PhaseSink {
            sink: self,
            what: phase.what.clone(),
            total: phase.total.max(1),
            done: AtomicU64::new(0),
        })
    }
}

/// One phase's count.
struct PhaseSink<'a> {
    sink: &'a Sink,
    what: String,
    total: u64,
    done: AtomicU64,
}

impl Progress for PhaseSink<'_> {
    fn advance(&self, n: u64) {
        let done = self.done.fetch_add(n, Ordering::Relaxed) + n;
        self.sink
            .report(done as f64 / self.total as f64, &self.what);
    }

    fn phase(&self, phase: &Phase) -> Box<dyn Progress + '_> {
        self.sink.phase(phase)
    }
}

impl Drop for PhaseSink<'_> {
    fn drop(&mut self) {
        self.sink.report(1.0, &self.what);
    }
}
