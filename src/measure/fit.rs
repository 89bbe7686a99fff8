//! Identification of a measured disc: the centre, orientation, modifications and form error of
//! the disc that measured points lie on, by Gauss–Newton on their normal distances to the
//! modified profile (MODEL.md "Measured profiles").
//!
//! Model. A point P_m measured in the machine's frame is turned into the disc frame,
//! Q_m = R(−θ0)·(P_m − c0), and its foot t_m on the roller-centre locus C (of R' = Rp + ΔRp,
//! turned by Δδ) is found by the guarded closest-point search of [`geometry::profile`](crate::geometry::profile). Its
//! residual is the signed normal distance to the profile with form error w,
//!   d_m = (Q_m − C(t_m))·N(t_m) + r' + w(t_m),   r' = Rrp + ΔRrp,
//! positive outside the material (Γ = C − (r' + w)·N: w > 0 is material missing, like a
//! positive ΔRrp). A point on the normal of C at t is at the foot t whatever w is, so d is
//! exact for points C(t) + s·N(t); for a real point it differs from the distance to the curve
//! Γ_w by O(d·(w'/|Γ'|)²), below 1e-6 of d for µm form errors.
//! Points on the bore of hole j: d = |Q − h_j| − (ρ_h + Δρ), h_j = rw·(cos 2πj/M, sin 2πj/M),
//! ρ_h the design's hole radius and Δρ one common fitted offset.
//!
//! Jacobian (the foot is stationary, so moving t does not change d to first order):
//!   ∂d/∂c0 = −N_machine,  ∂d/∂θ0 = ∂d/∂Δδ = −(C × N),  ∂d/∂ΔRp = −(cos t, sin t)·N,
//!   ∂d/∂ΔRrp = 1,  ∂d/∂a_k = cos k·t,  ∂d/∂b_k = sin k·t;
//! for hole points with u the unit vector from h_j: ∂d/∂c0 = −R(θ0)·u, ∂d/∂θ0 = −(Q × u),
//! ∂d/∂Δρ = −1. The w'(t)·∂t/∂p terms are dropped: they change the convergence rate, not the
//! solution.
//!
//! Well posedness. The form error is w(t) = Σ a_k cos k·t + b_k sin k·t over the orders
//! 2 ≤ k ≤ `harmonics` that are not multiples of the tooth count nc. The profile repeats after
//! a tooth pitch, C(t + 2π/nc) = R(2π/nc)·C(t), so the normal displacements of a turn (θ0, Δδ),
//! of ΔRp and of ΔRrp are functions of period 2π/nc: series in the orders 0, nc, 2nc, … —
//! leaving those orders out of w leaves the modifications alone to move every tooth alike. A
//! shift of the centre moves the profile along N·c0, whose series has the orders |1 + m·nc|,
//! dominated by order 1: leaving order 1 out keeps the centre apart from w. Δδ and θ0 are the
//! same motion of the profile; only points on the holes (which θ0 turns and Δδ does not) tell
//! them apart, so `rotation_deg` is fitted only with hole points. What remains correlated
//! (the centre with the orders nc ± 1 when points cover part of the disc, high orders on
//! sparse points) shows in the condition number of the column-scaled Jacobian, which is
//! computed at the solution and a fit above `MAX_CONDITION` is refused.
//!
//! Each Gauss–Newton step is the tall least-squares problem min ‖J·δ + d‖ with J's columns
//! scaled to unit norm, solved on the way by the normal equations (`normal_solve`) and at the
//! solution by the same normal equations while the condition number is at most 1e4 (their
//! errors ~κ²·ε ≤ 2e-8), else by a Householder QR of J; steps are halved until the sum of
//! squares decreases. Uncertainties: σ̂² = Σd²/(m − n), cov = σ̂²·(JᵀJ)⁻¹ = σ̂²·S⁻¹·P·R⁻¹R⁻ᵀ·Pᵀ·S⁻¹
//! from the same factorisation (S the column norms, P the pivoting), at the solution.

use super::fitted::{Estimate, FittedPoint, FormError, Harmonic};
use super::flanks::{flanks, Flank};
use super::thinning::{self, Thinning};
use super::{Feature, MeasuredPoint};
use crate::error::{Error, Result};
use crate::geometry::profile::{ClosestPointFailure, Foot, Profile};
use crate::geometry::{cos_sin_of_orders, cross, rotate, unit, wrap_pi, Vec2};
use crate::model::measured::Fitted;
use crate::model::{Design, Modification};
use faer::linalg::solvers::SolveLstsq;
use faer::Mat;
use std::f64::consts::{PI, TAU};

/// Largest condition number of the column-scaled Jacobian a fit accepts. With double precision
/// (ε ≈ 1e-16) and residuals of ~1 µm, a condition of 1e8 still resolves the unknowns to
/// ~1e-8 of their scale; beyond it the data cannot tell some unknowns apart.
pub const MAX_CONDITION: f64 = 1e8;

/// Largest RMS residual of an accepted fit, mm: a ground disc fits within a few µm, and 50 µm
/// is still far below the tooth depth (2e, millimetres) — points further off are not a disc
/// of this design, or not aligned to it.
pub const MAX_RMS_MM: f64 = 0.05;

const MAX_ITERATIONS: usize = 60;

/// Most entries (points × unknowns) of the Jacobian a fit holds: 2^24, 128 MiB of f64 per copy,
/// and the iteration holds three (the Jacobian, the trial step's and the column-scaled copy its
/// QR factors). A million points of the 5 unknowns of a fit without form error fit in it; 200
/// harmonics (up to 405 unknowns) leave room for 41,000 points, a point every 5 µm around the
/// paper's disc. A denser profile is thinned to fit (`thinning`).
pub const MAX_JACOBIAN_ENTRIES: usize = 1 << 24;

/// Below this RMS change of the residuals per step, mm, the feet of the last parameters start
/// Newton alone (`Profile::closest_point_from`): a µm-sized move keeps every foot on its flank.
const WARM_MM: f64 = 1e-2;

/// What to identify: the design, the spec's modification (the start, and the value of what is
/// not fitted), which modifications to fit and the highest form-error harmonic.
#[derive(Debug, Clone, Copy)]
pub struct Request<'a> {
    pub design: &'a Design,
    pub nominal: Modification,
    pub fit: Fitted,
    pub harmonics: usize,
}

/// How much of the profile the points cover.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coverage {
    /// Fraction of the bins of 1/16 tooth pitch in t that hold a point.
    pub fraction: f64,
    /// Teeth with at least 3 points on each flank.
    pub teeth_measured: usize,
}

/// The result of an identification.
#[derive(Debug, Clone, PartialEq)]
pub struct Identification {
    /// Disc centre in the machine frame, mm.
    pub centre_mm: [Estimate; 2],
    /// Turn of the disc frame in the machine frame, rad, counter-clockwise.
    pub orientation_rad: Estimate,
    /// The identified modification (fitted values, the spec's for the others).
    pub modification: Modification,
    pub shift_mm: Option<Estimate>,
    pub equidistant_mm: Option<Estimate>,
    pub rotation_rad: Option<Estimate>,
    /// Common offset of the hole radii from the design's, with hole points.
    pub hole_radius_offset_mm: Option<Estimate>,
    pub form: FormError,
    pub residual_rms_mm: f64,
    pub residual_max_mm: f64,
    /// File line of the point with the largest |residual|.
    pub residual_max_line: usize,
    /// Condition number of the column-scaled Jacobian at the solution.
    pub condition: f64,
    pub coverage: Coverage,
    pub flanks: Vec<Flank>,
    pub profile: Vec<FittedPoint>,
    pub hole_points: usize,
    pub unknowns: usize,
    pub iterations: usize,
    /// Every k-th profile point was used, the scan being denser than the Jacobian holds.
    pub thinning: Option<Thinning>,
}

/// Where each unknown sits in the parameter vector.
#[derive(Debug, Clone)]
struct Layout {
    shift: Option<usize>,
    equidistant: Option<usize>,
    rotation: Option<usize>,
    hole: Option<usize>,
    /// First column of the series; orders as `FormError::orders`.
    form: usize,
    orders: Vec<usize>,
    len: usize,
}

impl Layout {
    fn new(fit: Fitted, holes: bool, orders: Vec<usize>) -> Layout {
        let mut next = 3;
        let mut take = |on: bool| {
            on.then(|| {
                next += 1;
                next - 1
            })
        };
        let shift = take(fit.shift);
        let equidistant = take(fit.equidistant);
        let rotation = take(fit.rotation);
        let hole = take(holes);
        let form = next;
        let len = form + 2 * orders.len();
        Layout {
            shift,
            equidistant,
            rotation,
            hole,
            form,
            orders,
            len,
        }
    }

    /// The name of unknown `i`, for messages.
    fn name(&self, i: usize) -> String {
        let fixed = ["centre x0", "centre y0", "orientation θ0"];
        if i < 3 {
            return fixed[i].to_string();
        }
        for (slot, name) in [
            (self.shift, "shift_mm"),
            (self.equidistant, "equidistant_mm"),
            (self.rotation, "rotation_deg"),
            (self.hole, "hole radius"),
        ] {
            if slot == Some(i) {
                return name.to_string();
            }
        }
        let k = (i - self.form) / 2;
        let part = if (i - self.form).is_multiple_of(2) {
            "cos"
        } else {
            "sin"
        };
        format!("form harmonic {} ({part})", self.orders[k])
    }
}

/// The state the residuals are evaluated at, unpacked from the parameter vector.
struct State<'a> {
    design: &'a Design,
    profile: Profile,
    centre: Vec2,
    /// (sin, cos) of θ0 and of Δδ.
    orientation: (f64, f64),
    rotation: (f64, f64),
    hole_offset: f64,
    params: &'a [f64],
    layout: &'a Layout,
    /// The feet's starts are the feet of the previous, nearby parameters: Newton alone.
    warm: bool,
}

impl<'a> State<'a> {
    fn new(request: &'a Request, layout: &'a Layout, params: &'a [f64]) -> State<'a> {
        let get = |slot: Option<usize>, nominal: f64| slot.map_or(nominal, |i| params[i]);
        let d = request.design;
        let m = request.nominal;
        let profile = Profile::from_parts(
            d.rollers,
            d.eccentricity_mm,
            d.roller_circle_radius_mm + get(layout.shift, m.shift_mm),
            d.roller_radius_mm + get(layout.equidistant, m.equidistant_mm),
            get(layout.rotation, m.rotation_within_pitch(d.teeth)),
        );
        let rotation = profile.rotation_rad.sin_cos();
        State {
            design: d,
            profile,
            centre: Vec2::new(params[0], params[1]),
            orientation: params[2].sin_cos(),
            rotation,
            hole_offset: get(layout.hole, 0.0),
            params,
            layout,
            warm: false,
        }
    }

    fn to_disc(&self, p: Vec2) -> Vec2 {
        let (s, c) = self.orientation;
        rotate(p - self.centre, c, -s)
    }

    /// w(t) and, in `basis`, (cos k·t, sin k·t) of every order of the series.
    fn form(&self, t: f64, basis: &mut [f64]) -> f64 {
        let l = self.layout;
        let harmonics = cos_sin_of_orders(t, l.orders.iter().copied());
        for (pair, (c, s)) in basis.chunks_exact_mut(2).zip(harmonics) {
            pair[0] = c;
            pair[1] = s;
        }
        basis
            .iter()
            .zip(&self.params[l.form..])
            .map(|(b, a)| b * a)
            .sum()
    }

    /// Residual of a profile point, its foot, and (when `row` is given) its Jacobian row;
    /// `basis` holds two entries per order of the series (overwritten: a scratch the caller
    /// keeps, so that no array is allocated and zeroed per point).
    fn profile_residual(
        &self,
        point: &MeasuredPoint,
        t_start: f64,
        row: Option<&mut [f64]>,
        basis: &mut [f64],
    ) -> Result<(f64, f64)> {
        let q = self.to_disc(point.point);
        let foot = self.foot(q, t_start).map_err(|f| {
            Error::computation(format!(
                "the point of line {} has no foot on the profile near t = {:.4} rad \
                 (the closest-point search left its bracket at t = {:.4} rad)",
                point.line, f.t_start, f.t_last
            ))
        })?;
        let t = foot.t;
        let l = self.layout;
        let d = foot.locus_distance_mm + self.profile.offset_mm + self.form(t, basis);
        if let Some(row) = row {
            let (s, c) = self.orientation;
            let n_machine = rotate(foot.normal, c, s);
            let locus = foot.point + self.profile.offset_mm * foot.normal;
            let turn = -cross(locus, foot.normal);
            row[0] = -n_machine.x;
            row[1] = -n_machine.y;
            row[2] = turn;
            if let Some(i) = l.shift {
                let (s, c) = self.rotation;
                let radial = rotate(unit(t), c, s);
                row[i] = -radial.dot(&foot.normal);
            }
            if let Some(i) = l.equidistant {
                row[i] = 1.0;
            }
            if let Some(i) = l.rotation {
                row[i] = turn;
            }
            if let Some(i) = l.hole {
                row[i] = 0.0;
            }
            row[l.form..].copy_from_slice(basis);
        }
        Ok((d, t))
    }

    /// The foot of q on the profile: the guarded search from `t_start`, and when its bracket
    /// (half a roller pitch) does not hold the foot — a start far off, early in the iteration —
    /// the nearest of the searches started at every half pitch around the disc.
    fn foot(&self, q: Vec2, t_start: f64) -> std::result::Result<Foot, ClosestPointFailure> {
        if self.warm {
            if let Ok(foot) = self.profile.closest_point_from(q, t_start) {
                return Ok(foot);
            }
        }
        let first = self.profile.closest_point(q, t_start);
        if first.is_ok() {
            return first;
        }
        let half = PI / self.profile.rollers as f64;
        (1..2 * self.profile.rollers)
            .filter_map(|k| {
                self.profile
                    .closest_point(q, t_start + half * k as f64)
                    .ok()
            })
            .min_by(|a, b| {
                a.signed_distance_mm
                    .abs()
                    .total_cmp(&b.signed_distance_mm.abs())
            })
            .ok_or_else(|| first.unwrap_err())
    }

    /// Residual of a hole point and (when `row` is given) its Jacobian row.
    fn hole_residual(&self, point: &MeasuredPoint, j: usize, row: Option<&mut [f64]>) -> f64 {
        let q = self.to_disc(point.point);
        let v = q - Vec2::from(self.design.pins.centre_mm(j));
        let r = v.norm();
        let d = r - (self.design.hole_radius_mm() + self.hole_offset);
        if let Some(row) = row {
            row.fill(0.0);
            let u = if r > 0.0 { v / r } else { Vec2::new(1.0, 0.0) };
            let (s, c) = self.orientation;
            let u_machine = rotate(u, c, s);
            row[0] = -u_machine.x;
            row[1] = -u_machine.y;
            row[2] = -cross(q, u);
            if let Some(i) = self.layout.hole {
                row[i] = -1.0;
            }
        }
        d
    }
}

/// Residuals (and Jacobian when asked) of every point; `feet` are the starts of the profile
/// points' feet (warm: the feet at nearby parameters), updated.
fn evaluate(
    request: &Request,
    layout: &Layout,
    params: &[f64],
    points: &[MeasuredPoint],
    (feet, warm): (&mut [f64], bool),
    mut jacobian: Option<&mut [f64]>,
) -> Result<Vec<f64>> {
    let mut state = State::new(request, layout, params);
    state.warm = warm;
    let n = layout.len;
    let mut residuals = Vec::with_capacity(points.len());
    let mut basis = vec![0.0; 2 * layout.orders.len()];
    for (i, p) in points.iter().enumerate() {
        let row = jacobian.as_deref_mut().map(|j| &mut j[i * n..(i + 1) * n]);
        let d = match p.feature {
            Feature::Profile => {
                let (d, t) = state.profile_residual(p, feet[i], row, &mut basis)?;
                feet[i] = t;
                d
            }
            Feature::Hole(j) => state.hole_residual(p, j, row),
        };
        residuals.push(d);
    }
    Ok(residuals)
}

/// One least-squares solve: the step δ minimising ‖J·δ + d‖, the condition number of the
/// column-scaled J, the variances diag((JᵀJ)⁻¹) and the least independent column.
struct Step {
    delta: Vec<f64>,
    condition: f64,
    variances: Vec<f64>,
    weakest: usize,
}

/// The step, the condition number and the variances, by a column-pivoted QR (at the solution,
/// and for a step whose normal matrix is not numerically positive definite).
/// `jacobian` is row-major, a row of `n` per residual.
fn solve(jacobian: &[f64], n: usize, residuals: &[f64]) -> Result<Step> {
    let m = residuals.len();
    let mut scale = vec![0.0; n];
    for row in jacobian.chunks_exact(n) {
        for (s, v) in scale.iter_mut().zip(row) {
            *s += v * v;
        }
    }
    let scale: Vec<f64> = scale
        .into_iter()
        .map(|s| if s > 0.0 { s.sqrt() } else { 1.0 })
        .collect();
    let scaled = Mat::from_fn(m, n, |i, c| jacobian[i * n + c] / scale[c]);
    let mut rhs = Mat::from_fn(m, 1, |i, _| -residuals[i]);
    // J·S⁻¹ = Q₁R₁ by the blocked Householder QR without pivoting, then R₁ = Q₂R·Pᵀ by the
    // column-pivoted QR of the small n × n R₁: Q₁Q₂ is orthogonal, so this is a pivoted QR of
    // J·S⁻¹ (the pivots depend on column norms and inner products only, which Q₁ keeps),
    // at the cost of the unpivoted one (the pivoted QR of the tall matrix is slower).
    let qr = scaled.qr();
    qr.solve_lstsq_in_place(rhs.as_mut());
    let delta = (0..n).map(|c| rhs[(c, 0)] / scale[c]).collect();
    let pivoted = qr.thin_R().col_piv_qr();
    let (forward, _) = pivoted.P().arrays();
    let r = pivoted.thin_R();
    let singular = r
        .singular_values()
        .map_err(|e| Error::computation(format!("singular values of R: {e:?}")))?;
    let largest = singular.iter().cloned().fold(0.0, f64::max);
    let smallest = singular.iter().cloned().fold(f64::INFINITY, f64::min);
    let condition = if smallest > 0.0 {
        largest / smallest
    } else {
        f64::INFINITY
    };
    // diag((JᵀJ)⁻¹) = diag(S⁻¹·P·R⁻¹R⁻ᵀ·Pᵀ·S⁻¹): the squared row norms of R⁻¹, permuted.
    let mut inverse = Mat::<f64>::identity(n, n);
    faer::linalg::triangular_solve::solve_upper_triangular_in_place(
        r,
        inverse.as_mut(),
        faer::Par::Seq,
    );
    let mut variances = vec![0.0; n];
    for (pivoted, &original) in forward.iter().enumerate() {
        let row_norm2: f64 = (0..n).map(|c| inverse[(pivoted, c)].powi(2)).sum();
        variances[original] = row_norm2 / (scale[original] * scale[original]);
    }
    Ok(Step {
        delta,
        condition,
        variances,
        weakest: forward[n - 1],
    })
}

/// The factored normal equations of `normal_solve`.
struct Normal {
    scaled: Mat<f64>,
    scale: Vec<f64>,
    llt: faer::linalg::solvers::Llt<f64>,
    delta: Vec<f64>,
}

/// A Gauss–Newton step on the way, from the normal equations: (S⁻¹JᵀJS⁻¹)·y = −S⁻¹Jᵀd,
/// δ = S⁻¹·y, by a Cholesky factorisation of the n × n column-scaled normal matrix (JᵀJ costs
/// m·n² flops in a matrix product, half a Householder QR's 2·m·n² and at a faster rate).
/// None when the factorisation fails (the normal matrix is not numerically positive definite).
///
/// Why the squared condition number does no harm here: the step is only a direction. Its
/// relative error is ~κ²·ε (κ the condition number of the scaled J), and for any κ² < 1/ε the
/// iteration is still a contraction whose fixed point is Jᵀd = 0 — computed as a plain
/// product, as accurately as a QR would — so the solution does not depend on how accurately
/// the normal matrix was factored, only the speed of the approach. At the solution, the step
/// and statistics come from the normal equations only while κ ≤ `NORMAL_CONDITION` = 1e4
/// (errors ≤ ~2e-8), else from a Householder QR of J (`solve`), which polishes the last step
/// to QR accuracy and rejects κ above `MAX_CONDITION`.
fn normal_solve(jacobian: &[f64], n: usize, residuals: &[f64]) -> Option<Normal> {
    let m = residuals.len();
    // The row-major m × n Jacobian is the column-major n × m matrix Jᵀ: no copy.
    let jt = faer::MatRef::from_column_major_slice(jacobian, n, m);
    let d = faer::MatRef::from_column_major_slice(residuals, m, 1);
    let mut normal = Mat::<f64>::zeros(n, n);
    faer::linalg::matmul::triangular::matmul(
        normal.as_mut(),
        faer::linalg::matmul::triangular::BlockStructure::TriangularLower,
        faer::Accum::Replace,
        jt,
        faer::linalg::matmul::triangular::BlockStructure::Rectangular,
        jt.transpose(),
        faer::linalg::matmul::triangular::BlockStructure::Rectangular,
        1.0,
        faer::Par::Seq,
    );
    let scale: Vec<f64> = (0..n)
        .map(|c| {
            let s = normal[(c, c)];
            if s > 0.0 {
                s.sqrt()
            } else {
                1.0
            }
        })
        .collect();
    let scaled = Mat::from_fn(n, n, |i, c| {
        let (i, c) = if i >= c { (i, c) } else { (c, i) };
        normal[(i, c)] / (scale[i] * scale[c])
    });
    let mut rhs = jt * d;
    for (c, s) in scale.iter().enumerate() {
        rhs[(c, 0)] = -rhs[(c, 0)] / s;
    }
    let llt = scaled.llt(faer::Side::Lower).ok()?;
    faer::linalg::solvers::Solve::solve_in_place(&llt, rhs.as_mut());
    let delta: Vec<f64> = (0..n).map(|c| rhs[(c, 0)] / scale[c]).collect();
    delta.iter().all(|d| d.is_finite()).then_some(Normal {
        scaled,
        scale,
        llt,
        delta,
    })
}

/// Largest condition number of the column-scaled J whose statistics are taken from the normal
/// equations: their relative errors are then ~κ²·ε ≤ 1e8·2.2e-16 ≈ 2e-8 (the eigenvalues of
/// the scaled normal matrix, of norm ≤ n, carry absolute errors ~n·ε, against a smallest one
/// ≥ 1/κ² = 1e-8; the inverse's diagonal likewise), far below the ~1/√(2(m − n)) statistical
/// uncertainty of σ̂ itself. Above it, up to `MAX_CONDITION` and beyond, the Householder QR
/// of J (`solve`) computes them, and names the weakest column.
const NORMAL_CONDITION: f64 = 1e4;

/// The step and statistics at the solution from the normal equations when the condition
/// number allows it (`NORMAL_CONDITION`), else None.
fn normal_statistics(jacobian: &[f64], n: usize, residuals: &[f64]) -> Option<Step> {
    let normal = normal_solve(jacobian, n, residuals)?;
    let eigen = normal
        .scaled
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .ok()?;
    let largest = eigen.iter().cloned().fold(0.0, f64::max);
    let smallest = eigen.iter().cloned().fold(f64::INFINITY, f64::min);
    // NaN eigenvalues fail both tests (`is_finite`, `<=`) and go to the QR.
    let condition = (largest / smallest).sqrt();
    if smallest <= 0.0 || !condition.is_finite() || condition > NORMAL_CONDITION {
        return None;
    }
    let inverse = faer::linalg::solvers::DenseSolveCore::inverse(&normal.llt);
    let variances: Vec<f64> = (0..n)
        .map(|c| inverse[(c, c)] / (normal.scale[c] * normal.scale[c]))
        .collect();
    if !variances.iter().all(|v| v.is_finite() && *v > 0.0) {
        return None;
    }
    Some(Step {
        delta: normal.delta,
        condition,
        variances,
        // Only named above `MAX_CONDITION`, which this path never reaches.
        weakest: 0,
    })
}

fn sum_squares(r: &[f64]) -> f64 {
    r.iter().map(|d| d * d).sum()
}

/// Identify the disc the points lie on. Errors (exit 2): too few points for the unknowns,
/// `rotation_deg` without hole points, a fit whose Jacobian is ill-conditioned, a fit that does
/// not converge, and points that do not fit a disc of this design. A profile denser than
/// `MAX_JACOBIAN_ENTRIES` holds is thinned first (`thinning`, every k-th point; the residuals,
/// coverage and flanks are those of the points used), and the identification says so.
pub fn identify(request: &Request, points: &[MeasuredPoint]) -> Result<Identification> {
    let design = request.design;
    let profile_count = points
        .iter()
        .filter(|p| p.feature == Feature::Profile)
        .count();
    let hole_points = points.len() - profile_count;
    if let Some(bad) = points.iter().find_map(|p| match p.feature {
        Feature::Hole(j) if j >= design.pins.count => Some((p.line, j)),
        _ => None,
    }) {
        return Err(Error::invalid_value(format!(
            "line {}: hole:{} does not exist: the design has {} output-pin holes, \
             numbered 0 to {}",
            bad.0,
            bad.1,
            design.pins.count,
            design.pins.count - 1
        )));
    }
    if request.fit.rotation && hole_points == 0 {
        return Err(Error::invalid_value(
            "`rotation_deg` cannot be fitted without points on the pin holes: the rotation \
             modification is the turn of the teeth relative to the holes, and on the profile \
             alone it is the same motion as the orientation of the disc on the machine",
        ));
    }
    let layout = Layout::new(
        request.fit,
        hole_points > 0,
        FormError::orders(request.harmonics, design.teeth),
    );
    if layout.orders.len() > MAX_ORDERS {
        return Err(Error::invalid_value(format!(
            "{} form-error orders asked for; at most {MAX_ORDERS}",
            layout.orders.len()
        )));
    }
    if profile_count <= layout.len {
        return Err(Error::invalid_value(format!(
            "{profile_count} profile points for {} unknowns (centre, orientation, {} fitted \
             modifications, {} form-error coefficients): measure more points or ask for \
             fewer harmonics",
            layout.len,
            layout.len - 3 - 2 * layout.orders.len(),
            2 * layout.orders.len()
        )));
    }
    // Points repeated (one point measured over and over) fix no more unknowns than one: the
    // circle through them, and every foot after it, would be NaN.
    let mut distinct: Vec<(u64, u64)> = points
        .iter()
        .filter(|p| p.feature == Feature::Profile)
        .map(|p| (p.point.x.to_bits(), p.point.y.to_bits()))
        .collect();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() <= layout.len {
        return Err(Error::invalid_value(format!(
            "{} distinct profile points (of {profile_count}; the others repeat them) for {} \
             unknowns: measure points spread along the profile",
            distinct.len(),
            layout.len
        )));
    }
    let thinning = thinning::needed(profile_count, hole_points, layout.len, MAX_JACOBIAN_ENTRIES);
    let thinned;
    let points = match thinning {
        Some(t) => {
            thinned = thinning::thin(points, t.every);
            &thinned[..]
        }
        None => points,
    };
    let entries = points.len().saturating_mul(layout.len);
    if entries > MAX_JACOBIAN_ENTRIES {
        return Err(Error::invalid_value(format!(
            "{} points × {} unknowns = {entries} Jacobian entries, more than the \
             {MAX_JACOBIAN_ENTRIES} (128 MiB) a fit holds: thin the points (every k-th) or \
             ask for fewer harmonics",
            points.len(),
            layout.len
        )));
    }
    let (mut params, mut feet) = initial(request, &layout, points)?;
    let n = layout.len;
    let mut jac = vec![0.0; points.len() * n];
    let mut residuals = evaluate(
        request,
        &layout,
        &params,
        points,
        (&mut feet, false),
        Some(&mut jac),
    )?;
    let mut trial_jac = vec![0.0; points.len() * n];
    let mut iterations = 0;
    let mut warm = false;
    let mut converged = false;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let delta = match normal_solve(&jac, n, &residuals) {
            Some(normal) => normal.delta,
            None => solve(&jac, n, &residuals)?.delta,
        };
        let cost = sum_squares(&residuals);
        // Size of the full step's effect on the residuals, RMS mm: ‖J·δ‖/√m.
        let full_move = jac
            .chunks_exact(n)
            .map(|row| {
                row.iter()
                    .zip(&delta)
                    .map(|(j, d)| j * d)
                    .sum::<f64>()
                    .powi(2)
            })
            .sum::<f64>()
            .sqrt()
            / (points.len() as f64).sqrt();
        let mut lambda = 1.0;
        let mut accepted = None;
        for _ in 0..30 {
            let trial: Vec<f64> = params
                .iter()
                .zip(&delta)
                .map(|(p, d)| p + lambda * d)
                .collect();
            let mut trial_feet = feet.clone();
            // The trial's feet start warm when this step moves the residuals by less than
            // `WARM_MM` (as after a small previous step): the feet then move by as little.
            let at = (&mut trial_feet[..], warm || lambda * full_move < WARM_MM);
            if let Ok(r) = evaluate(request, &layout, &trial, points, at, Some(&mut trial_jac)) {
                if sum_squares(&r) <= cost {
                    accepted = Some((trial, trial_feet, r));
                    break;
                }
            }
            lambda *= 0.5;
        }
        let Some((trial, trial_feet, trial_residuals)) = accepted else {
            // No step along the Gauss–Newton direction decreases the cost: a minimum to
            // working precision.
            converged = true;
            break;
        };
        let moved = lambda * full_move;
        params = trial;
        feet = trial_feet;
        residuals = trial_residuals;
        std::mem::swap(&mut jac, &mut trial_jac);
        warm = moved < WARM_MM;
        // Converged when the step moves the residuals by less than 1e-4 of their RMS (or 1 pm):
        // what remains changes no unknown by more than ~1e-4 of its uncertainty.
        let rms = (sum_squares(&residuals) / points.len() as f64).sqrt();
        if moved < (1e-4 * rms).max(1e-9) {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err(Error::computation(format!(
            "the identification did not converge in {MAX_ITERATIONS} Gauss–Newton steps \
             (residual RMS {:.3} µm)",
            1e3 * (sum_squares(&residuals) / points.len() as f64).sqrt()
        )));
    }
    let last = match normal_statistics(&jac, n, &residuals) {
        Some(last) => last,
        None => solve(&jac, n, &residuals)?,
    };
    // The last step from the statistics' own factorisation (the normal equations' when the
    // condition number is at most `NORMAL_CONDITION`, where they are accurate to ~2e-8; the
    // QR's above, where it polishes the normal-equation steps to QR accuracy). It moves the residuals by less than 1e-4 of their
    // RMS (the convergence test), so the statistics of the point before it hold after it.
    let polished: Vec<f64> = params.iter().zip(&last.delta).map(|(p, d)| p + d).collect();
    let mut polished_feet = feet.clone();
    let at = (&mut polished_feet[..], true);
    if let Ok(r) = evaluate(request, &layout, &polished, points, at, None) {
        if sum_squares(&r) <= sum_squares(&residuals) {
            (params, feet, residuals) = (polished, polished_feet, r);
        }
    }
    let id = finish(
        request, &layout, &params, points, &feet, &residuals, &last, iterations,
    )?;
    Ok(Identification { thinning, ..id })
}

#[allow(clippy::too_many_arguments)]
fn finish(
    request: &Request,
    layout: &Layout,
    params: &[f64],
    points: &[MeasuredPoint],
    feet: &[f64],
    residuals: &[f64],
    last: &Step,
    iterations: usize,
) -> Result<Identification> {
    let m = points.len();
    let rms = (sum_squares(residuals) / m as f64).sqrt();
    if last.condition > MAX_CONDITION || !last.condition.is_finite() {
        return Err(Error::invalid_value(format!(
            "the identification is ill-posed: the condition number of its Jacobian is \
             {:.2e}, above {MAX_CONDITION:.0e}; the least determined unknown is the {}: \
             measure more of the profile, or ask for fewer harmonics or fitted \
             modifications",
            last.condition,
            layout.name(last.weakest)
        )));
    }
    if rms > MAX_RMS_MM {
        return Err(Error::invalid_value(format!(
            "the points are not a disc of this design: after the fit their RMS distance \
             to the profile is {:.1} µm, more than the {:.0} µm any ground disc keeps \
             (check the design, the file's units (mm) and its features)",
            rms * 1e3,
            MAX_RMS_MM * 1e3
        )));
    }
    let dof = (m - layout.len) as f64;
    let sigma = (sum_squares(residuals) / dof).sqrt();
    let est = |i: usize| Estimate {
        value: params[i],
        sigma: sigma * last.variances[i].sqrt(),
    };
    let harmonics: Vec<Harmonic> = layout
        .orders
        .iter()
        .enumerate()
        .map(|(k, &order)| Harmonic {
            order,
            cos_mm: est(layout.form + 2 * k),
            sin_mm: est(layout.form + 2 * k + 1),
        })
        .collect();
    let form = FormError { harmonics };
    let nominal = request.nominal;
    let modification = Modification {
        shift_mm: layout.shift.map_or(nominal.shift_mm, |i| params[i]),
        equidistant_mm: layout
            .equidistant
            .map_or(nominal.equidistant_mm, |i| params[i]),
        rotation_rad: layout.rotation.map_or(nominal.rotation_rad, |i| params[i]),
    };
    let (max_i, max) = residuals
        .iter()
        .enumerate()
        .fold((0, 0.0f64), |(bi, b), (i, r)| {
            if r.abs() > b {
                (i, r.abs())
            } else {
                (bi, b)
            }
        });
    let profile: Vec<FittedPoint> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.feature == Feature::Profile)
        .map(|(i, p)| FittedPoint {
            t: feet[i],
            residual_mm: residuals[i],
            line: p.line,
        })
        .collect();
    let hole_points = points.len() - profile.len();
    let teeth = request.design.teeth;
    let reference = Profile::new(request.design, &modification);
    let flanks = flanks(&reference, &profile, &form, teeth);
    let coverage = coverage(&profile, &flanks, teeth);
    Ok(Identification {
        centre_mm: [est(0), est(1)],
        orientation_rad: est(2),
        modification,
        shift_mm: layout.shift.map(est),
        equidistant_mm: layout.equidistant.map(est),
        rotation_rad: layout.rotation.map(est),
        hole_radius_offset_mm: layout.hole.map(est),
        form,
        residual_rms_mm: rms,
        residual_max_mm: max,
        residual_max_line: points[max_i].line,
        condition: last.condition,
        coverage,
        flanks,
        profile,
        hole_points,
        unknowns: layout.len,
        iterations,
        thinning: None,
    })
}

/// Most orders of a form-error series ([`spec::measured::MAX_HARMONICS`](crate::spec::measured::MAX_HARMONICS) = 200 and fewer).
const MAX_ORDERS: usize = 256;

/// The bins per tooth pitch in t over which `Coverage::fraction` counts the points.
pub const COVERAGE_BINS_PER_TOOTH: usize = 16;

/// The width in t of a coverage bin, rad: a stretch this long without a point is unmeasured.
pub fn coverage_bin_rad(teeth: usize) -> f64 {
    TAU / (COVERAGE_BINS_PER_TOOTH * teeth) as f64
}

fn coverage(profile: &[FittedPoint], flanks: &[Flank], teeth: usize) -> Coverage {
    let bins = COVERAGE_BINS_PER_TOOTH * teeth;
    let mut hit = vec![false; bins];
    for p in profile {
        let b = ((p.t.rem_euclid(TAU) / TAU * bins as f64) as usize).min(bins - 1);
        hit[b] = true;
    }
    let teeth_measured = flanks
        .chunks(2)
        .filter(|f| f.iter().all(|x| x.points >= 3))
        .count();
    Coverage {
        fraction: hit.iter().filter(|h| **h).count() as f64 / bins as f64,
        teeth_measured,
    }
}

/// The start of the iteration: the centre from a circle fit to the profile points, the
/// orientation from the holes (circular mean of each hole point's angle less its hole's) and
/// from a scan of one tooth pitch for the profile; modifications at the spec's values, no form
/// error. Returns the parameters and the feet's warm starts.
fn initial(
    request: &Request,
    layout: &Layout,
    points: &[MeasuredPoint],
) -> Result<(Vec<f64>, Vec<f64>)> {
    let design = request.design;
    let profile: Vec<MeasuredPoint> = points
        .iter()
        .filter(|p| p.feature == Feature::Profile)
        .copied()
        .collect();
    let centre = circle_centre(&profile);
    let mut params = vec![0.0; layout.len];
    params[0] = centre.x;
    params[1] = centre.y;
    let nominal = request.nominal;
    let rotation = nominal.rotation_within_pitch(design.teeth);
    if let Some(i) = layout.shift {
        params[i] = nominal.shift_mm;
    }
    if let Some(i) = layout.equidistant {
        params[i] = nominal.equidistant_mm;
    }
    if let Some(i) = layout.rotation {
        params[i] = rotation;
    }
    // Profile scan: the turn of the teeth, modulo a pitch, on at most 100 points (each of the
    // 48 turns costs a cold foot search per point; 100 points spread over the measured teeth,
    // ~11 per tooth of the paper's 9-tooth disc, and the scan only has to rank 48 turns of which
    // the Gauss–Newton steps refine the best).
    let stride = (profile.len() / 100).max(1);
    let sample: Vec<MeasuredPoint> = profile.iter().step_by(stride).copied().collect();
    let pitch = TAU / design.teeth as f64;
    const SCAN: usize = 48;
    let mut best = (f64::INFINITY, 0.0);
    for k in 0..SCAN {
        let turn = pitch * k as f64 / SCAN as f64;
        let mut trial = params.clone();
        trial[2] = turn - rotation;
        let mut feet = start_feet(&trial, &sample);
        if let Ok(r) = evaluate(request, layout, &trial, &sample, (&mut feet, false), None) {
            let cost = sum_squares(&r);
            if cost < best.0 {
                best = (cost, turn);
            }
        }
    }
    let teeth_turn = best.1;
    let holes: Vec<(usize, Vec2)> = points
        .iter()
        .filter_map(|p| match p.feature {
            Feature::Hole(j) => Some((j, p.point)),
            _ => None,
        })
        .collect();
    params[2] = if holes.is_empty() {
        teeth_turn - rotation
    } else {
        let m = design.pins.count as f64;
        let sum = holes.iter().fold(Vec2::zeros(), |acc, (j, p)| {
            let v = p - centre;
            let a = v.y.atan2(v.x) - TAU * *j as f64 / m;
            acc + unit(a)
        });
        let orientation = sum.y.atan2(sum.x);
        if let Some(i) = layout.rotation {
            params[i] =
                wrap_pi((teeth_turn - orientation) * design.teeth as f64) / design.teeth as f64;
        }
        orientation
    };
    let feet = start_feet(&params, points);
    Ok((params, feet))
}

/// Warm starts of the feet: the polar angle of each point in the disc frame (the locus's polar
/// angle is within asin(e/R') of t).
fn start_feet(params: &[f64], points: &[MeasuredPoint]) -> Vec<f64> {
    let centre = Vec2::new(params[0], params[1]);
    points
        .iter()
        .map(|p| {
            let v = p.point - centre;
            v.y.atan2(v.x) - params[2]
        })
        .collect()
}

/// Centre of the least-squares circle through the points (Kåsa: x² + y² = 2a·x + 2b·y + c,
/// linear in a, b, c), about their mean to keep the squares small.
fn circle_centre(points: &[MeasuredPoint]) -> Vec2 {
    let n = points.len().max(1) as f64;
    let mean = points.iter().fold(Vec2::zeros(), |a, p| a + p.point) / n;
    let a = Mat::from_fn(points.len(), 3, |i, c| {
        let p = points[i].point - mean;
        [2.0 * p.x, 2.0 * p.y, 1.0][c]
    });
    let mut b = Mat::from_fn(points.len(), 1, |i, _| {
        (points[i].point - mean).norm_squared()
    });
    a.col_piv_qr().solve_lstsq_in_place(b.as_mut());
    mean + Vec2::new(b[(0, 0)], b[(1, 0)])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 40 × 5 row-major Jacobian with columns of scales 1e-3 to 1e3; column 3 is 1 + x plus
    /// `wobble`·cos 3x, nearly dependent on the constant and linear parts as `wobble` → 0.
    fn test_jacobian(wobble: f64) -> (usize, usize, Vec<f64>) {
        let (m, n) = (40, 5);
        let value = |i: usize, c: usize| {
            let x = i as f64 / m as f64;
            match c {
                0 => 1e-3 * (1.0 + x),
                1 => 1e3 * x * x,
                2 => (7.0 * x).sin(),
                3 => 1.0 + x + wobble * (3.0 * x).cos(),
                _ => 5.0 * (2.0 * x).cos(),
            }
        };
        (m, n, (0..m * n).map(|k| value(k / n, k % n)).collect())
    }

    /// The normal equations' step, condition number and variances agree with the QR's
    /// (`solve`) on columns of scales 1e-3 to 1e3 (the next test's, less nearly dependent:
    /// condition of the scaled J under `NORMAL_CONDITION`); on the next test's own columns
    /// (condition 5.5e4) it declines and leaves them to the QR.
    #[test]
    fn normal_statistics_agree_with_the_qr() {
        let (m, n, j) = test_jacobian(0.3);
        let r: Vec<f64> = (0..m).map(|i| (i as f64 * 0.37).cos()).collect();
        let qr = solve(&j, n, &r).unwrap();
        let normal = normal_statistics(&j, n, &r).expect("condition under NORMAL_CONDITION");
        assert!(qr.condition > 10.0, "a test matrix whose scaling matters");
        // Relative errors of the normal equations ~κ²·ε ≈ 1e6·2e-16 (and the QR's ~κ·ε):
        // 1e-6 covers them with a wide margin and catches any wrong scale or index.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs().max(1e-300);
        assert!(
            close(normal.condition, qr.condition),
            "{} vs {}",
            normal.condition,
            qr.condition
        );
        for c in 0..n {
            assert!(close(normal.variances[c], qr.variances[c]), "variance {c}");
            assert!(close(normal.delta[c], qr.delta[c]), "step {c}");
        }
    }

    /// The variances from the pivoted QR are diag((JᵀJ)⁻¹) computed independently by nalgebra
    /// from the normal equations (checks the permutation's direction and the scaling).
    #[test]
    fn variances_are_the_diagonal_of_the_inverse_normal_matrix() {
        // Columns of very different scales and a near-dependence, so pivoting reorders them.
        let (m, n, j) = test_jacobian(1e-2);
        let r = vec![0.0; m];
        assert!(
            normal_statistics(&j, n, &r).is_none(),
            "κ above NORMAL_CONDITION"
        );
        let step = solve(&j, n, &r).unwrap();
        let jn = nalgebra::DMatrix::from_fn(m, n, |i, c| j[i * n + c]);
        let inv = (jn.transpose() * &jn).try_inverse().unwrap();
        for c in 0..n {
            let rel = (step.variances[c] - inv[(c, c)]).abs() / inv[(c, c)];
            // Normal equations square the condition (~1e6 here): 1e-6 covers their round-off.
            assert!(
                rel < 1e-6,
                "column {c}: {} vs {}",
                step.variances[c],
                inv[(c, c)]
            );
        }
    }
}
