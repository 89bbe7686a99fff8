//! What a search that found no feasible design missed: per requirement, how many of the
//! evaluated designs met it, passed it at the screen, missed it (with the closest miss) or
//! were stopped before it was judged; and the cause, the requirements no design met or, when
//! each was met by some design, the smallest combinations no design met together.

use super::evaluate::{Evaluation, Stage};
use super::failure::{Failure, Requirement};
use crate::model::requirements::Requirements;
use crate::model::Crowning;

/// What became of one requirement in one design.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Judged and met at the stage that decides it (the rules for the envelope and rules, the
    /// full check for the torque and the limits).
    Met,
    /// Passed at the screen (a quarter of the crank angles), the design then stopped there or
    /// at the full check by another requirement: not decided, not missed.
    PassedScreen,
    /// Missed.
    Missed,
    /// Not judged: the design stopped before a stage that judges it.
    NotJudged,
}

/// A design stopped at the end of `stage` can have missed `r` there: the rules (no physics)
/// at the first; the torque and the limits the screen judges (extremes over the crank angles,
/// `evaluate::screened`) at the screen or the full check; the other limits (means, lives, the
/// torsion loop) at the full check only.
pub fn missed_at(r: &Requirement, stage: Stage) -> bool {
    match r {
        Requirement::Torque => stage != Stage::Rules,
        Requirement::Limit(def) if super::evaluate::screened(def) => stage != Stage::Rules,
        Requirement::Limit(_) => stage == Stage::Full,
        _ => stage == Stage::Rules,
    }
}

/// The verdict on `r` of the design `e`: its failures list every requirement it missed at
/// the last stage it reached (`missed_at`), so one not listed was met when that
/// stage decides it.
pub fn verdict(e: &Evaluation, r: &Requirement) -> Verdict {
    if e.failures.iter().any(|f| &f.requirement == r) {
        return Verdict::Missed;
    }
    // A scene that could not be computed (the torque) judged no limit at its stage.
    let torque = e
        .failures
        .iter()
        .any(|f| f.requirement == Requirement::Torque);
    match (r, e.stage) {
        (Requirement::SpecRule(_), Stage::Rules) => Verdict::NotJudged,
        (Requirement::Torque | Requirement::Limit(_), Stage::Rules) => Verdict::NotJudged,
        (Requirement::Torque, Stage::Screen) => Verdict::PassedScreen,
        (Requirement::Limit(_), Stage::Full) if !torque => Verdict::Met,
        (Requirement::Limit(_), Stage::Screen) if torque => Verdict::NotJudged,
        // Stopped at the screen by another limit, or at the full check by the torque.
        (Requirement::Limit(def), _) if super::evaluate::screened(def) => Verdict::PassedScreen,
        (Requirement::Limit(_), _) => Verdict::NotJudged,
        _ => Verdict::Met,
    }
}

/// One requirement over the evaluated designs.
#[derive(Debug, Clone, PartialEq)]
pub struct Count {
    pub requirement: Requirement,
    /// Designs that met it (`Verdict::Met`).
    pub met: u64,
    /// Designs that passed it at the screen only (`Verdict::PassedScreen`).
    pub passed_screen: u64,
    /// Designs that missed it.
    pub missed: u64,
    /// Designs stopped before it was judged.
    pub not_judged: u64,
    /// The miss of least excess (the best value a design that missed it reached).
    pub closest: Option<Failure>,
}

impl Count {
    /// No design met it, nor passed it at the screen, and some design missed it.
    pub fn never_met(&self) -> bool {
        self.met == 0 && self.passed_screen == 0 && self.missed > 0
    }
}

/// Why no design is feasible.
#[derive(Debug, Clone, PartialEq)]
pub enum Cause {
    /// No design met these (nor passed them at the screen): each design judged on one
    /// missed it.
    NeverMet(Vec<Requirement>),
    /// Each requirement was met or passed by some design, never all by one: the smallest
    /// combinations of requirements that no design met (or passed) together.
    Together(Vec<Vec<Requirement>>),
    /// No design was generated.
    NoDesign,
}

/// What no design met: the designs evaluated, every requirement's count and the cause.
#[derive(Debug, Clone, PartialEq)]
pub struct Infeasible {
    /// Designs evaluated (the global stage and any local refinement).
    pub evaluated: u64,
    /// The requirements file's requirements in its order (envelope, rules, the crown's
    /// start, the limits), then the spec's rules and the torque when some design missed them.
    pub counts: Vec<Count>,
    pub cause: Cause,
}

/// The requirements every design is judged on, in the requirements file's order, then those
/// that show only when missed (a rule of the spec, the torque), in the order first missed.
fn requirements(req: &Requirements, all: &[Evaluation]) -> Vec<Requirement> {
    let mut out = vec![
        Requirement::OuterDiameter,
        Requirement::AxialLength,
        Requirement::MaxK1,
        Requirement::MinRollerGap,
        Requirement::MinLigament,
    ];
    if matches!(req.crowning, Crowning::Circular { .. }) {
        out.push(Requirement::CrownStart);
    }
    let limits: Vec<Requirement> = req
        .limits
        .entries
        .iter()
        .map(|l| Requirement::Limit(l.def))
        .collect();
    let mut shown = Vec::new();
    for f in all.iter().flat_map(|e| &e.failures) {
        let known = out.contains(&f.requirement) || limits.contains(&f.requirement);
        if !known && !shown.contains(&f.requirement) {
            shown.push(f.requirement.clone());
        }
    }
    out.extend(shown);
    out.extend(limits);
    out
}

/// Count `r` over the designs.
fn count(r: Requirement, all: &[Evaluation]) -> Count {
    let mut c = Count {
        requirement: r,
        met: 0,
        passed_screen: 0,
        missed: 0,
        not_judged: 0,
        closest: None,
    };
    for e in all {
        match verdict(e, &c.requirement) {
            Verdict::Met => c.met += 1,
            Verdict::PassedScreen => c.passed_screen += 1,
            Verdict::NotJudged => c.not_judged += 1,
            Verdict::Missed => {
                c.missed += 1;
                let f = e.failures.iter().find(|f| f.requirement == c.requirement);
                if let Some(f) = f {
                    if c.closest.as_ref().is_none_or(|b| f.excess() < b.excess()) {
                        c.closest = Some(f.clone());
                    }
                }
            }
        }
    }
    c
}

/// Checks (a subset against a design's set) spent on the search for the smallest combination
/// no design met; beyond them the combination named is every requirement some design missed
/// (which no design met together: each design missed one of them).
const MAX_CHECKS: usize = 1 << 24;

/// The smallest combinations of `missed` (requirements some design missed, at most 63) that
/// no design met or passed together, each design given as the set of those it met or passed
/// (`cleared`, a bit per requirement).
fn smallest_together(missed: &[Requirement], cleared: &[u64]) -> Vec<Vec<Requirement>> {
    let n = missed.len().min(63);
    let mut distinct: Vec<u64> = cleared.to_vec();
    distinct.sort_unstable();
    distinct.dedup();
    let pick = |set: u64| -> Vec<Requirement> {
        (0..n)
            .filter(|b| set >> b & 1 == 1)
            .map(|b| missed[b].clone())
            .collect()
    };
    let mut spent = 0usize;
    for k in 1..=n {
        let mut found = Vec::new();
        // Every k-subset of the n bits, in increasing order (Gosper's hack).
        let mut set: u64 = (1 << k) - 1;
        while set < 1 << n && spent < MAX_CHECKS {
            spent += distinct.len();
            if !distinct.iter().any(|c| c & set == set) {
                found.push(pick(set));
            }
            let low = set & set.wrapping_neg();
            let up = set + low;
            set = (((up ^ set) >> 2) / low) | up;
        }
        if !found.is_empty() {
            return found;
        }
    }
    vec![pick((1 << n) - 1)]
}

/// What no design met, from every evaluated design of the search.
pub fn diagnose(req: &Requirements, all: &[Evaluation]) -> Infeasible {
    let counts: Vec<Count> = requirements(req, all)
        .into_iter()
        .map(|r| count(r, all))
        .collect();
    let never: Vec<Requirement> = counts
        .iter()
        .filter(|c| c.never_met())
        .map(|c| c.requirement.clone())
        .collect();
    let cause = if all.is_empty() {
        Cause::NoDesign
    } else if !never.is_empty() {
        Cause::NeverMet(never)
    } else {
        let missed: Vec<Requirement> = counts
            .iter()
            .filter(|c| c.missed > 0)
            .map(|c| c.requirement.clone())
            .take(63)
            .collect();
        let cleared: Vec<u64> = all
            .iter()
            .map(|e| {
                missed
                    .iter()
                    .enumerate()
                    .fold(0u64, |set, (b, r)| match verdict(e, r) {
                        Verdict::Met | Verdict::PassedScreen => set | 1 << b,
                        _ => set,
                    })
            })
            .collect();
        Cause::Together(smallest_together(&missed, &cleared))
    };
    Infeasible {
        evaluated: all.len() as u64,
        counts,
        cause,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reqs(n: usize) -> Vec<Requirement> {
        (0..n)
            .map(|k| Requirement::SpecRule(format!("r{k}")))
            .collect()
    }

    /// Three requirements met pairwise by three designs (ab, bc, ca) but never all three:
    /// the smallest combination is the three together; with a fourth design meeting only a,
    /// still the three. Two designs meeting a and b apart: the pair.
    #[test]
    fn the_smallest_combination_is_one_no_design_clears() {
        let r = reqs(3);
        assert_eq!(
            smallest_together(&r, &[0b011, 0b110, 0b101, 0b001]),
            vec![r.clone()]
        );
        let two = reqs(2);
        assert_eq!(smallest_together(&two, &[0b01, 0b10]), vec![two.clone()]);
        // Designs clearing {a, b} and {c}: the pairs {a, c} and {b, c} are never cleared.
        assert_eq!(
            smallest_together(&r, &[0b011, 0b100]),
            vec![
                vec![r[0].clone(), r[2].clone()],
                vec![r[1].clone(), r[2].clone()]
            ]
        );
    }
}
