//! Statistics of the study: order-statistic quantiles and the Clopper–Pearson interval of a
//! failure rate.

/// The p-quantile of `sorted` (ascending, not empty): the order statistic of rank ⌈p·n⌉
/// (1-based, at least 1) — the inverse of the empirical distribution function (Hyndman and
/// Fan's definition 1). It is always a value some sample has, so it can be replayed.
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    let n = sorted.len();
    let rank = ((p * n as f64).ceil() as usize).clamp(1, n);
    sorted[rank - 1]
}

/// ln B(a, b) = ln Γ(a) + ln Γ(b) − ln Γ(a + b) (`libm::lgamma`).
fn ln_beta(a: f64, b: f64) -> f64 {
    libm::lgamma(a) + libm::lgamma(b) - libm::lgamma(a + b)
}

/// The regularized incomplete beta function I_x(a, b), a, b > 0, x in [0, 1]: the continued
/// fraction of Numerical Recipes (3rd ed., §6.4) by the modified Lentz method, on the side of
/// x where it converges fast (x < (a + 1)/(a + b + 2)), else through I_x(a, b) = 1 − I_{1−x}(b, a).
pub fn beta_regularized(a: f64, b: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    let front = (a * x.ln() + b * (-x).ln_1p() - ln_beta(a, b)).exp();
    if x < (a + 1.0) / (a + b + 2.0) {
        front * continued_fraction(a, b, x) / a
    } else {
        1.0 - front * continued_fraction(b, a, 1.0 - x) / b
    }
}

/// The continued fraction of I_x(a, b) (Numerical Recipes `betacf`); it needs O(√max(a, b))
/// terms, so 10⁵ terms suffice for a million samples.
fn continued_fraction(a: f64, b: f64, x: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let guard = |v: f64| if v.abs() < TINY { TINY } else { v };
    let mut c = 1.0;
    let mut d = 1.0 / guard(1.0 - qab * x / qap);
    let mut h = d;
    for m in 1..100_000 {
        let m = m as f64;
        let m2 = 2.0 * m;
        let aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 / guard(1.0 + aa * d);
        c = guard(1.0 + aa / c);
        h *= d * c;
        let aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 / guard(1.0 + aa * d);
        c = guard(1.0 + aa / c);
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < 1e-15 {
            break;
        }
    }
    h
}

/// The p at which the increasing function `f` of p in [0, 1] reaches `target`, by bisection
/// to the resolution of f64 (at most 200 halvings).
fn solve_increasing(f: impl Fn(f64) -> f64, target: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The Clopper–Pearson ("exact") two-sided interval of a binomial rate with `k` of `n` trials,
/// at confidence 1 − `alpha`: the lower bound is the p with P(X ≥ k | p) = α/2, i.e. the α/2
/// quantile of Beta(k, n − k + 1) (0 when k = 0); the upper bound the p with P(X ≤ k | p) =
/// α/2, the 1 − α/2 quantile of Beta(k + 1, n − k) (1 when k = n).
pub fn clopper_pearson(k: u64, n: u64, alpha: f64) -> (f64, f64) {
    let (kf, nf) = (k as f64, n as f64);
    let lower = if k == 0 {
        0.0
    } else {
        solve_increasing(|p| beta_regularized(kf, nf - kf + 1.0, p), alpha / 2.0)
    };
    let upper = if k >= n {
        1.0
    } else {
        solve_increasing(
            |p| beta_regularized(kf + 1.0, nf - kf, p),
            1.0 - alpha / 2.0,
        )
    };
    (lower, upper)
}
