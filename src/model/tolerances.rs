//! Tolerances of the parts (`tolerances:`): a band per deviation kind, how deviations are
//! distributed in it, and the Monte Carlo study that draws as-built reducers from them
//! (`cycloid tolerance`; MODEL.md "Part deviations"). Engine units (mm).

use super::deviations::{CentreDeviation, Deviations, RollerDeviation};

/// A kind of deviation a tolerance band is given for; the name is the spec key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    /// de, the crank's eccentricity minus the design's (`eccentricity_mm`).
    Eccentricity,
    /// A roller centre's offset outward (`roller_radial_mm`).
    RollerRadial,
    /// A roller centre's offset along its circle, counter-clockwise (`roller_tangential_mm`).
    RollerTangential,
    /// A roller's radius minus the design's (`roller_radius_mm`).
    RollerRadius,
    /// An output pin centre's offset outward (`pin_radial_mm`).
    PinRadial,
    /// An output pin centre's offset along its circle, counter-clockwise (`pin_tangential_mm`).
    PinTangential,
    /// A pin hole centre's offset outward, in its disc (`hole_radial_mm`).
    HoleRadial,
    /// A pin hole centre's offset along its circle, counter-clockwise (`hole_tangential_mm`).
    HoleTangential,
    /// The grinding error of the shift modification ΔRp (`shift_mm`).
    Shift,
    /// The grinding error of the equidistant modification ΔRrp (`equidistant_mm`).
    Equidistant,
}

named!(Kind "deviation kind" {
    Eccentricity => "eccentricity_mm",
    RollerRadial => "roller_radial_mm",
    RollerTangential => "roller_tangential_mm",
    RollerRadius => "roller_radius_mm",
    PinRadial => "pin_radial_mm",
    PinTangential => "pin_tangential_mm",
    HoleRadial => "hole_radial_mm",
    HoleTangential => "hole_tangential_mm",
    Shift => "shift_mm",
    Equidistant => "equidistant_mm",
});

/// The kinds drawn for each roller, in the draw order (`parameters`).
pub const ROLLER_KINDS: [Kind; 3] = [
    Kind::RollerRadial,
    Kind::RollerTangential,
    Kind::RollerRadius,
];
/// The kinds drawn for each output pin, in the draw order.
pub const PIN_KINDS: [Kind; 2] = [Kind::PinRadial, Kind::PinTangential];
/// The kinds drawn for each pin hole of each disc, in the draw order.
pub const HOLE_KINDS: [Kind; 2] = [Kind::HoleRadial, Kind::HoleTangential];

/// How a deviation is distributed in its band ±b.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Distribution {
    /// Normal with σ = b/3 (the band holds 99.73 %), truncated at ±`NORMAL_CUT_SIGMA`·σ.
    Normal,
    /// Uniform over [−b, b].
    Uniform,
}

named!(Distribution "distribution" {
    Normal => "normal",
    Uniform => "uniform",
});

/// Where a normal draw is cut, in σ: a draw beyond ±6σ (probability 2·10⁻⁹) is drawn again.
/// Without a cut a normal part could move by any amount, and a part moved by e or more is out
/// of its mesh; with it, the spec can refuse a band whose largest draw reaches e
/// (`largest_draw_mm`). 6σ = 2b: a part never moves by more than twice its band.
pub const NORMAL_CUT_SIGMA: f64 = 6.0;

/// The `tolerances:` section of a spec.
#[derive(Debug, Clone, PartialEq)]
pub struct PartTolerances {
    /// Half-width b of each kind's band, mm, indexed by `Kind as usize`; 0: not toleranced.
    pub bands_mm: [f64; Kind::ALL.len()],
    /// How the deviations are distributed in their bands (`distribution`; normal by default).
    pub distribution: Distribution,
    /// Index into the spec's scenes of the scene every sample runs.
    pub scene: usize,
    /// How many as-built reducers are drawn, 1 to 10⁹ (`samples`; 1000 by default).
    pub samples: usize,
    /// The seed of the draws (`seed`; 0 by default): sample k depends on (seed, k) alone.
    pub seed: u64,
    /// Largest fraction of the samples that may fail some limit.
    pub max_failure_rate: f64,
}

impl PartTolerances {
    /// The band of `kind`, mm (0: not toleranced).
    pub fn band_mm(&self, kind: Kind) -> f64 {
        self.bands_mm[kind as usize]
    }

    /// The kinds toleranced (a band above 0), in `Kind::ALL`'s order.
    pub fn toleranced(&self) -> impl Iterator<Item = Kind> + '_ {
        Kind::ALL.into_iter().filter(|&k| self.band_mm(k) > 0.0)
    }

    /// Standard deviation of a draw of `kind`, mm: b/3 for the normal (ignoring its cut at 6σ,
    /// which changes σ by 10⁻⁷ relative), b/√3 for the uniform.
    pub fn sigma_mm(&self, kind: Kind) -> f64 {
        let b = self.band_mm(kind);
        match self.distribution {
            Distribution::Normal => b / 3.0,
            Distribution::Uniform => b / 3f64.sqrt(),
        }
    }

    /// The largest |draw| of `kind`, mm: the normal's cut 6σ = 2b, the uniform's band b.
    pub fn largest_draw_mm(&self, kind: Kind) -> f64 {
        match self.distribution {
            Distribution::Normal => NORMAL_CUT_SIGMA * self.sigma_mm(kind),
            Distribution::Uniform => self.band_mm(kind),
        }
    }
}

/// One drawn number: a kind of deviation of one part (`part` the roller, pin or hole index,
/// `disc` the disc of a hole; both 0 for the crank and the grinding errors).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Parameter {
    /// The kind of deviation drawn.
    pub kind: Kind,
    /// The roller, pin or hole index (0 for the crank and the grinding errors).
    pub part: usize,
    /// The disc of a hole (0 for every other part).
    pub disc: usize,
}

impl Parameter {
    /// The column name of the samples CSV: `roller3_radial_mm`, `pin0_tangential_mm`,
    /// `hole2_radial_mm` (`disc1_hole2_radial_mm` with several discs), `shift_mm`.
    pub fn name(&self, discs: usize) -> String {
        // A part's kind is named `{part}_{what}_mm` (`roller_radial_mm`); the crank's and the
        // grinding errors' (`eccentricity_mm`, `shift_mm`) name no part.
        let key = self.kind.name();
        let Some((part, what)) = key.strip_suffix("_mm").and_then(|k| k.split_once('_')) else {
            return key.to_string();
        };
        let disc = if part == "hole" && discs > 1 {
            format!("disc{}_", self.disc)
        } else {
            String::new()
        };
        format!("{disc}{part}{}_{what}_mm", self.part)
    }
}

/// The drawn parameters of a reducer with `rollers`, `pins` and `discs`, in the draw order:
/// the crank eccentricity; per roller its radial, tangential and radius deviation; per pin
/// radial and tangential; per disc, per hole radial and tangential; the shift and equidistant
/// grinding errors. Only kinds with a band are drawn.
pub fn parameters(
    tol: &PartTolerances,
    rollers: usize,
    pins: usize,
    discs: usize,
) -> Vec<Parameter> {
    let one = |kind| Parameter {
        kind,
        part: 0,
        disc: 0,
    };
    let mut all = vec![one(Kind::Eccentricity)];
    let per_part = |all: &mut Vec<Parameter>, disc, count, kinds: &[Kind]| {
        for part in 0..count {
            all.extend(kinds.iter().map(|&kind| Parameter { kind, part, disc }));
        }
    };
    per_part(&mut all, 0, rollers, &ROLLER_KINDS);
    per_part(&mut all, 0, pins, &PIN_KINDS);
    for disc in 0..discs {
        per_part(&mut all, disc, pins, &HOLE_KINDS);
    }
    all.extend([one(Kind::Shift), one(Kind::Equidistant)]);
    all.retain(|p| tol.band_mm(p.kind) > 0.0);
    all
}

/// The as-built state of drawn `values` (one per parameter of `params`) of a reducer with
/// `rollers`, `pins` and `discs`: the parts a kind of which is drawn get one entry each.
pub fn deviations(
    params: &[Parameter],
    values: &[f64],
    (rollers, pins, discs): (usize, usize, usize),
) -> Deviations {
    let mut d = Deviations::default();
    let has = |kinds: &[Kind]| params.iter().any(|p| kinds.contains(&p.kind));
    if has(&ROLLER_KINDS) {
        d.rollers = vec![RollerDeviation::default(); rollers];
    }
    if has(&PIN_KINDS) {
        d.pins = vec![CentreDeviation::default(); pins];
    }
    if has(&HOLE_KINDS) {
        d.holes = vec![vec![CentreDeviation::default(); pins]; discs];
    }
    use Kind::*;
    for (p, &v) in params.iter().zip(values) {
        let slot = match p.kind {
            Eccentricity => &mut d.eccentricity_mm,
            Shift => &mut d.shift_mm,
            Equidistant => &mut d.equidistant_mm,
            RollerRadial => &mut d.rollers[p.part].centre.radial_mm,
            RollerTangential => &mut d.rollers[p.part].centre.tangential_mm,
            RollerRadius => &mut d.rollers[p.part].radius_mm,
            PinRadial => &mut d.pins[p.part].radial_mm,
            PinTangential => &mut d.pins[p.part].tangential_mm,
            HoleRadial => &mut d.holes[p.disc][p.part].radial_mm,
            HoleTangential => &mut d.holes[p.disc][p.part].tangential_mm,
        };
        *slot = v;
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tol(kinds: &[Kind]) -> PartTolerances {
        let mut bands_mm = [0.0; Kind::ALL.len()];
        for &k in kinds {
            bands_mm[k as usize] = 0.01;
        }
        PartTolerances {
            bands_mm,
            distribution: Distribution::Normal,
            scene: 0,
            samples: 1,
            seed: 0,
            max_failure_rate: 0.0,
        }
    }

    /// The draw order and the column names the README documents; each value lands in its part.
    #[test]
    fn parameters_are_in_draw_order_and_land_in_their_part() {
        use Kind::*;
        let t = tol(&[Equidistant, RollerRadius, HoleTangential, Eccentricity]);
        let params = parameters(&t, 2, 1, 2);
        let names: Vec<String> = params.iter().map(|p| p.name(2)).collect();
        assert_eq!(
            names,
            [
                "eccentricity_mm",
                "roller0_radius_mm",
                "roller1_radius_mm",
                "disc0_hole0_tangential_mm",
                "disc1_hole0_tangential_mm",
                "equidistant_mm"
            ]
        );
        let d = deviations(&params, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], (2, 1, 2));
        assert_eq!(d.eccentricity_mm, 1.0);
        assert_eq!((d.rollers[0].radius_mm, d.rollers[1].radius_mm), (2.0, 3.0));
        assert_eq!(d.holes[1][0].tangential_mm, 5.0);
        assert_eq!(d.equidistant_mm, 6.0);
        assert!(d.pins.is_empty());
        assert_eq!(params[3].name(1), "hole0_tangential_mm");
    }
}
