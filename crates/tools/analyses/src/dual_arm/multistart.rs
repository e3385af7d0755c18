//! The default answer: the cheapest of the extremals that the shooting method reaches
//! from several starts, checked to be a local minimum.
//!
//! A single shooting run converges to whichever extremal its guess leads to (from the
//! paper's unlocked guess on path A one that costs 13 % more than the minimum). So the
//! shooting is started from a deterministic set: the given guess (or, when it is out of
//! reach at tf, the best-conditioned reachable point of a lattice around it), the final
//! redundant joints of the direct method started from that guess, and each of these
//! moved by `+-spread` along every redundant joint. Converged extremals are merged when
//! their final redundant joints agree to 1e-6 rad (modulo 2 pi), listed by cost, and the
//! cheapest is checked by [`check_local_minimum`].

use super::DualArmError;
use super::direct::{DirectOptions, DirectSolution, solve_direct};
use super::kinematics::{joint_name, nearest_angle};
use super::locks::Chain;
use super::optimality::{CheckOptions, MinimumCheck, check_local_minimum};
use super::paths::Path;
use super::reach::check_path_in_reach;
use super::shooting::{PmpSolution, Shooting, ShootingOptions};
use rayon::prelude::*;

/// Final redundant joints closer than this (rad, modulo 2 pi) are one extremal.
const SAME_EXTREMAL: f64 = 1e-6;

/// Settings of the multi-start search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultiStartOptions {
    /// The shooting method run from every start.
    pub shooting: ShootingOptions,
    /// The direct method whose final joints are a start.
    pub direct: DirectOptions,
    /// Offset of the spread starts along each redundant joint, rad.
    pub spread: f64,
    /// Lattice step of the search for a reachable start when the guess is out of
    /// reach at tf, rad.
    pub lattice_step: f64,
    /// The local-minimum check of the cheapest extremal.
    pub check: CheckOptions,
}

impl Default for MultiStartOptions {
    fn default() -> Self {
        Self {
            shooting: ShootingOptions::default(),
            direct: DirectOptions {
                intervals: 100,
                ..DirectOptions::default()
            },
            spread: 0.25,
            lattice_step: 15f64.to_radians(),
            check: CheckOptions::default(),
        }
    }
}

/// One start of the shooting method: the redundant joints at tf (rad) and where they
/// come from.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    pub label: String,
    pub guess: Vec<f64>,
}

/// A converged extremal and the starts (indices into [`MultiStart::starts`]) that led
/// to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Extremal {
    pub solution: PmpSolution,
    pub starts: Vec<usize>,
}

/// Everything the multi-start search found.
#[derive(Debug, Clone, PartialEq)]
pub struct MultiStart {
    /// Every start with its outcome: the index of its extremal in `extremals`, or why
    /// the shooting failed from it.
    pub starts: Vec<(Start, Result<usize, DualArmError>)>,
    /// The distinct converged extremals, cheapest first.
    pub extremals: Vec<Extremal>,
    /// The direct method from the (reachable) guess, or why it failed.
    pub direct: Result<DirectSolution, DualArmError>,
}

/// The default answer: the cheapest extremal and its local-minimum check.
#[derive(Debug, Clone, PartialEq)]
pub struct BestPath {
    pub search: MultiStart,
    /// The check of `search.extremals[0]`, or why it could not be made.
    pub check: Result<MinimumCheck, DualArmError>,
}

impl BestPath {
    /// The returned path: the cheapest extremal.
    pub fn best(&self) -> &PmpSolution {
        &self.search.extremals[0].solution
    }
}

/// Shoots from every start and lists the distinct extremals by cost. Errors only when
/// the guess is malformed or no start converges (then with the guess's own failure).
pub fn multi_start(
    chain: &Chain,
    path: &dyn Path,
    guess: &[f64],
    options: MultiStartOptions,
) -> Result<MultiStart, DualArmError> {
    check_path_in_reach(chain, path, 1000)?;
    let tf = path.end();
    let first = match chain.complete(guess, path.position(tf), None, tf) {
        Ok(_) => Start {
            label: "the guess".into(),
            guess: guess.to_vec(),
        },
        Err(DualArmError::Unreachable { .. }) => {
            best_conditioned_start(chain, path, guess, options)?
        }
        Err(e) => return Err(e),
    };
    let direct = solve_direct(chain, path, &first.guess, options.direct);
    let mut centres = vec![first];
    if let Ok(d) = &direct {
        let last = d.trajectory.joints.last().copied().unwrap_or_default();
        centres.push(Start {
            label: "the direct method's final joints".into(),
            guess: chain.redundant_joints().iter().map(|&j| last[j]).collect(),
        });
    }
    let starts = spread_starts(chain, &centres, options.spread);
    let shooting = Shooting::new(chain, path, options.shooting);
    let outcomes: Vec<Result<PmpSolution, DualArmError>> = starts
        .par_iter()
        .map(|s| shooting.solve(&s.guess))
        .collect();
    let (extremals, indices) = merge(outcomes);
    if extremals.is_empty() {
        return Err(indices.into_iter().next().and_then(Result::err).unwrap_or(
            DualArmError::InvalidInput("no start for the shooting method".into()),
        ));
    }
    Ok(MultiStart {
        starts: starts.into_iter().zip(indices).collect(),
        extremals,
        direct,
    })
}

/// The multi-start search followed by the local-minimum check of the cheapest extremal.
pub fn best_path(
    chain: &Chain,
    path: &dyn Path,
    guess: &[f64],
    options: MultiStartOptions,
) -> Result<BestPath, DualArmError> {
    let search = multi_start(chain, path, guess, options)?;
    let best = &search.extremals[0].solution;
    let check = check_local_minimum(
        chain,
        path,
        &best.redundant_final,
        options.shooting,
        options.check,
    );
    Ok(BestPath { search, check })
}

/// The centres followed by each centre moved by `+-spread` along every redundant
/// joint, duplicates dropped.
fn spread_starts(chain: &Chain, centres: &[Start], spread: f64) -> Vec<Start> {
    let names: Vec<String> = chain
        .redundant_joints()
        .iter()
        .map(|&j| joint_name(j))
        .collect();
    let mut starts: Vec<Start> = centres.to_vec();
    for centre in centres {
        for (i, name) in names.iter().enumerate() {
            for sign in [1.0, -1.0] {
                let mut guess = centre.guess.clone();
                guess[i] += sign * spread;
                let label = format!(
                    "{} {} {spread} rad on {name}",
                    centre.label,
                    if sign > 0.0 { "+" } else { "-" }
                );
                starts.push(Start { label, guess });
            }
        }
    }
    let mut distinct: Vec<Start> = Vec::with_capacity(starts.len());
    for s in starts {
        if !distinct.iter().any(|d| same_joints(&d.guess, &s.guess)) {
            distinct.push(s);
        }
    }
    distinct
}

/// Merges the converged solutions into distinct extremals sorted by cost; returns them
/// and, for each start, the index of its extremal or its error.
fn merge(
    outcomes: Vec<Result<PmpSolution, DualArmError>>,
) -> (Vec<Extremal>, Vec<Result<usize, DualArmError>>) {
    let mut extremals: Vec<Extremal> = Vec::new();
    let mut indices = Vec::with_capacity(outcomes.len());
    for (k, outcome) in outcomes.into_iter().enumerate() {
        indices.push(outcome.map(|solution| {
            let found = extremals
                .iter()
                .position(|e| same_joints(&e.solution.redundant_final, &solution.redundant_final));
            match found {
                Some(i) => {
                    extremals[i].starts.push(k);
                    i
                }
                None => {
                    extremals.push(Extremal {
                        solution,
                        starts: vec![k],
                    });
                    extremals.len() - 1
                }
            }
        }));
    }
    let mut order: Vec<usize> = (0..extremals.len()).collect();
    order.sort_by(|&a, &b| {
        extremals[a]
            .solution
            .pi()
            .total_cmp(&extremals[b].solution.pi())
    });
    let rank: Vec<usize> = (0..order.len())
        .map(|i| order.iter().position(|&o| o == i).unwrap_or(i))
        .collect();
    let mut slots: Vec<Option<Extremal>> = extremals.into_iter().map(Some).collect();
    let sorted = order.iter().filter_map(|&i| slots[i].take()).collect();
    let indices = indices.into_iter().map(|r| r.map(|i| rank[i])).collect();
    (sorted, indices)
}

/// Whether two joint vectors agree to `SAME_EXTREMAL` modulo 2 pi.
fn same_joints(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| nearest_angle(x - y, 0.0).abs() < SAME_EXTREMAL)
}

/// The point of the lattice `guess + step * k` (integer `k`, each `|k| <= pi / step`,
/// so half a turn each way) farthest from a fold of the inverse kinematics at tf: the
/// best-conditioned reachable final pose. Near the guess the reachable points lie on
/// the edge of the reachable set, where the shooting's difference quotients step out.
fn best_conditioned_start(
    chain: &Chain,
    path: &dyn Path,
    guess: &[f64],
    options: MultiStartOptions,
) -> Result<Start, DualArmError> {
    let tf = path.end();
    let step = options.lattice_step;
    let radius = (std::f64::consts::PI / step).floor() as usize;
    let side = 2 * radius + 1;
    let count = side.pow(guess.len() as u32);
    let point = |index: usize| -> Vec<f64> {
        let mut rest = index;
        guess
            .iter()
            .map(|g| {
                let k = (rest % side) as f64 - radius as f64;
                rest /= side;
                g + step * k
            })
            .collect()
    };
    let margin = |s: &[f64]| {
        let q = chain.complete(s, path.position(tf), None, tf).ok()?;
        Some(chain.inverse_kinematics_margin(&q))
    };
    let best = (0..count)
        .into_par_iter()
        .filter_map(|i| Some((margin(&point(i))?, i)))
        .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
    match best {
        Some((_, i)) => Ok(Start {
            label: format!(
                "the best-conditioned final pose on a {:.0} deg lattice about the guess",
                step.to_degrees()
            ),
            guess: point(i),
        }),
        None => chain
            .complete(guess, path.position(tf), None, tf)
            .map(|_| Start {
                label: "the guess".into(),
                guess: guess.to_vec(),
            }),
    }
}
