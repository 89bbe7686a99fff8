//! What a run will do and what its numbers leave unsaid, in words: `check --explain`'s plan of
//! every scene (`explain`), the notes a reader of the results must be told (`note`, each of
//! [`engine::scene::notes`](crate::engine::scene::notes)) and the sentence every output gives of a torsion scene's hysteresis.

use crate::contact::fatigue;
use crate::engine::scene::{self, Note, Writes};
use crate::engine::verdict;
use crate::equilibrium::coupling::Coupling;
use crate::equilibrium::pin_beam::PinBeam;
use crate::model::period;
use crate::model::results::TorsionCompliances;
use crate::model::strength::ContactFatigue;
use crate::model::{
    CentreDeviation, ContactLaw, Design, Detail, Deviations, Effect, Face, FrictionModel,
    PinFriction, PinMode, PinSupport, PinSupportKind, Plan, RollerFriction, RollerMode, Scene,
};
use crate::numeric::{input, number, with_unit};
use crate::spec::Spec;
use crate::units;

/// What every output says of a torsion scene's hysteresis.
pub const HYSTERESIS: &str = "hysteresis loss 0: the quasi-static model has no friction, so \
     the loading and unloading branches of the torsion loop coincide";

/// What a torsion scene's reader is told of its hysteresis loss where its loop carries the
/// friction of `reducer.friction` (`engine::torsion`).
pub const HYSTERESIS_FROM_FRICTION: &str = "hysteresis loss from friction: every contact's \
     Coulomb friction (`reducer.friction`, in the balance whichever model the efficiency uses) \
     resists the disc's turn, so the loop's loading and unloading branches part; the branches \
     are in full sliding, the disc held after each reversal until the other branch reaches it \
     (its own lag held, what is in series still twisting); lost motion and backlash are read on \
     the loop's centre line, the rigidity on the branch loading its way, the hysteresis loss and \
     the energy per cycle off the loop the disc traverses: its width at zero torque and its \
     area";

/// The torsion plot's word on its hysteresis: with friction a short one (the whole sentence
/// is in the section's text).
pub fn hysteresis_in_plot(friction: bool) -> &'static str {
    if friction {
        "with friction: loading branch below, unloading above, held after each reversal"
    } else {
        HYSTERESIS
    }
}

/// The hysteresis text of a torsion scene (`HYSTERESIS`, or `HYSTERESIS_FROM_FRICTION` where
/// its loop carries friction).
pub fn hysteresis(friction: bool) -> &'static str {
    if friction {
        HYSTERESIS_FROM_FRICTION
    } else {
        HYSTERESIS
    }
}

/// The compliances of a torsion curve in words, in three lists: those `modelled` (computed
/// by the loaded model), those `not_modelled` (a part the model holds rigid: it adds no twist)
/// and those `given` (the structure's, added as c·T), e.g. modelled "roller contacts
/// (paper_linear law, exact geometry)", "output-pin contacts (paper_linear law)"; not modelled
/// "pin bending (pins rigid)", "crank bearing (rigid)"; given "none (carrier, housing and
/// shafts rigid)".
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CompliancesText {
    /// Computed by the loaded model.
    pub modelled: Vec<String>,
    /// Held rigid by the model (a rigid crank bearing, rigid pins): no twist of theirs.
    pub not_modelled: Vec<String>,
    /// Given in the spec and added (the structure's c·T).
    pub given: Vec<String>,
}

/// The compliances a torsion curve is made of (`CompliancesText`).
pub fn torsion_compliances(c: &TorsionCompliances) -> CompliancesText {
    let mut modelled = vec![format!(
        "roller contacts ({} law, {} geometry)",
        c.contact_law, c.geometry
    )];
    let mut not_modelled = Vec::new();
    if c.pin_contacts {
        modelled.push(format!("output-pin contacts ({} law)", c.contact_law));
    } else {
        not_modelled.push("output pins (rigid output)".into());
    }
    if let Some(s) = &c.pin_bending {
        let discs: Vec<String> = s
            .disc_positions_mm
            .iter()
            .filter(|&&a| a > 0.0)
            .map(|&a| number(a))
            .collect();
        modelled.push(format!(
            "pin bending ({}, {} mm long, disc mid-planes at {} mm from the flange)",
            match s.kind {
                PinSupportKind::Cantilever => "cantilever clamped in the flange",
                PinSupportKind::BothEnds =>
                    "clamped in the flange, simply supported at the far end",
            },
            number(s.length_mm),
            discs.join(", ")
        ));
    } else if c.pin_contacts {
        not_modelled.push("pin bending (pins rigid)".into());
    }
    match c.bearing_stiffness_n_per_mm {
        Some(k) => modelled.push(format!("crank bearing {} N/mm", number(k))),
        None => not_modelled.push("crank bearing (rigid)".into()),
    }
    let given = if c.structure_rad_per_nmm > 0.0 {
        vec![format!(
            "structure (carrier, housing, shafts) {} arcmin per kN·m, added as c·T",
            number(units::arcmin_per_knm(c.structure_rad_per_nmm))
        )]
    } else {
        vec!["none (carrier, housing and shafts rigid)".into()]
    };
    CompliancesText {
        modelled,
        not_modelled,
        given,
    }
}

/// What a torsion scene's reader is told of its contact law: the catalogue figures are
/// measured on reducers, and the paper's linear law is stiffer than Hertz's.
pub fn torsion_law_note(law: ContactLaw) -> &'static str {
    match law {
        ContactLaw::PaperLinear => TORSION_LINEAR_NOTE,
        ContactLaw::HertzNonlinear => TORSION_JOHNSON_NOTE,
    }
}

/// See `torsion_law_note`. The ratio is measured on `specs/reducer-torsion.yaml` (the paper's
/// design and optimum, 20 N·m rated, locked at 0°, 9°, 18°, 27°), the scene solved under both
/// laws: 53.14 against 22.15 N·m/arcmin, the smallest rigidity of the angles under each.
pub const TORSION_LINEAR_NOTE: &str = "Contact law paper_linear (the paper's Eq. 9, a \
     constant stiffness): on the paper's design it gives 2.4 times the torsional rigidity of \
     Johnson's Hertz law (hertz_nonlinear), 53.14 against 22.15 N·m/arcmin \
     (specs/reducer-torsion.yaml); before comparing a rigidity with a catalogue's, solve it \
     with hertz_nonlinear";

/// See `torsion_law_note`.
pub const TORSION_JOHNSON_NOTE: &str = "Contact law hertz_nonlinear (Johnson's logarithmic \
     line-contact law): the paper's linear law would give about 2.4 times this rigidity on \
     the paper's design";

/// A note ([`engine::scene::Note`](crate::engine::scene::Note)) in one line.
pub fn note(n: &Note) -> String {
    match n {
        Note::Hysteresis { scene, friction } => {
            format!("scene `{scene}`: {}", hysteresis(*friction))
        }
        Note::LifeNotRated {
            scene,
            loaded_period_rad,
        } => format!(
            "scene `{scene}`: crank-bearing life not rated: its crank range is not a whole \
             number of loaded periods ({}°), and the equivalent load is a mean over \
             whole load cycles",
            number(units::deg(*loaded_period_rad))
        ),
        Note::LifeHoursNotRated { scene } => format!(
            "scene `{scene}`: crank-bearing life in hours not rated: the scene has no \
             `input_speed_rpm`"
        ),
        Note::LossWattsNotRated { scene } => format!(
            "scene `{scene}`: friction losses in watts (and the temperature) not given: the \
             scene has no `input_speed_rpm`; the efficiency does not depend on the speed"
        ),
        Note::PinsPreloaded {
            scene,
            interference_mm,
            drawn,
        } => format!(
            "scene `{scene}`: {} the crank longer than the pin holes were bored for (e + hole \
             clearance): every output pin is pressed {} µm into its hole at every crank angle, \
             a preload the crank bearing carries whatever the torque; zero hole clearance is \
             ideal only for a crank of the nominal eccentricity",
            match drawn {
                true => "samples drawn with",
                false => "`reducer.deviations` make",
            },
            match drawn {
                true => format!("up to {}", number(units::um(*interference_mm))),
                false => number(units::um(*interference_mm)),
            }
        ),
    }
}

/// Human-readable plan of `check` on `spec` writing `writes` (`check --explain`): what runs, in
/// which scene, and why, with the tolerance study when `tolerance` (`--tolerance`): the discs,
/// every scene, then the studies, the goldens, the accuracy ladder and the tolerance study:
/// everything the run will compute.
pub fn explain(spec: &Spec, writes: Writes, tolerance: bool) -> String {
    let mut out = format!("spec `{}`: {} scene(s)\n", spec.name, spec.scenes.len());
    out += &discs_line(spec);
    out += &friction_lines(spec);
    let mass = crate::engine::mass_properties::mass_properties(spec);
    let unbalances = crate::engine::mass_properties::unbalances(spec, &mass.disc);
    out += &super::mass_properties::explain_design(spec, &mass);
    let deviations = deviation_lines(&spec.design.deviations);
    if !deviations.is_empty() {
        out += &format!(
            "parts as built (reducer.deviations), in force in every scene, exact geometry; \
             gaps repeat every {}°, loaded curves with the pins every {}°:\n",
            number(units::deg(spec.design.mesh_period_rad())),
            number(units::deg(spec.design.loaded_period_rad(
                true,
                period::tilted(&spec.design, &Face::default())
            )))
        );
        for line in deviations {
            out += &format!("  deviation {line}\n");
        }
    }
    for (k, scene) in spec.scenes.iter().enumerate() {
        let plan = scene::plan(spec, scene, writes);
        let first = units::deg(scene.crank_rad.first().copied().unwrap_or(0.0));
        let step = units::deg(crate::numeric::step(&scene.crank_rad));
        let load = match &scene.torque_sweep {
            Some(t) => format!(
                "input locked, output torque looped ±{} N·m ({} steps per quarter)",
                units::nm(t.rated_nmm),
                t.steps
            ),
            None => format!("output torque {} N·m", units::nm(scene.output_torque_nmm)),
        };
        out += &format!(
            "\nscene `{}`: {load}, {} crank angles from {:.4}° in steps of {:.4}°, \
             {} geometry\n",
            scene.name,
            scene.crank_rad.len(),
            first,
            step,
            scene.geometry
        );
        if plan.has(Effect::RollerContact) || plan.has(Effect::OutputPins) {
            out += &format!(
                "  contact law {}, crank bearing {}\n",
                scene.contact_law,
                match scene.bearing_stiffness_n_per_mm {
                    Some(k) => format!("compliant ({k} N/mm)"),
                    None => "rigid".to_string(),
                }
            );
        }
        if plan.has(Effect::Torsion) {
            out += &format!(
                "  note    torsion: per locked crank angle the torsion curve and the catalogue \
                 figures, no loaded curves over the crank angle; {}\n",
                hysteresis(spec.design.friction.is_some())
            );
        }
        if plan.has(Effect::Clearance) {
            out += &format!(
                "  note    min clearance over the whole period of the gaps ({}° of crank), \
                 whatever crank angles the scene samples\n",
                number(units::deg(spec.design.clearance_period_rad()))
            );
        }
        if plan.has(Effect::RollerContact) && !plan.has(Effect::OutputPins) {
            out +=
                "  note    output pins not modelled: loaded TE is the disc lag β alone (βo = 0)\n";
        }
        if plan.has(Effect::Inertia) {
            let unbalance = unbalances.iter().find(|u| u.scene == k);
            out += &super::mass_properties::explain_scene(spec, scene, &mass.disc, unbalance);
        }
        for p in &plan.effects {
            out += &format!("  compute {:<15} {}\n", p.effect.name(), p.reason);
        }
        for p in &plan.details {
            out += &format!(
                "  compute {:<15} part of {}, read by {}\n",
                p.detail.name(),
                p.detail.effect().name(),
                p.read_by.join(", ")
            );
        }
        for d in Detail::ALL {
            if plan.has(d.effect()) && !plan.has_detail(d) {
                out += &format!(
                    "  skip    {} (part of {}; no limit, golden or output file reads it)\n",
                    d.name(),
                    d.effect().name()
                );
            }
        }
        // Without friction there is no efficiency to skip, without a strength figure of the
        // materials or the bearing no strength, without a speed no inertia: the plan reads as
        // before they existed.
        let strength_given = spec.design.strength != Default::default()
            || spec
                .design
                .crank_bearing
                .is_some_and(|b| b.static_load_rating_n.is_some());
        if plan.has(Effect::Strength) {
            out += &strength_lines(spec, scene, &plan);
        }
        let skipped: Vec<&str> = Effect::listed()
            .filter(|e| !plan.has(*e))
            .filter(|e| *e != Effect::Efficiency || spec.design.friction.is_some())
            .filter(|e| *e != Effect::Strength || strength_given)
            .filter(|e| *e != Effect::Inertia || scene.has_speed())
            .map(|e| e.name())
            .collect();
        if !skipped.is_empty() {
            out += &format!("  skip    {} (not asked for)\n", skipped.join(", "));
        }
        let limits: Vec<&str> = (verdict::limits_for(&spec.limits, &plan).iter())
            .map(|l| l.def.key)
            .collect();
        if !limits.is_empty() {
            out += &format!("  limits  {}\n", limits.join(", "));
        }
    }
    out += &studies_text(spec);
    out += &goldens_text(spec);
    out += &ladder_text(spec, writes);
    out += &tolerance_text(spec, tolerance);
    if let Some(m) = &spec.measured {
        out += &format!(
            "\nas built: every scene runs on the disc identified from `{}` (its modification \
             and form error), exact geometry\n",
            m.path
        );
    }
    out
}

/// The formulas a scene that computes `strength` will use, one `formula` line each with its
/// source and this design's numbers, and one `skip` line for each figure the spec gives no input
/// for (`docs/effects/strength.md`).
fn strength_lines(spec: &Spec, scene: &Scene, plan: &Plan) -> String {
    let design = &spec.design;
    let (mut formulas, mut unjudged) = (Vec::new(), Vec::new());
    match (design.pins.support, PinBeam::of(design)) {
        (Some(support), Some(beam)) => {
            // The coupled model's friction on the pins bends them too.
            let pin_friction = scene::coupled_sweep(design, plan)
                .map(|f| Coupling::new(&f, design).pin)
                .filter(|&c| c > 0.0);
            let d_mm = 2.0 * beam.bending_radius_mm;
            formulas.extend(pin_formulas(design, &support, d_mm, pin_friction));
        }
        _ => unjudged.push(
            "pin bending stress and safety: reducer.output_pins.support not given (the pins \
             are rigid, no bending moment is computed)"
                .to_string(),
        ),
    }
    if design.pins.support.is_some() && design.strength.rollers.yield_strength_mpa.is_none() {
        unjudged.push(
            "pin bending safety: yield_strength_mpa not given (reducer.roller_material, or \
             reducer.material without it)"
                .to_string(),
        );
    }
    match fatigue_unjudged(design, scene, plan) {
        Some(why) => unjudged.push(format!("contact fatigue life: {why}")),
        None => formulas.extend(fatigue_formulas(design, scene)),
    }
    match design.crank_bearing.and_then(|b| b.static_load_rating_n) {
        Some(c0) => formulas.push(format!(
            "static safety of the crank bearing s0 = C0/max |Fb|, C0 = {} N, max |Fb| the \
             largest crank-bearing force of the scene{} (ISO 76)",
            input(c0),
            if scene.duty_cycle.is_some() {
                " (of the duty cycle: its peak bin)"
            } else {
                ""
            }
        )),
        None => unjudged.push(
            "static safety: reducer.crank_bearing.static_load_rating_n not given".to_string(),
        ),
    }
    let formulas = formulas.iter().map(|f| format!("  formula {f}\n"));
    let skips = unjudged.iter().map(|u| format!("  skip    {u}\n"));
    formulas.chain(skips).collect()
}

/// The pins' bending, shear and safety formulas for the pin of diameter `d_mm` held by
/// `support` (Roark, Table 8.1 cases 1a and 1c).
fn pin_formulas(
    design: &Design,
    support: &PinSupport,
    d_mm: f64,
    pin_friction: Option<f64>,
) -> Vec<String> {
    let discs = &support.disc_positions_mm[..design.discs];
    let at: Vec<String> = discs.iter().map(|&a| input(a)).collect();
    let moment = match support.kind {
        PinSupportKind::Cantilever => {
            "M = |Σ F_k·a_k| at the clamp (cantilever, Roark Table 8.1 case 1a)".to_string()
        }
        PinSupportKind::BothEnds => format!(
            "M the larger of the moment at the clamp, F·a·(L − a)·(2L − a)/(2L²) for one \
             load, and the moment under each load, R·F·(L − a) with the prop's share \
             R = a²·(3L − a)/(2L³), L = {} mm (propped cantilever, Roark Table 8.1 case 1c)",
            input(support.length_mm)
        ),
    };
    let mut lines = vec![
        format!(
            "pin bending σ_b = 32·M/(π·d³), d = {} mm (the pin that bends), {moment}; F_k \
             disc k's pin force{} at a_k = {} mm from the flange{}",
            input(d_mm),
            pin_friction.map_or(String::new(), |c| format!(
                " (the hole's whole push: its normal force F and the coupled model's Coulomb \
                 force c_p·F along ẑ × e_φk, c_p = {}, F·√(1 + c_p²) in all)",
                number(c)
            )),
            at.join(", "),
            if discs.len() > 1 {
                ", the discs' moments summed as vectors"
            } else {
                ""
            }
        ),
        "pin shear τ = 4·V/(3·A), A = π·d²/4, at the largest shear force V along the pin \
         (the peak of the round section, Jourawski)"
            .to_string(),
    ];
    if let Some(y) = design.strength.rollers.yield_strength_mpa {
        lines.push(format!(
            "pin bending safety = yield/σ_b, yield {} MPa (the rollers' material)",
            input(y)
        ));
    }
    lines
}

/// Why `scene` gets no contact fatigue life, or none when it does.
fn fatigue_unjudged(design: &Design, scene: &Scene, plan: &Plan) -> Option<String> {
    let s = &design.strength;
    if s.disc.contact_fatigue.is_none() && s.rollers.contact_fatigue.is_none() {
        return Some(
            "no contact_fatigue law given (reducer.material or reducer.roller_material)".into(),
        );
    }
    if !scene.has_speed() {
        return Some("the scene has no input_speed_rpm (a life in hours is at a speed)".into());
    }
    if !scene.spans_loaded_periods(design, plan) {
        return Some(format!(
            "the crank range is not a whole number of periods of the reducer as run ({}°): \
             the largest pressure of part of a period is not the reducer's",
            number(units::deg(scene.run_period_rad(design, plan)))
        ));
    }
    None
}

/// The S–N law of each part, the passes per crank turn and the life (or Miner's sum).
fn fatigue_formulas(design: &Design, scene: &Scene) -> Vec<String> {
    let s = &design.strength;
    let law = |f: &ContactFatigue| {
        let endurance = f.endurance_pressure_mpa.map_or(String::new(), |e| {
            format!(", no damage at p ≤ {} MPa", input(e))
        });
        format!(
            "N(p) = {:e}·({} MPa/p)^{}{endurance}",
            f.cycles,
            input(f.pressure_mpa),
            input(f.exponent)
        )
    };
    let (disc, rollers) = (s.disc.contact_fatigue, s.rollers.contact_fatigue);
    // One law of both parts is said once.
    let parts = match (disc, rollers) {
        (Some(d), Some(r)) if d == r => vec![("disc and rollers", disc)],
        _ => vec![("the disc", disc), ("the rollers", rollers)],
    };
    let mut lines: Vec<String> = (parts.into_iter())
        .filter_map(|(part, f)| {
            Some(format!(
                "contact fatigue of {part} {} cycles to failure at the Hertz pressure p \
                 (Basquin's form)",
                law(&f?)
            ))
        })
        .collect();
    let disc_passes = fatigue::disc_passes_per_crank_turn(design.teeth);
    lines.push(format!(
        "passes per crank turn: each disc lobe np/nc = {}/{} = {} (the load turns 1 + 1/nc \
         times in the disc), each roller {} per disc track",
        design.teeth + 1,
        design.teeth,
        number(disc_passes),
        input(fatigue::ROLLER_PASSES_PER_CRANK_TURN)
    ));
    lines.push(match (scene.duty_cycle.as_ref(), scene.input_speed_rpm) {
        (Some(bins), _) => format!(
            "duty cycle of {} bins: Palmgren–Miner, bin i uses up sᵢ·nᵢ·60·passes/N(pᵢ) of a \
             part per hour at its largest pressure pᵢ, the drive flanks (T ≥ 0) and the coast \
             flanks (T < 0) apart, life = 1/max(D_drive, D_coast) h",
            bins.len()
        ),
        (None, rpm) => format!(
            "life = N(p)/(passes·n·60) h at n = {} rpm, p the largest Hertz pressure over the \
             scene's whole periods",
            input(rpm.unwrap_or(0.0))
        ),
    });
    lines
}

/// The discs on the crank: "reducer: 2 discs at crank phases 0°, 180° ..." (MODEL.md "Several
/// discs"); with one disc, one line saying so.
fn discs_line(spec: &Spec) -> String {
    let n = spec.design.discs;
    if n == 1 {
        return "reducer: 1 disc\n".to_string();
    }
    // 360k/n is a whole number of degrees for every allowed count (1 to 4 discs).
    let phases: Vec<String> = (0..n).map(|k| format!("{}°", 360 * k / n)).collect();
    format!(
        "reducer: {n} identical discs at crank phases {} (reducer.discs): every scene solves \
         each disc, and the per-disc quantities are given per disc\n",
        phases.join(", ")
    )
}

/// The friction model and what each path assumes (`reducer.friction`, MODEL.md "Friction,
/// efficiency and heat"); nothing without friction.
fn friction_lines(spec: &Spec) -> String {
    let Some(f) = &spec.design.friction else {
        return String::new();
    };
    let mut out = format!(
        "friction (reducer.friction): the {} model, {}\n",
        f.model,
        match f.model {
            FrictionModel::Loss => {
                "forces of the frictionless balance, each path's loss μ·F·sliding speed \
                 (forces, lags and the other outputs as without friction)"
            }
            FrictionModel::Coupled => {
                "friction μ·F along every contact's tangent inside its balance, the input \
                 torque from the crank's"
            }
        }
    );
    match f.rollers {
        Some(RollerFriction { mode, mu }) => {
            out += &match mode {
                RollerMode::Fixed => format!(
                    "  rollers      fixed, μ {mu}: the disc slides over each roller at the \
                     tangential speed of its contact point, (|P_i − I| − Rrp)·ω/nc unmodified\n"
                ),
                RollerMode::Rotating { bore_radius_mm } => format!(
                    "  rollers      rotating on pins of radius {bore_radius_mm} mm, μ {mu}: they \
                     roll on the disc and slide on their pins at the disc's sliding speed × \
                     r_b/Rrp\n"
                ),
            }
        }
        None => out += "  rollers      no friction (not given)\n",
    }
    match f.output_pins {
        Some(PinFriction { mode, mu }) => {
            out += &match mode {
                PinMode::Fixed => format!(
                    "  output pins  fixed, μ {mu}: each hole slides over its pin at e·Ω, \
                     Ω = ω(1 + 1/nc)\n"
                ),
                PinMode::Sleeve { bore_radius_mm } => format!(
                    "  output pins  free sleeves on pins of radius {bore_radius_mm} mm, μ {mu}: \
                     they roll in the holes and slide on their pins at e·Ω·r_bore/r_pin\n"
                ),
            }
        }
        None => out += "  output pins  no friction (not given)\n",
    }
    match f.crank_bearing {
        Some(b) => {
            out += &format!(
                "  crank bearing μ {} at its bore of {} mm: friction torque μ·|Fb|·d/2 at Ω\n",
                b.mu, b.bore_diameter_mm
            )
        }
        None => out += "  crank bearing no friction (not given)\n",
    }
    let t0 = &f.no_load_torque_nmm;
    if !t0.is_constant() {
        out += &format!(
            "  no-load      a drag at the input over its speed: {} (linear between, held \
             beyond)\n",
            no_load_table(t0)
        );
    } else if t0.max_nmm() > 0.0 {
        out += &format!(
            "  no-load      a drag of {} N·mm at the input\n",
            number(t0.max_nmm())
        );
    }
    out
}

/// A no-load torque table as "0 rpm 20 N·mm, 3000 rpm 60 N·mm".
pub fn no_load_table(t0: &crate::model::NoLoadTorque) -> String {
    (t0.points().iter())
        .map(|[n, t]| format!("{} rpm {} N·mm", number(*n), number(*t)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The optimisation studies (`optimise:`), one line each: scene, objective, variables and the
/// most evaluations the study may take.
fn studies_text(spec: &Spec) -> String {
    if spec.studies.is_empty() {
        return String::new();
    }
    let mut out = String::from("\noptimisation studies (optimise:), each with its checks:\n");
    for s in &spec.studies {
        let objective: Vec<String> = match s.objective.as_slice() {
            [(o, w)] if *w == 1.0 => vec![o.name.to_string()],
            terms => (terms.iter())
                .map(|(o, w)| format!("{} × {}", number(*w), o.name))
                .collect(),
        };
        let variables: Vec<&str> = s.variables.iter().map(|v| v.kind.key()).collect();
        out += &format!(
            "  study `{}` on scene `{}`: minimise {} over {}; at most {} \
             evaluations ({} global and {} boundary samples, {} per local run, verification \
             grid of {} points per variable)\n",
            s.name,
            spec.scenes[s.scene].name,
            objective.join(" + "),
            variables.join(", "),
            crate::engine::optimise::most_evaluations(s),
            s.global_samples,
            s.boundary_samples,
            s.local_evaluations,
            s.verify_grid
        );
    }
    out
}

/// The golden curves (`golden:`), one line each: quantity, scene, disc, file and band.
fn goldens_text(spec: &Spec) -> String {
    if spec.golden.is_empty() {
        return String::new();
    }
    let mut out = String::from("\ngolden curves (golden:), each a check:\n");
    for g in &spec.golden {
        let disc = g.disc.map_or(String::new(), |d| format!(" of disc {d}"));
        out += &format!(
            "  golden {}{disc} of scene `{}` against `{}`, every point within {}\n",
            g.quantity.key,
            g.scene,
            g.file,
            band(g.tolerance.abs, g.quantity.unit, g.tolerance.rel)
        );
    }
    out
}

/// A golden's band abs + rel·|golden| in words, without a term that is zero.
fn band(abs: f64, unit: &str, rel: f64) -> String {
    let abs_text = with_unit(number(abs), unit);
    let rel_text = format!("{} of the golden value", crate::numeric::percent(rel));
    match (abs != 0.0, rel != 0.0) {
        (true, true) => format!("{abs_text} + {rel_text}"),
        (false, true) => rel_text,
        _ => abs_text,
    }
}

/// The accuracy ladder (`accuracy:`): in full with the design review, else only the rungs that
/// judge the scene's resolution.
fn ladder_text(spec: &Spec, writes: Writes) -> String {
    let Some(a) = &spec.accuracy else {
        return String::new();
    };
    let scene = &spec.scenes[a.scene].name;
    if writes.report {
        format!(
            "\naccuracy ladder (accuracy:) on scene `{scene}`: every rung, up to {} crank \
             angles per mesh period, for the design review\n",
            a.options.finest
        )
    } else {
        format!(
            "\naccuracy ladder (accuracy:) on scene `{scene}`: only the rungs that judge \
             whether the scene's crank steps resolve the mesh (the whole ladder runs with \
             --report)\n"
        )
    }
}

/// The tolerance study (`tolerances:`): run with `--tolerance`, said so either way.
fn tolerance_text(spec: &Spec, asked: bool) -> String {
    let Some(t) = &spec.tolerances else {
        return String::new();
    };
    let head = format!(
        "\ntolerance study (tolerances:) on scene `{}`: {} samples, seed {}, allowed failure \
         rate {}",
        spec.scenes[t.scene].name,
        t.samples,
        t.seed,
        crate::numeric::percent(t.max_failure_rate)
    );
    match asked {
        true => format!("{head}: runs (--tolerance), its failure rate one more check\n"),
        false => format!("{head}: skipped (runs with --tolerance, or `cycloid tolerance`)\n"),
    }
}

/// The part deviations in force (`reducer.deviations`), one line each (empty when nominal).
pub fn deviation_lines(d: &Deviations) -> Vec<String> {
    let um = |mm: f64| format!("{:+.3} µm", units::um(mm));
    let mut lines = Vec::new();
    if d.eccentricity_mm != 0.0 {
        lines.push(format!("crank eccentricity {}", um(d.eccentricity_mm)));
    }
    if d.shift_mm != 0.0 || d.equidistant_mm != 0.0 {
        lines.push(format!(
            "grinding: shift {}, equidistant {}",
            um(d.shift_mm),
            um(d.equidistant_mm)
        ));
    }
    let centre = |what: String, c: &CentreDeviation| {
        format!(
            "{what}: radial {}, tangential {}",
            um(c.radial_mm),
            um(c.tangential_mm)
        )
    };
    for (i, r) in d.rollers.iter().enumerate().filter(|(_, r)| !r.is_zero()) {
        let at = centre(format!("roller {i}"), &r.centre);
        lines.push(format!("{at}, radius {}", um(r.radius_mm)));
    }
    for (j, p) in d.pins.iter().enumerate().filter(|(_, p)| !p.is_zero()) {
        lines.push(centre(format!("pin {j}"), p));
    }
    for (k, holes) in d.holes.iter().enumerate() {
        for (j, h) in holes.iter().enumerate().filter(|(_, h)| !h.is_zero()) {
            lines.push(centre(format!("disc {k} hole {j}"), h));
        }
    }
    if !d.form.is_empty() {
        lines.push(format!(
            "form error: {} harmonics of orders {} to {}, |w| ≤ {:.3} µm",
            d.form.len(),
            d.form.iter().map(|f| f.order).min().unwrap_or(0),
            d.form.iter().map(|f| f.order).max().unwrap_or(0),
            units::um(d.form_bound_mm())
        ));
    }
    lines
}
