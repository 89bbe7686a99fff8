//! Root of a monotone balance m(x) = target: bracket first, then safeguarded Newton.
//!
//! Used for the roller balance Σ F_i·l_i(β) = T and the pin balance Σ F_j·a_j(βo) = T, both
//! non-decreasing in their lag (more lag closes more contacts harder). The bracket makes the
//! iteration unable to diverge; Newton steps that leave it, or stall, fall back to bisection.

/// One evaluation of the balance: value, slope ∂m/∂x (may be 0 on flat parts), a scale for
/// relative convergence (e.g. Σ|F·l|) and the value's resolution: a bound on its round-off,
/// absolute (0 when unknown: the value is then taken as exact).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balance {
    pub value: f64,
    pub slope: f64,
    pub scale: f64,
    pub resolution: f64,
}

/// Converged root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    pub x: f64,
    pub residual: f64,
    /// The other end of a one-ulp bracket across which the balance steps over the target by
    /// no more than its round-off (`monotone_root`): no double meets the tolerance, and the
    /// caller mixes its states at `x` and near this end (`settle_straddle`). `residual` is
    /// then that of the mix as the solver saw it.
    pub straddle: Option<f64>,
    /// The balance's slope ∂m/∂x at x as the solver last evaluated it (a caller's guess at a
    /// nearby target, `Work::guess_at_torque`).
    pub slope: f64,
}

use crate::geometry::clearance::GapFailure;
use crate::numeric::input;
use crate::units;

/// Why a solve stopped without a root. A status, not a panic: the caller names scene and angle.
#[derive(Debug, Clone, PartialEq)]
pub enum SolveFailure {
    /// No sign change found within the search range. `nearest` is the evaluation (x, value)
    /// that came nearest the target, when there was one.
    NoBracket {
        lo: f64,
        hi: f64,
        nearest: Option<(f64, f64)>,
    },
    /// Iterations exhausted; the best residual reached.
    NotConverged { x: f64, residual: f64 },
    /// A roller's closest point could not be found: the roller and the pose.
    Gap(GapFailure),
    /// The rollers' moment never reached the torque (N·mm): the largest moment found (N·mm),
    /// at that lag (rad), and the deepest roller there (index, depth mm, roller radius mm).
    BeyondCapacity {
        torque_nmm: f64,
        moment_nmm: f64,
        lag_rad: f64,
        deepest: Option<(usize, f64, f64)>,
    },
    /// Self-locking: with friction in the balance, the rollers' coupled moment never reached
    /// the output torque (N·mm) because the friction moment against the disc's turn (N·mm, in
    /// the torque's direction: rollers, pins and crank bearing) took the whole normal forces'
    /// moment (N·mm), or all of it the torque did not need, at that lag (rad).
    SelfLocking {
        torque_nmm: f64,
        friction_moment_nmm: f64,
        normal_moment_nmm: f64,
        lag_rad: f64,
    },
    /// No roller touches the disc in the direction of the torque (N·mm) at any lag within
    /// `range_rad` of the ideal pose: the disc turns freely further than the search reaches
    /// (its clearance is large against its moment arms), so no balance can be found.
    NoContact { torque_nmm: f64, range_rad: f64 },
    /// A compliant crank bearing (N/mm) so soft under the torque (N·mm) that the disc centre
    /// moved (mm) more than the eccentricity (mm), still out of balance by a force (N).
    OutOfMesh {
        bearing_n_per_mm: f64,
        torque_nmm: f64,
        offset_mm: f64,
        unbalanced_n: f64,
        eccentricity_mm: f64,
    },
    /// The balance could not be evaluated, for a reason given by a caller's own evaluation.
    Evaluation(String),
    /// A non-finite value appeared.
    NonFinite { x: f64 },
    /// The solve of disc `disc` (0-based, as the results count discs) of `discs`, alone at
    /// its own crank angle `crank_rad` (the reducer's plus its phase) and its share of the
    /// output torque, failed: the coupled solve of several discs names the disc.
    Disc {
        disc: usize,
        discs: usize,
        crank_rad: f64,
        failure: Box<SolveFailure>,
    },
}

impl SolveFailure {
    /// The failure itself, without the disc that names where it happened.
    pub fn cause(&self) -> &SolveFailure {
        match self {
            SolveFailure::Disc { failure, .. } => failure.cause(),
            other => other,
        }
    }
}

impl From<GapFailure> for SolveFailure {
    fn from(f: GapFailure) -> Self {
        SolveFailure::Gap(f)
    }
}

impl From<String> for SolveFailure {
    fn from(message: String) -> Self {
        SolveFailure::Evaluation(message)
    }
}

impl std::fmt::Display for SolveFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolveFailure::NoBracket { lo, hi, nearest } => {
                write!(
                    f,
                    "no balance found for a lag between {lo:.3e} and {hi:.3e} rad"
                )?;
                match nearest {
                    Some((x, value)) => write!(
                        f,
                        " (the nearest the balance came is {value:.4e} N·mm, at lag {x:.3e} rad)"
                    ),
                    None => Ok(()),
                }
            }
            SolveFailure::NotConverged { x, residual } => write!(
                f,
                "did not converge (lag {x:.6e} rad, relative residual {residual:.2e})"
            ),
            SolveFailure::Gap(g) => write!(f, "{g}"),
            SolveFailure::BeyondCapacity {
                torque_nmm,
                moment_nmm,
                lag_rad,
                deepest,
            } => {
                write!(
                    f,
                    "the rollers cannot balance an output torque of {} N·m: the largest moment \
                     found is {:.4} N·m, at a lag of {lag_rad:.4} rad",
                    input(units::nm(*torque_nmm)),
                    units::nm(*moment_nmm)
                )?;
                if let Some((i, depth, radius)) = deepest {
                    write!(
                        f,
                        "; there roller {i} is pressed {depth:.3} mm into the disc (roller \
                         radius {radius} mm)"
                    )?;
                }
                write!(
                    f,
                    "; the load is beyond what this disc can hold in the contact model"
                )
            }
            SolveFailure::SelfLocking {
                torque_nmm,
                friction_moment_nmm,
                normal_moment_nmm,
                lag_rad,
            } => write!(
                f,
                "self-locking: friction holds the disc against an output torque of {} N·m: no \
                 lag turns the rollers' moment towards it, the friction moment against the \
                 disc's turn (rollers, pins and crank bearing) growing with the load as fast as \
                 the normal forces' moment; nearest, at a lag of {lag_rad:.4} rad, the friction \
                 moment is {} N·m against the normal forces' {} N·m. Lower μ",
                input(units::nm(*torque_nmm)),
                crate::numeric::number(units::nm(*friction_moment_nmm)),
                crate::numeric::number(units::nm(*normal_moment_nmm)),
            ),
            SolveFailure::NoContact {
                torque_nmm,
                range_rad,
            } => write!(
                f,
                "no roller touches the disc in the direction of an output torque of {} N·m at \
                 any lag within {range_rad} rad ({:.1}°) of the ideal pose: the disc turns \
                 freely further than the model searches, its clearance too large for its \
                 moment arms, and carries no torque there",
                input(units::nm(*torque_nmm)),
                units::deg(*range_rad)
            ),
            SolveFailure::OutOfMesh {
                bearing_n_per_mm,
                torque_nmm,
                offset_mm,
                unbalanced_n,
                eccentricity_mm,
            } => write!(
                f,
                "the crank bearing of {} N/mm cannot hold the disc at {} N·m: its centre has \
                 moved by {offset_mm:.3} mm (still {unbalanced_n:.0} N out of balance), more than \
                 the eccentricity {} mm, and the disc would leave its mesh; the bearing is too \
                 soft for this torque",
                input(*bearing_n_per_mm),
                input(units::nm(*torque_nmm)),
                input(*eccentricity_mm)
            ),
            SolveFailure::Evaluation(msg) => write!(f, "{msg}"),
            SolveFailure::NonFinite { x } => write!(f, "non-finite value at lag {x:.6e} rad"),
            SolveFailure::Disc {
                disc,
                discs,
                crank_rad,
                failure,
            } => write!(
                f,
                "disc {disc} of {discs}, at its own crank angle {:.4}° and its share of the \
                 output torque: {failure}",
                units::deg(*crank_rad).rem_euclid(360.0)
            ),
        }
    }
}

/// Settings of a monotone solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Converged when |m − target| ≤ rel_tol · max(|target|, scale). The default 1e-11 is 100×
    /// inside the product bound (1e-9) and above the ~1e-12 round-off of exact moment arms.
    pub rel_tol: f64,
    /// First bracketing step; doubled until the target is enclosed.
    pub initial_step: f64,
    /// The bracket search gives up beyond this distance from the guess and from 0, having
    /// evaluated the range's end (`within_range`).
    pub max_range: f64,
    pub max_iterations: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            rel_tol: 1e-11,
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

/// Solve m(x) = target for non-decreasing m, starting at `guess`. The last evaluation of m
/// is always at the returned x, so a caller whose m writes states holds those of the answer.
///
/// Newton steps from the guess while they stay inside the bracket known so far (every
/// evaluation tightens it: below the target is a lower end, above an upper end). A step that
/// would leave the bracket, or a flat part (slope 0), expands the bracket by doubling steps
/// while it is one-sided and bisects once it is closed. From a warm start this costs 2–4
/// evaluations; it can never diverge.
///
/// A balance is a staircase at the scale of its round-off: at a tiny target (1e-6 N·m on
/// gaps of 0.03 mm) one ulp of a gap moves the value by more than the 1e-9 tolerance, and no
/// double x meets it. When the bracket has shrunk to adjacent doubles and the step of the
/// value across it is within the two ends' `resolution` (plus the slope over one ulp), the
/// root is returned with `straddle` set to the other end. A larger step is a real jump of the
/// balance and stays `NotConverged`.
// Inlined into its callers: when the compiler chose otherwise (a build whose only changes were
// elsewhere, 2026-11-30) a rated 3,600-angle `check` took 0.96 % more instructions (59.95 M
// against 59.38 M, callgrind, one thread): the rigid bearing's solve calls it at every angle.
#[inline]
pub fn monotone_root<E: Into<SolveFailure>>(
    mut m: impl FnMut(f64) -> Result<Balance, E>,
    target: f64,
    guess: f64,
    settings: &Settings,
) -> Result<Root, SolveFailure> {
    let mut eval = |x: f64| -> Result<Balance, SolveFailure> {
        let b = m(x).map_err(Into::into)?;
        if b.value.is_finite() && b.slope.is_finite() && b.scale.is_finite() {
            Ok(b)
        } else {
            Err(SolveFailure::NonFinite { x })
        }
    };
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut at_lo, mut at_hi) = (None::<Balance>, None::<Balance>);
    let mut step = 16.0 * settings.initial_step;
    let mut x = guess;
    let mut last_residual = f64::INFINITY;
    let mut last_miss = f64::INFINITY;
    let mut nearest: Option<(f64, f64)> = None;
    // Whether x is an end of the search range that a march stepped onto (`within_range`).
    let mut at_end = false;
    for _ in 0..settings.max_iterations {
        let b = match eval(x) {
            Ok(b) => b,
            // The range's end is an extra point beyond the march's own steps: where the balance
            // cannot be evaluated there, the search ends as it would without it.
            Err(_) if at_end => return Err(SolveFailure::NoBracket { lo, hi, nearest }),
            Err(e) => return Err(e),
        };
        let residual = relative(&b, target);
        if nearest.is_none_or(|(_, v)| nearer(b.value, v, target)) {
            nearest = Some((x, b.value));
        }
        // Newton that fails to halve the miss |m − target| (a kink where a contact opens or
        // closes) gives way to bisection once the bracket is closed. The miss is absolute: a
        // relative residual is scaled by the moment of the point itself, and stays near 1 at
        // every point far above a tiny target (1e-100 N·m), so Newton, exact on a linear
        // segment, would never be taken again.
        let miss = (b.value - target).abs();
        let stalled = miss > 0.5 * last_miss;
        last_miss = miss;
        last_residual = residual;
        // At a zero target a value within its round-off is zero: the relative residual of
        // forces that are themselves round-off (an unmodified profile touching every roller at
        // zero torque) is 1 at any x.
        let zero = target == 0.0 && b.value.abs() <= b.resolution;
        let found = Root {
            x,
            residual,
            straddle: None,
            slope: b.slope,
        };
        if residual <= settings.rel_tol || zero {
            return Ok(found);
        }
        if b.value < target {
            lo = x;
            at_lo = Some(b);
        } else {
            hi = x;
            at_hi = Some(b);
        }
        let newton = (b.slope > 0.0).then(|| x - (b.value - target) / b.slope);
        let next = if let (Some(a), Some(c)) = (at_lo.filter(|_| lo.is_finite()), at_hi) {
            // Newton, else the secant through the bracket's ends, else bisection. The secant
            // lo + (target − m_lo)·(hi − lo)/(m_hi − m_lo) has no cancellation where Newton's
            // x − (m − target)/slope has: far above a tiny target (1e-100 N·m) the two terms of
            // Newton's step agree to round-off and its answer is noise, while the secant from
            // an unloaded lo is the exact root of a balance linear in the lag.
            let secant = lo + (target - a.value) * ((hi - lo) / (c.value - a.value));
            match newton {
                _ if stalled => 0.5 * (lo + hi),
                Some(n) if n > lo && n < hi => n,
                _ if secant > lo && secant < hi => secant,
                _ => 0.5 * (lo + hi),
            }
        } else {
            // One-sided: Newton within a trust step that doubles whenever it binds, so a
            // wild Newton step (steep or flat parts) becomes a march outwards.
            let toward = if lo.is_finite() { 1.0 } else { -1.0 };
            let wanted = newton.map_or(toward * f64::INFINITY, |n| n - x);
            if wanted.abs() > step || wanted * toward <= 0.0 {
                let move_by = toward * step;
                step *= 2.0;
                x + move_by
            } else {
                x + wanted
            }
        };
        let Some(stepped) = within_range(next, x, guess, settings.max_range) else {
            return Err(SolveFailure::NoBracket { lo, hi, nearest });
        };
        at_end = stepped != next;
        let next = stepped;
        if next <= lo || next >= hi || next == x {
            // The bracket is one ulp wide: this is as close as f64 gets. A step of the value
            // across it within round-off is straddled; otherwise accept x only within the
            // product's residual bound (1e-9 relative), or say so.
            if let (Some(a), Some(b)) = (at_lo, at_hi) {
                let jump = b.value - a.value;
                let noise = a.resolution + b.resolution + a.slope.max(b.slope) * (hi - lo);
                if jump > 0.0 && jump <= noise {
                    let weight = ((target - a.value) / jump).clamp(0.0, 1.0);
                    let blend = Balance {
                        value: a.value + weight * jump,
                        scale: a.scale.max(b.scale),
                        ..b
                    };
                    return Ok(Root {
                        x,
                        residual: relative(&blend, target),
                        straddle: Some(if x == lo { hi } else { lo }),
                        slope: blend.slope,
                    });
                }
            }
            return if residual <= 1e-9 {
                Ok(found)
            } else {
                Err(SolveFailure::NotConverged { x, residual })
            };
        }
        x = next;
    }
    Err(SolveFailure::NotConverged {
        x,
        residual: last_residual,
    })
}

/// Whether the value `a` is nearer `target` than `b`. On one side of the target by their order,
/// not by the differences: far below a huge target (1e300 N·m against moments of 1e5) every
/// difference rounds to the target itself, and the largest moment found would be lost.
fn nearer(a: f64, b: f64, target: f64) -> bool {
    match (a < target, b < target) {
        (true, true) => a > b,
        (false, false) => a < b,
        _ => (a - target).abs() < (b - target).abs(),
    }
}

/// The next point of a bracket search from x, or `None` when x already ends the range: the
/// range is `max_range` about the guess and about x = 0, the ideal pose every lag is measured
/// from, so that a warm start on the far side of a dead band (a torsion loop that reverses
/// the torque on a 3-roller disc crosses 0.21 rad of backlash) still reaches the root beyond
/// it. A march that would step past an end evaluates the end itself: the doubling steps
/// (1.6e-4·(2ⁿ − 1) rad) would otherwise give up at 0.164 rad of a 0.3 rad range.
fn within_range(next: f64, x: f64, guess: f64, max_range: f64) -> Option<f64> {
    let (first, last) = (guess.min(0.0) - max_range, guess.max(0.0) + max_range);
    if next < first {
        (x > first).then_some(first)
    } else if next > last {
        (x < last).then_some(last)
    } else {
        Some(next)
    }
}

/// The weights of two states mixed to balance exactly (`settle_straddle`), each formed from the
/// values directly: one of them can be far below ε (1e-88 at 1e-100 N·m), and as 1 − the
/// other it would round to nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    pub x: f64,
    pub y: f64,
}

/// Settle a straddled root (`Root::straddle`): the caller holds its states at `x`, where the
/// balance is `value_x`; `evaluate(y)` evaluates the balance at y into scratch states and
/// returns its value. Round-off depends on the path (a closest point found from another warm
/// start differs in its last bits), so the pair is re-established here: y moves away from x,
/// starting at the bracket's width |towards − x| and doubling, until m(y) lies on the other
/// side of the target, at most 1e-9·max(1, |x|) away. Returns y and the weights with
/// w_x·value_x + w_y·m(y) = target: the states mixed so balance exactly, and the root lies
/// between x and y (a few ulp apart).
pub fn settle_straddle(
    x: f64,
    towards: f64,
    value_x: f64,
    target: f64,
    mut evaluate: impl FnMut(f64) -> Result<f64, SolveFailure>,
) -> Result<(f64, Weights), SolveFailure> {
    if value_x == target {
        return Ok((x, Weights { x: 1.0, y: 0.0 }));
    }
    // m is non-decreasing: below the target the other side lies at larger x.
    let below = value_x < target;
    let step = (towards - x)
        .abs()
        .max(f64::EPSILON * x.abs())
        .max(f64::MIN_POSITIVE);
    let mut distance = if below { step } else { -step };
    // Up to 1e-9 of max(1, |x|) away: far below any physical scale of the lag, and enough
    // doublings to cross zero from a root at round-off distance from it (zero torque on an
    // unmodified profile puts the root at |x| ~ 1e-27).
    while distance.abs() <= 1e-9 * x.abs().max(1.0) {
        let y = x + distance;
        let value_y = evaluate(y)?;
        let crossed = if below {
            value_y >= target
        } else {
            value_y <= target
        };
        if crossed {
            let span = value_y - value_x;
            let weights = Weights {
                x: (value_y - target) / span,
                y: (target - value_x) / span,
            };
            return Ok((y, weights));
        }
        distance *= 2.0;
    }
    Err(SolveFailure::NotConverged {
        x,
        residual: (value_x - target).abs() / target.abs().max(value_x.abs()),
    })
}

/// |x| relative to `scale` (|x| itself when the scale is 0: nothing to compare with).
pub(super) fn rel(x: f64, scale: f64) -> f64 {
    if scale > 0.0 {
        x.abs() / scale
    } else {
        x.abs()
    }
}

/// Exact root of the first-order linear balance
///   M(x) = Σ_i k·max(0, l_i·x − g_i)·l_i = target,
/// a continuous, non-decreasing, piecewise-linear function of the lag x (each term is a contact
/// of gap g_i at x = 0 and arm l_i that closes at the breakpoint x = g_i/l_i). The breakpoints
/// are swept in order, tracking M = A·x − B on each segment. At zero target with a plateau
/// (clearance, no preload) the answer is its upper end, the limit target → 0⁺.
/// `None` when the target is never reached (no arm of the needed sign).
/// `events` is scratch space: (breakpoint, change of A, change of B).
///
/// Started from a guess (the previous crank angle's root): a few Newton steps on the segment
/// of the guess, each exact on its segment; when one lands on the segment it was computed
/// from, that is the root. Otherwise (or at zero target, or without a guess: NaN) the
/// breakpoint sweep decides.
pub fn piecewise_linear_root_near(
    k: f64,
    terms: &[(f64, f64)],
    target: f64,
    guess: f64,
    events: &mut Vec<(f64, f64, f64)>,
) -> Option<f64> {
    if guess.is_finite() && target != 0.0 {
        if let Some(root) = newton_on_segments(k, terms, target, guess) {
            return Some(root);
        }
    }
    sweep_breakpoints(k, terms, target, events)
}

/// Up to four Newton steps of `piecewise_linear_root_near` from x = `guess`. The active set
/// (terms with l·x > g) of each point is kept as a bit mask, so a step is one pass over the
/// terms: the step to x' = (target + B)/A, with A = Σ k·l² and B = Σ k·l·g over the active set
/// at x, is the root when the active set at x' is the same.
fn newton_on_segments(k: f64, terms: &[(f64, f64)], target: f64, guess: f64) -> Option<f64> {
    if terms.len() > 128 {
        return None;
    }
    let active = |x: f64| {
        let (mut mask, mut a, mut b) = (0u128, 0.0, 0.0);
        for (i, &(g, l)) in terms.iter().enumerate() {
            if l != 0.0 && l * x > g {
                mask |= 1 << i;
                a += k * l * l;
                b += k * l * g;
            }
        }
        (mask, a, b)
    };
    let (mut mask, mut a, mut b) = active(guess);
    for _ in 0..4 {
        if a <= 0.0 {
            return None;
        }
        let next = (target + b) / a;
        let at_next = active(next);
        if at_next.0 == mask {
            return Some(next);
        }
        (mask, a, b) = at_next;
    }
    None
}

fn sweep_breakpoints(
    k: f64,
    terms: &[(f64, f64)],
    target: f64,
    events: &mut Vec<(f64, f64, f64)>,
) -> Option<f64> {
    events.clear();
    let (mut a, mut b) = (0.0, 0.0);
    // Terms in contact by the sign of their arm. Where none is, the running sums are reset to
    // the exact zero: their round-off after a cancellation (~1e-7 of sums ~1e9) would be taken
    // for a slope. A segment where only negative arms touch has M ≤ 0 and holds no root of a
    // positive target (and vice versa): its affine root lies past its end by t/(k·l²), which
    // rounds to the end itself at a tiny target (1e-97 N·mm).
    let (mut positive, mut negative) = (0usize, 0usize);
    let (mut plateau_lo, mut plateau_hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for &(g, l) in terms {
        if l == 0.0 {
            continue;
        }
        let (x, da, db) = (g / l, k * l * l, k * l * g);
        if l > 0.0 {
            // Closes as x grows past its breakpoint.
            events.push((x, da, db));
            plateau_hi = plateau_hi.min(x);
        } else {
            // In contact for x below its breakpoint, so already at x → −∞.
            a += da;
            b += db;
            negative += 1;
            events.push((x, -da, -db));
            plateau_lo = plateau_lo.max(x);
        }
    }
    if target == 0.0 && plateau_lo <= plateau_hi && plateau_hi.is_finite() {
        return Some(plateau_hi);
    }
    let reachable = |positive: usize, negative: usize| {
        (target >= 0.0 || negative > 0) && (target <= 0.0 || positive > 0)
    };
    events.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
    for &(x_end, da, db) in events.iter() {
        if a > 0.0 && reachable(positive, negative) {
            let root = (target + b) / a;
            if root <= x_end {
                return Some(root);
            }
        }
        (a, b) = (a + da, b + db);
        if da > 0.0 {
            positive += 1;
        } else {
            negative -= 1;
        }
        if positive + negative == 0 {
            (a, b) = (0.0, 0.0);
        }
    }
    (a > 0.0 && reachable(positive, negative)).then(|| (target + b) / a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A disc on the line of centres: rollers in symmetric pairs (g, ±l), clear at lag 0.
    /// A positive torque, however tiny, is carried by the positive arms once they close at
    /// x = g/l (the limit T → 0⁺ of the root (T + k·l·g)/(k·l²)); M ≤ 0 below it. Running
    /// sums over the breakpoints would keep ~1e-7 of round-off after the negative arms open,
    /// and put the root of 1e-97 N·mm at 1e-97/1e-7 inside the clearance plateau.
    #[test]
    fn a_tiny_target_closes_the_first_positive_arm() {
        let k = 7.111737215818652e5;
        let pairs = [(0.0641, 17.4943), (0.0616, 16.8481), (0.0487, 12.5642)];
        let terms: Vec<(f64, f64)> = pairs.iter().flat_map(|&(g, l)| [(g, l), (g, -l)]).collect();
        let closes = pairs
            .iter()
            .map(|(g, l)| g / l)
            .fold(f64::INFINITY, f64::min);
        for target in [1e-3, 1e-97, 1e-297] {
            let x =
                piecewise_linear_root_near(k, &terms, target, f64::NAN, &mut Vec::new()).unwrap();
            // The root sits on the first closing breakpoint to within one ulp of it plus
            // the approach T/(k·l²) it needs (below 1e-10 rad at 1e-3 N·mm).
            assert!(
                x >= closes * (1.0 - 1e-15),
                "{target:e}: {x:e} < {closes:e}"
            );
            assert!(x <= closes + 1e-10, "{target:e}: {x:e}");
            let below =
                piecewise_linear_root_near(k, &terms, -target, f64::NAN, &mut Vec::new()).unwrap();
            assert!(below <= -closes * (1.0 - 1e-15), "{target:e}: {below:e}");
        }
    }
}
