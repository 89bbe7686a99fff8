//! Root of a monotone balance m(x) = target: bracket first, then safeguarded Newton.
//!
//! Used for the roller balance Σ F_i·l_i(β) = T and the pin balance Σ F_j·a_j(βo) = T, both
//! non-decreasing in their lag (more lag closes more contacts harder). The bracket makes the
//! iteration unable to diverge; Newton steps that leave it, or stall, fall back to bisection.

/// One evaluation of the balance: value, slope ∂m/∂x (may be 0 on flat parts) and a scale for
/// relative convergence (e.g. Σ|F·l|).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balance {
    pub value: f64,
    pub slope: f64,
    pub scale: f64,
}

/// Converged root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    pub x: f64,
    pub residual: f64,
    pub iterations: usize,
}

/// Why a solve stopped without a root. A status, not a panic: the caller names scene and angle.
#[derive(Debug, Clone, PartialEq)]
pub enum SolveFailure {
    /// No sign change found within the search range.
    NoBracket { lo: f64, hi: f64 },
    /// Iterations exhausted; the best residual reached.
    NotConverged { x: f64, residual: f64 },
    /// The balance itself could not be evaluated (e.g. a closest point failed).
    Evaluation(String),
    /// A non-finite value appeared.
    NonFinite { x: f64 },
}

impl std::fmt::Display for SolveFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolveFailure::NoBracket { lo, hi } => {
                write!(
                    f,
                    "no balance found for a lag between {lo:.3e} and {hi:.3e} rad"
                )
            }
            SolveFailure::NotConverged { x, residual } => write!(
                f,
                "did not converge (lag {x:.6e} rad, relative residual {residual:.2e})"
            ),
            SolveFailure::Evaluation(msg) => write!(f, "{msg}"),
            SolveFailure::NonFinite { x } => write!(f, "non-finite value at lag {x:.6e} rad"),
        }
    }
}

/// Settings of a monotone solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Converged when |m − target| ≤ rel_tol · max(|target|, scale).
    pub rel_tol: f64,
    /// First bracketing step; doubled until the target is enclosed.
    pub initial_step: f64,
    /// The bracket search gives up beyond this distance from the guess.
    pub max_range: f64,
    pub max_iterations: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            rel_tol: 1e-12,
            initial_step: 1e-5,
            max_range: 0.3,
            max_iterations: 200,
        }
    }
}

fn relative(b: &Balance, target: f64) -> f64 {
    let scale = target.abs().max(b.scale);
    if scale == 0.0 {
        0.0
    } else {
        (b.value - target).abs() / scale
    }
}

/// Solve m(x) = target for non-decreasing m, starting at `guess`.
pub fn monotone_root<E: std::fmt::Display>(
    mut m: impl FnMut(f64) -> Result<Balance, E>,
    target: f64,
    guess: f64,
    settings: &Settings,
) -> Result<Root, SolveFailure> {
    let mut eval = |x: f64| -> Result<Balance, SolveFailure> {
        let b = m(x).map_err(|e| SolveFailure::Evaluation(e.to_string()))?;
        if b.value.is_finite() && b.slope.is_finite() && b.scale.is_finite() {
            Ok(b)
        } else {
            Err(SolveFailure::NonFinite { x })
        }
    };
    let mut calls = 1;
    let first = eval(guess)?;
    if relative(&first, target) <= settings.rel_tol {
        return Ok(Root {
            x: guess,
            residual: relative(&first, target),
            iterations: calls,
        });
    }
    // Bracket: step from the guess in the direction that moves m towards the target.
    let up = first.value < target;
    let (mut lo, mut hi) = (guess, guess);
    let (mut b_lo, mut b_hi) = (first, first);
    let mut step = settings.initial_step;
    loop {
        let x = if up { hi + step } else { lo - step };
        let b = eval(x)?;
        calls += 1;
        if up {
            (lo, b_lo) = (hi, b_hi);
            (hi, b_hi) = (x, b);
            if b.value >= target {
                break;
            }
        } else {
            (hi, b_hi) = (lo, b_lo);
            (lo, b_lo) = (x, b);
            if b.value <= target {
                break;
            }
        }
        step *= 2.0;
        if (x - guess).abs() > settings.max_range {
            return Err(SolveFailure::NoBracket { lo, hi });
        }
    }
    // Safeguarded Newton inside [lo, hi], from the end nearer the target.
    let (mut x, mut b) = if (b_lo.value - target).abs() < (b_hi.value - target).abs() {
        (lo, b_lo)
    } else {
        (hi, b_hi)
    };
    for _ in 0..settings.max_iterations {
        let residual = relative(&b, target);
        if residual <= settings.rel_tol {
            return Ok(Root {
                x,
                residual,
                iterations: calls,
            });
        }
        let newton = x - (b.value - target) / b.slope;
        let mid = 0.5 * (lo + hi);
        let next = if b.slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            mid
        };
        if next <= lo || next >= hi {
            // The bracket is one ulp wide: this is as close as f64 gets. Accept it only within
            // the product's residual bound (1e-9 relative); otherwise say so.
            return if residual <= 1e-9 {
                Ok(Root {
                    x,
                    residual,
                    iterations: calls,
                })
            } else {
                Err(SolveFailure::NotConverged { x, residual })
            };
        }
        x = next;
        b = eval(x)?;
        calls += 1;
        if b.value < target {
            lo = x;
        } else {
            hi = x;
        }
    }
    Err(SolveFailure::NotConverged {
        x,
        residual: relative(&b, target),
    })
}
