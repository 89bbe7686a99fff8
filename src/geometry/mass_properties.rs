//! Area properties of the disc's face: the region inside the exact modified profile less the
//! output-pin holes and the bore (the outline, holes and bore of `disc_solid`): the profile by
//! Green's theorem over its parameter (`profile_moments`, to round-off), the circles in closed
//! form. Disc frame (origin at the disc centre), mm.

use super::disc_solid::Circle;
use super::polyline::polyline;
use super::profile::Profile;
use super::{cross, Vec2};
use crate::model::{Design, Modification};
use crate::units;
use std::f64::consts::PI;

/// How close two successive trapezoid sums of the profile's moments must agree, relative to
/// their size (`profile_moments`): the finer sum is then far closer still, the rule
/// converging geometrically on a periodic analytic integrand. Above it, the floor of a sum of
/// n terms' round-off, 8·√n·ε (4e-13 at 160,000 points, where two sums were seen to differ by
/// their round-off alone).
pub const PROFILE_MOMENTS_REL_TOL: f64 = 1e-13;

/// The most points per lobe `profile_moments` doubles to (2^14). The convergence rate falls
/// as the locus factor K1 = e·np/R' nears 1 (the branch point of |C'| nears the real axis):
/// at np = 10, K1 = 0.99 converges at 20,481 points, K1 = 0.9995 not by 163,841. Beyond the
/// cap the profile's polygon within `SECTION_TOLERANCE_MM` takes over.
const MOST_POINTS_PER_LOBE: usize = 1 << 14;

/// Chordal tolerance of the profile's polygon where the trapezoid sums do not converge, mm
/// (0.1 µm). A chord is off the curve by at most the tolerance, so the area is off by at most
/// tolerance × perimeter (1e-5 of the shipped disc).
pub const SECTION_TOLERANCE_MM: f64 = 1e-4;

/// The area moments of a plane region about the disc centre: A = ∫dA (mm²), the first moment
/// S = ∫(x, y) dA (mm³) and the polar second moment J = ∫(x² + y²) dA (mm⁴).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AreaMoments {
    pub area_mm2: f64,
    pub first_mm3: Vec2,
    pub polar_mm4: f64,
}

impl AreaMoments {
    /// The centroid S/A, mm.
    pub fn centroid_mm(&self) -> Vec2 {
        self.first_mm3 / self.area_mm2
    }

    /// This region less `other` (which lies inside it).
    pub fn less(self, other: AreaMoments) -> AreaMoments {
        AreaMoments {
            area_mm2: self.area_mm2 - other.area_mm2,
            first_mm3: self.first_mm3 - other.first_mm3,
            polar_mm4: self.polar_mm4 - other.polar_mm4,
        }
    }
}

/// The moments of the polygon through `points` (closed, counter-clockwise; clockwise gives
/// them negated), exact by Green's theorem over each edge (pᵢ, pᵢ₊₁) with cᵢ = pᵢ × pᵢ₊₁:
///   A = ½·Σ cᵢ,  S = ⅙·Σ cᵢ·(pᵢ + pᵢ₊₁),
///   J = (1/12)·Σ cᵢ·(|pᵢ|² + pᵢ·pᵢ₊₁ + |pᵢ₊₁|²).
pub fn polygon_moments(points: &[Vec2]) -> AreaMoments {
    let mut m = AreaMoments::default();
    for (i, &a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        let c = cross(a, b);
        m.area_mm2 += c;
        m.first_mm3 += (a + b) * c;
        m.polar_mm4 += c * (a.norm_squared() + a.dot(&b) + b.norm_squared());
    }
    m.area_mm2 *= 0.5;
    m.first_mm3 /= 6.0;
    m.polar_mm4 /= 12.0;
    m
}

/// The moments of a full circle of radius r about the disc centre, the circle's own
/// πr⁴/2 moved to the disc centre by the parallel-axis theorem:
///   A = πr²,  S = A·c,  J = A·(r²/2 + |c|²).
pub fn circle_moments(circle: &Circle) -> AreaMoments {
    let r = circle.radius_mm;
    let area = PI * r * r;
    AreaMoments {
        area_mm2: area,
        first_mm3: circle.centre * area,
        polar_mm4: area * (0.5 * r * r + circle.centre.norm_squared()),
    }
}

/// The moments of the region inside `profile`, by Green's theorem over its parameter
/// t ∈ [0, 2π) (counter-clockwise), Γ' = `Profile::tangent`:
///   A = ½∮ Γ×Γ' dt,  S = ⅓∮ Γ·(Γ×Γ') dt,  J = ¼∮ |Γ|²·(Γ×Γ') dt
/// (the limits of `polygon_moments`' sums as the edges shrink). Each integrand is periodic and
/// analytic in t, so the trapezoid rule on n equal steps converges geometrically in n
/// (Trefethen & Weideman, "The exponentially convergent trapezoidal rule", SIAM Review 56(3),
/// 2014), at a rate set by the nearest complex singularity of |C'|, which nears the real axis
/// as K1 → 1 (`MOST_POINTS_PER_LOBE`). The steps are about doubled from 32 per lobe until two
/// sums agree within `PROFILE_MOMENTS_REL_TOL` (or their round-off) of the area, of the polar
/// moment and of A·(RMS radius) for S; the finer is returned. A profile that does not converge
/// by the cap is integrated as its polygon within `SECTION_TOLERANCE_MM` (`polygon_moments`),
/// within tolerance × perimeter whatever the profile.
pub fn profile_moments(profile: &Profile) -> AreaMoments {
    let lobes = profile.rollers.max(1);
    // Odd counts, each 2n − 1 after n: two successive counts share no factor, so no harmonic
    // of the integrand aliases onto the mean in both sums alike (with n and 2n the harmonics
    // at multiples of 2n do: on a disc of 9 lobes the first moment's harmonics ±1 + 9k met 640
    // in the sums on 320 and 640 points, which agreed on a centroid 1.1e-5 mm off).
    let mut n = 32 * lobes + 1;
    let mut coarse = trapezoid_moments(profile, n);
    loop {
        n = 2 * n - 1;
        let fine = trapezoid_moments(profile, n);
        if agree(&coarse, &fine, n) {
            return fine;
        }
        if n >= MOST_POINTS_PER_LOBE * lobes {
            let outline: Vec<Vec2> = (polyline(profile, SECTION_TOLERANCE_MM).iter())
                .map(|p| p.point)
                .collect();
            return polygon_moments(&outline);
        }
        coarse = fine;
    }
}

/// Whether two estimates of the same moments, the finer a sum of `n` terms, agree within
/// `PROFILE_MOMENTS_REL_TOL` or the sum's round-off.
fn agree(a: &AreaMoments, b: &AreaMoments, n: usize) -> bool {
    let tol = PROFILE_MOMENTS_REL_TOL.max(8.0 * (n as f64).sqrt() * f64::EPSILON);
    let radius = (b.polar_mm4 / b.area_mm2).abs().sqrt();
    (a.area_mm2 - b.area_mm2).abs() <= tol * b.area_mm2.abs()
        && (a.polar_mm4 - b.polar_mm4).abs() <= tol * b.polar_mm4.abs()
        && (a.first_mm3 - b.first_mm3).norm() <= tol * b.area_mm2.abs() * radius
}

/// The trapezoid sums of `profile_moments`' integrals on `n` equal steps of t.
fn trapezoid_moments(profile: &Profile, n: usize) -> AreaMoments {
    let h = std::f64::consts::TAU / n as f64;
    let mut m = AreaMoments::default();
    for i in 0..n {
        let t = h * i as f64;
        let (p, d) = (profile.point(t), profile.tangent(t));
        let c = cross(p, d);
        m.area_mm2 += c;
        m.first_mm3 += p * c;
        m.polar_mm4 += c * p.norm_squared();
    }
    m.area_mm2 *= 0.5 * h;
    m.first_mm3 *= h / 3.0;
    m.polar_mm4 *= 0.25 * h;
    m
}

/// Mass properties of one disc, a prism of its face over the face width B: m = ρ·B·A (kg),
/// J_c = ρ·B·J (kg·mm², about the disc centre, the axis of its own turning) and the centroid's
/// distance from the disc centre (mm; zero for a disc as drawn, by its symmetry).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscMass {
    pub face: AreaMoments,
    pub mass_kg: f64,
    pub inertia_kgmm2: f64,
    pub centroid_offset_mm: f64,
}

impl DiscMass {
    /// The disc whose face lies inside `profile` (`profile_moments`) less `holes` and `bore`
    /// (which the design rules keep inside the profile and apart), `face_width_mm` thick, at
    /// `density_kg_per_mm3`: the face's moments over the face width. Every disc mass is this
    /// call: `disc_mass` for a spec's design, the design search's candidate before its design
    /// exists.
    pub fn of_face(
        profile: &Profile,
        holes: &[Circle],
        bore: Option<&Circle>,
        face_width_mm: f64,
        density_kg_per_mm3: f64,
    ) -> DiscMass {
        let face = (holes.iter().chain(bore))
            .fold(profile_moments(profile), |m, c| m.less(circle_moments(c)));
        let per_mm2 = density_kg_per_mm3 * face_width_mm;
        DiscMass {
            face,
            mass_kg: per_mm2 * face.area_mm2,
            inertia_kgmm2: per_mm2 * face.polar_mm4,
            centroid_offset_mm: face.centroid_mm().norm(),
        }
    }

    /// The disc's share of the inertia at the input, kg·mm²: m·e² + J_c/nc². The disc's centre
    /// orbits at the crank's ω on a circle of radius e and the disc turns at −ω/nc (MODEL.md
    /// "Conventions": ψ0 = −φ/nc), so its kinetic energy is ½·(m·e² + J_c/nc²)·ω², taken
    /// about its centre; a centroid off the centre by d adds a term m·e·d·ω²/nc·cos(…) that
    /// averages to zero over a turn.
    pub fn input_inertia_kgmm2(&self, eccentricity_mm: f64, teeth: usize) -> f64 {
        self.orbit_inertia_kgmm2(eccentricity_mm) + self.turning_inertia_kgmm2(teeth)
    }

    /// m·e², kg·mm²: the orbit's share of `input_inertia_kgmm2`.
    pub fn orbit_inertia_kgmm2(&self, eccentricity_mm: f64) -> f64 {
        self.mass_kg * eccentricity_mm * eccentricity_mm
    }

    /// J_c/nc², kg·mm²: the disc's own turning at −ω/nc, its share of `input_inertia_kgmm2`.
    pub fn turning_inertia_kgmm2(&self, teeth: usize) -> f64 {
        let nc = teeth as f64;
        self.inertia_kgmm2 / (nc * nc)
    }

    /// F = m·e·ω², N: the centripetal force that keeps this disc's centre on its orbit of
    /// radius `eccentricity_mm` at the crank speed `crank_rad_per_s` (kg · mm · 1e-3 m/mm ·
    /// rad²/s²), the force the crank bearing carries at zero torque.
    pub fn centripetal_force_n(&self, eccentricity_mm: f64, crank_rad_per_s: f64) -> f64 {
        self.mass_kg * units::m_from_mm(eccentricity_mm) * crank_rad_per_s * crank_rad_per_s
    }
}

/// One disc of `design` under `modification`, as ground (`Profile::as_ground`, the profile
/// every check runs on): the face inside it (`profile_moments`), less the output-pin holes and
/// the bore of `disc_solid`, over the face width at the design's density. The one home of a
/// disc's mass: the results' mass properties, the design search's mass objective and the
/// centripetal force of `Effect::Inertia` read it.
pub fn disc_mass(design: &Design, modification: &Modification) -> DiscMass {
    let profile = Profile::as_ground(design, modification);
    let holes = super::disc_solid::pin_holes(&design.pins, design.hole_radius_mm());
    let bore = super::disc_solid::bore(design);
    DiscMass::of_face(
        &profile,
        &holes,
        bore.as_ref(),
        design.face_width_mm,
        design.density_kg_per_mm3,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::disc_solid::circle_polygon;

    /// A regular n-gon inscribed in a circle of radius r has A = (n/2)·r²·sin(2π/n) and
    /// J = (n/12)·r⁴·sin(2π/n)·(2 + cos(2π/n)) (each triangle from the centre); the
    /// polygon integration must give them to round-off (1e-12 relative: a sum of n terms of
    /// size r⁴).
    #[test]
    fn regular_polygon_matches_its_closed_form() {
        let circle = Circle {
            centre: Vec2::zeros(),
            radius_mm: 7.0,
        };
        let points = circle_polygon(&circle, 1e-3, false);
        let n = points.len() as f64;
        let (s, c) = (std::f64::consts::TAU / n).sin_cos();
        let m = polygon_moments(&points);
        let r: f64 = 7.0;
        assert!((m.area_mm2 / (0.5 * n * r * r * s) - 1.0).abs() < 1e-12);
        assert!((m.polar_mm4 / (n / 12.0 * r.powi(4) * s * (2.0 + c)) - 1.0).abs() < 1e-12);
        assert!(m.first_mm3.norm() < 1e-9);
    }
}
