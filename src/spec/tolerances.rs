//! `tolerances:` → [`model::tolerances::PartTolerances`](crate::model::tolerances::PartTolerances): bands non-negative, a scene that exists and
//! uses the exact geometry, a study that can run, and bands no draw of which takes a part out
//! of its mesh (the largest draw of every part, placed where it hurts most, must pass the
//! rules of an as-built state, [`spec::deviations::check`](crate::spec::deviations::check)).

use super::raw::RawTolerances;
use super::values::named;
use crate::error::{Error, Result};
use crate::model::tolerances::{
    Distribution, Kind, PartTolerances, HOLE_KINDS, NORMAL_CUT_SIGMA, PIN_KINDS, ROLLER_KINDS,
};
use crate::model::{
    CentreDeviation, Design, Deviations, GeometryMode, Limits, Modification, RollerDeviation, Scene,
};
use crate::numeric;

const KEY: &str = "tolerances";

fn invalid(key: &str, message: String) -> Error {
    Error::invalid(format!("{KEY}.{key}"), message)
}

/// Default number of samples: the 0.135 % quantiles are then order statistics 1 and 999.
pub(crate) const DEFAULT_SAMPLES: usize = 1000;

/// Largest study: 10⁹ samples, a cluster's job array of shards.
pub(crate) const MAX_SAMPLES: i64 = 1_000_000_000;

/// A study's sample count (the spec's `samples` or `--samples`), or what is wrong with it.
/// (Wide enough for both: the spec's is an i64, the flag's a usize.)
pub(crate) fn sample_count(n: i128) -> std::result::Result<usize, String> {
    match usize::try_from(n) {
        Ok(count) if (1..=MAX_SAMPLES as i128).contains(&n) => Ok(count),
        _ => Err(format!("must be 1 to {MAX_SAMPLES}, got {n}")),
    }
}

/// The validated `tolerances:` of a spec whose design, modification, scenes and limits are
/// `design`, `m`, `scenes` and `limits`.
pub(crate) fn build(
    raw: &RawTolerances,
    (design, m): (&Design, &Modification),
    scenes: &[Scene],
    limits: &Limits,
) -> Result<PartTolerances> {
    let mut bands_mm = raw.bands();
    for (kind, band) in Kind::ALL.into_iter().zip(&mut bands_mm) {
        if !(band.is_finite() && *band >= 0.0) {
            return Err(invalid(
                kind.name(),
                format!(
                    "a tolerance band ±b must be zero (not toleranced) or positive, got {}",
                    numeric::input(*band)
                ),
            ));
        }
    }
    let distribution = named(&format!("{KEY}.distribution"), raw.distribution.as_deref())?
        .unwrap_or(Distribution::Normal);
    let scene = super::scenes::scene_index(scenes, &raw.scene, &format!("{KEY}.scene"))?;
    super::scenes::refuse_duty(scenes, scene, &format!("{KEY}.scene"), "a tolerance study")?;
    if scenes[scene].geometry != GeometryMode::Exact {
        return Err(invalid(
            "scene",
            format!(
                "scene `{}` uses the first-order geometry; part deviations are computed with the \
                 exact geometry only: give the scene `geometry: exact` or choose another scene",
                raw.scene
            ),
        ));
    }
    let samples = raw.samples.unwrap_or(DEFAULT_SAMPLES as i64);
    let samples = sample_count(samples.into()).map_err(|m| invalid("samples", m))?;
    let seed = raw.seed.unwrap_or(0);
    if seed < 0 {
        return Err(invalid(
            "seed",
            format!("must be zero or positive, got {seed}"),
        ));
    }
    let rate = raw.max_failure_rate;
    if !(rate.is_finite() && (0.0..=1.0).contains(&rate)) {
        return Err(invalid(
            "max_failure_rate",
            format!(
                "a failure rate is a fraction in [0, 1], got {}",
                numeric::input(rate)
            ),
        ));
    }
    let tol = PartTolerances {
        bands_mm,
        distribution,
        scene,
        samples,
        seed: seed as u64,
        max_failure_rate: rate,
    };
    // With every band 0 each sample is the nominal reducer: a rate of 0 or 1 that no sample
    // count could make more certain; `check` judges the nominal.
    if tol.toleranced().next().is_none() {
        return Err(Error::invalid(
            KEY,
            "every band is 0: nothing is toleranced, and every sample would be the nominal \
             reducer; give a band > 0 (e.g. roller_radial_mm), or judge the nominal with \
             `cycloid check`"
                .into(),
        ));
    }
    largest_draws_fit(&tol, design, m)?;
    drawn_periods(&tol, design, scenes, limits)?;
    Ok(tol)
}

/// The study's scene keeps the rules that hold on the reducer as drawn: a bearing life over
/// whole loaded periods ([`spec::bearing_life`](crate::spec::bearing_life)). The draws replace
/// the spec's deviations, and every draw moves each part of a toleranced kind (a draw of
/// exactly zero has probability zero), so the reducer with every toleranced part at its band
/// repeats with the period of every sample.
fn drawn_periods(
    tol: &PartTolerances,
    design: &Design,
    scenes: &[Scene],
    limits: &Limits,
) -> Result<()> {
    let d = design;
    let params = crate::model::tolerances::parameters(tol, d.rollers, d.pins.count, d.discs);
    let bands: Vec<f64> = params.iter().map(|p| tol.band_mm(p.kind)).collect();
    let drawn = Design {
        deviations: crate::model::tolerances::deviations(
            &params,
            &bands,
            (d.rollers, d.pins.count, d.discs),
        ),
        ..design.clone()
    };
    let kinds: Vec<String> = tol
        .toleranced()
        .map(|k| format!("{KEY}.{}", k.name()))
        .collect();
    let what = format!("the parts the tolerance study draws: {}", kinds.join(", "));
    let scene = (tol.scene, &scenes[tol.scene]);
    super::bearing_life::check_built(limits, &drawn, std::iter::once(scene), &what)
}

/// The kinds whose deviations one rule of an as-built state judges together.
const GROUPS: [&[Kind]; 5] = [
    &[Kind::Eccentricity],
    &ROLLER_KINDS,
    &PIN_KINDS,
    &HOLE_KINDS,
    &[Kind::Shift, Kind::Equidistant],
];

/// Every part at its largest draw (`PartTolerances::largest_draw_mm`), placed where it hurts most,
/// keeps the rules of an as-built state: no part moves by e or more, neighbouring rollers
/// (moved towards each other, inward, and grown) do not overlap, and the profile ground at
/// each corner of the grinding errors is a disc. A group of kinds that breaks a rule is named
/// by its first toleranced key.
fn largest_draws_fit(tol: &PartTolerances, design: &Design, m: &Modification) -> Result<()> {
    let cut = |k: Kind| tol.largest_draw_mm(k);
    for group in GROUPS {
        let Some(&first) = group.iter().find(|&&k| tol.band_mm(k) > 0.0) else {
            continue;
        };
        for d in worst_states(group, &cut, design) {
            let built = Design {
                deviations: d,
                ..design.clone()
            };
            super::deviations::check(&built, m).map_err(|e| {
                let how = match tol.distribution {
                    Distribution::Normal => format!(
                        "the normal is cut at {NORMAL_CUT_SIGMA}σ = 2 × band, so a part can be \
                         drawn up to twice its band"
                    ),
                    Distribution::Uniform => "a uniform draw reaches the band".into(),
                };
                invalid(
                    first.name(),
                    format!(
                        "band too large: a part drawn at the edge of its band breaks a rule of \
                         the as-built reducer ({how}): {}",
                        e.message
                    ),
                )
            })?;
        }
    }
    Ok(())
}

/// The as-built states at the largest draws of the kinds of `group`.
fn worst_states(group: &[Kind], cut: &dyn Fn(Kind) -> f64, design: &Design) -> Vec<Deviations> {
    let one = Deviations::default();
    match group[0] {
        Kind::Eccentricity => vec![Deviations {
            eccentricity_mm: cut(Kind::Eccentricity),
            ..one
        }],
        // Neighbours moved towards each other (tangential signs alternate), inward, grown.
        Kind::RollerRadial => vec![Deviations {
            rollers: (0..design.rollers)
                .map(|i| RollerDeviation {
                    centre: CentreDeviation {
                        radial_mm: -cut(Kind::RollerRadial),
                        tangential_mm: if i % 2 == 0 { 1.0 } else { -1.0 }
                            * cut(Kind::RollerTangential),
                    },
                    radius_mm: cut(Kind::RollerRadius),
                })
                .collect(),
            ..one
        }],
        Kind::PinRadial => vec![Deviations {
            pins: vec![
                CentreDeviation {
                    radial_mm: cut(Kind::PinRadial),
                    tangential_mm: cut(Kind::PinTangential),
                };
                design.pins.count
            ],
            ..one
        }],
        Kind::HoleRadial => vec![Deviations {
            holes: vec![
                vec![
                    CentreDeviation {
                        radial_mm: cut(Kind::HoleRadial),
                        tangential_mm: cut(Kind::HoleTangential),
                    };
                    design.pins.count
                ];
                design.discs
            ],
            ..one
        }],
        _ => [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .into_iter()
            .map(|(s, q)| Deviations {
                shift_mm: s * cut(Kind::Shift),
                equidistant_mm: q * cut(Kind::Equidistant),
                ..Deviations::default()
            })
            .collect(),
    }
}
