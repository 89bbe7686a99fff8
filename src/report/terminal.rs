//! Progress on a terminal: a bar on stderr while stdout is a terminal, nothing otherwise (a
//! pipe, a file, a CI log), so that what a script reads from stdout never carries it and a
//! log stays clean. The engine and the sweeps report through `crate::progress::Progress`.

use crate::progress::{Phase, Progress};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar of one phase (`Terminal::phase`).
pub struct Bar {
    bar: ProgressBar,
}

impl Progress for Bar {
    fn advance(&self, n: u64) {
        self.bar.inc(n);
    }
}

/// The command line's listener: each phase of a command gets its own bar (`Bar`), drawn only
/// while stdout is a terminal.
#[derive(Debug, Clone, Copy, Default)]
pub struct Terminal;

impl Progress for Terminal {
    /// The phase's bar, drawn only when stdout is a terminal and the phase is worth showing;
    /// with the units per second for work whose units take long each.
    fn phase(&self, p: &Phase) -> Box<dyn Progress + '_> {
        let shown = std::io::stdout().is_terminal() && p.total >= p.worth_showing;
        let bar = ProgressBar::with_draw_target(
            Some(p.total),
            if shown {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            },
        );
        let unit = p.unit;
        let rate = if p.slow_units { ", {per_sec}" } else { "" };
        let template =
            format!("{{msg}} [{{bar:30}}] {{human_pos}}/{{human_len}} {unit}{rate}, {{eta}} left");
        bar.set_style(
            ProgressStyle::with_template(&template)
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        bar.set_message(p.what.clone());
        Box::new(Bar { bar })
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
