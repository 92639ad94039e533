//! The contact quantities of the default scene at accuracy targets (issue 28's tolerance
//! table), from a cache of the accuracy ladder: for each tolerance, the step `capstan contact
//! --tol TOL` stops at, and for every reported quantity its value, its relative estimate and
//! rule, its true relative error against a reference and the ratio estimate / true error,
//! with the old rule's ratio beside it; then the time of each tolerance.
//!
//! # Problem
//! The paper's body on the circle (`Scene::default()`, ratio 2, `eps` regularised Coulomb,
//! the default probes at the quarter points). Step `k` of the ladder is
//! `Problem::accuracy_step(k)`: Qp `p = 2 ... 6` graded toward the ends, then the order-6
//! mesh with 2, 4, 8, ... times the elements along `x2`.
//!
//! # Cache
//! `docs/data/contact_ladder.json`: every solved step's quantities, scales, grid, unknowns,
//! wall and CPU time and load average. The ladder is deterministic, so the stop of a
//! tolerance is [`capstan::problem::assess`] and [`AccuracyTarget::met`] on the cached steps,
//! the very functions `Problem::refine_to` calls after each solve; its time is the sum of the
//! cached steps' times (refine_to solves each step once). `--solve LAST` solves the steps up
//! to `LAST` missing from the cache (the cache is rewritten after each); `--live TOL` also
//! runs `contact_to` at `TOL` and checks that it stops where the cache says with the same
//! estimates.
//!
//! # Reference
//! The cached step `--reference-step K` (default: the last cached): the "true error" column.
//! Beside it a reference outside the ladder's family: the cached `p6-240x14` (p 6 on 240 x 14
//! elements with the ladder's grading, 1441 x 85 nodes: `--reference-elements 240`; the mesh of
//! the contact work-precision reference, docs/work-precision/contact/contact-reference.json,
//! which it reproduces, and whose values stand in where the cache lacks it).
//!
//! On the transition-graded cache, `--graded-reference P,E2,E3[,STEP] [--face-layers M]` solves
//! a reference outside the ladder (order P on `E2 x E3` cells graded toward the transitions;
//! with M rows toward the contact face, `Problem::face_graded`, graded toward its order-(P-1)
//! twin's transitions when that is cached). The table takes the finest face-graded one
//! (`graded-p10-24x8-f3`, docs/data/contact_reference.json), else the finest graded one.
//!
//! On the transition-graded cache, `--twin K[,K...]` solves the twins of the cached steps K
//! (`Problem::transition_twin`: the step with 3 rows toward the contact face), cached by step:
//! `contact_to` solves the twin of its stop and reports its differences as the estimates (rule
//! `twin`), so the table takes the stop's twin's estimates (and its time), and shows the
//! ladder's own estimates beside them ("ladder's rule est / true").
//!
//! Run: `cargo run --release --example contact_accuracy -- [TOL ...] [--solve LAST]
//! [--reference-step K] [--live TOL] [--twin K,...] [--cache PATH]` (default `1e-3 1e-4
//! 1e-5`). Look at: every
//! true error below its tolerance and every `estimate / true` between 0.5 and 10
//! (docs/verification.md, "The contact tolerance table").

use std::collections::BTreeMap;
use std::time::Instant;

use capstan::commands::accuracy::{behaviour, contact_to, graded_behaviour, probes, scaled};
use capstan::problem::estimate::Rule;
use capstan::problem::{AccuracyTarget, Scaled, assess, assess_twin};
use capstan::scene::Scene;
use capstan_elasticity::solvers::SilentObserver;
use serde::{Deserialize, Serialize};

/// One ladder step as cached.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct CachedStep {
    step: usize,
    grid: Vec<usize>,
    unknowns: usize,
    /// Wall time of the solve, seconds.
    seconds: f64,
    /// CPU time (user + system) of the solve, seconds.
    cpu_seconds: f64,
    /// The one-minute load average when the step finished.
    load_average: f64,
    values: BTreeMap<String, f64>,
    scales: BTreeMap<String, f64>,
    /// The stick/slip transitions this step's solution located (the next graded step's points).
    #[serde(default)]
    located: Vec<f64>,
}

/// The cache file.
#[derive(Debug, Default, Serialize, Deserialize)]
struct Cache {
    scene: String,
    steps: Vec<CachedStep>,
    /// Solves outside the ladder (`--reference-elements E`: p 6, `E x 14` elements, the
    /// ladder's grading), by name `p6-Ex14`.
    #[serde(default)]
    references: BTreeMap<String, CachedStep>,
    /// The ladder: `hp` (`Problem::accuracy_step`, the cache before h28-acc) or
    /// `transition-graded` (`Problem::transition_step`, what `contact_to` climbs since).
    #[serde(default = "hp")]
    ladder: String,
    /// The transition-graded ladder's first pass (`Problem::transition_first_pass`).
    #[serde(default)]
    first_pass: Option<CachedStep>,
    /// The stick/slip transitions the first pass located (the graded ladder's points).
    #[serde(default)]
    transitions: Vec<f64>,
    /// The twins of the transition-graded ladder's steps (`Problem::transition_twin`: the
    /// step with rows toward the contact face), by step (`--twin K`): `contact_to` solves the
    /// stop's twin and takes its differences as the estimates.
    #[serde(default)]
    twins: BTreeMap<usize, CachedStep>,
}

fn hp() -> String {
    "hp".to_owned()
}

impl Cache {
    /// Step `k` of the cached ladder.
    fn problem(
        &self,
        base: &capstan::problem::Problem,
        k: usize,
    ) -> Result<capstan::problem::Problem, capstan::problem::ProblemError> {
        match self.ladder.as_str() {
            "hp" => base.accuracy_step(k),
            // graded toward the transitions the step before located (the first pass's at k = 0),
            // as `contact_to` does
            _ => {
                let before = k
                    .checked_sub(1)
                    .and_then(|j| self.steps.get(j))
                    .map(|s| &s.located)
                    .filter(|l| !l.is_empty())
                    .unwrap_or(&self.transitions);
                base.transition_step(k, before)
            }
        }
    }
}

impl CachedStep {
    /// The step's quantities as `refine_to` saw them (the behaviour by name, as the contact
    /// report classifies them on the hp ladder, and on the graded one: `scaled_graded`).
    fn scaled(&self, graded: bool) -> BTreeMap<String, Scaled> {
        self.values
            .iter()
            .map(|(n, &value)| {
                let behaviour = if graded {
                    graded_behaviour(n)
                } else {
                    behaviour(n)
                };
                let scale = self.scales[n];
                (
                    n.clone(),
                    Scaled {
                        value,
                        scale,
                        behaviour,
                    },
                )
            })
            .collect()
    }
}

/// User + system CPU seconds of this process (`/proc/self/stat`, clock ticks of 1/100 s).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // after the command name in parentheses: utime and stime are the 12th and 13th fields
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let f: Vec<f64> = after
        .split_whitespace()
        .map(|x| x.parse().unwrap_or(0.0))
        .collect();
    (f.get(11).copied().unwrap_or(0.0) + f.get(12).copied().unwrap_or(0.0)) / 100.0
}

fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|x| x.parse().ok()))
        .unwrap_or(f64::NAN)
}

/// Solves one problem of the ladder (or beside it) and records it.
fn solve_step(
    k: usize,
    problem: &capstan::problem::Problem,
    probes: &[f64],
) -> Result<CachedStep, Box<dyn std::error::Error>> {
    let (t, c) = (Instant::now(), cpu_seconds());
    let solved = problem.solve()?;
    let q = scaled(&solved.quantities(probes)?, &solved.solution);
    let step = CachedStep {
        step: k,
        grid: problem.grid(),
        unknowns: solved.model.operator().dof_count(),
        seconds: t.elapsed().as_secs_f64(),
        cpu_seconds: cpu_seconds() - c,
        load_average: load_average(),
        values: q.iter().map(|(n, v)| (n.clone(), v.value)).collect(),
        scales: q.iter().map(|(n, v)| (n.clone(), v.scale)).collect(),
        located: solved.transitions(),
    };
    eprintln!(
        "step {k}: {:?}, {} unknowns, {:.1} s wall, {:.1} s CPU, load {:.1}",
        step.grid, step.unknowns, step.seconds, step.cpu_seconds, step.load_average
    );
    Ok(step)
}

/// The old rule (before h28-est): `max(|d_k|, |d_{k-1}| / 4)` on the values up to step `k`.
fn old_estimate(values: &[f64]) -> Option<f64> {
    let n = values.len();
    (n >= 2).then(|| {
        let d = (values[n - 1] - values[n - 2]).abs();
        if n >= 3 {
            d.max((values[n - 2] - values[n - 3]).abs() / 4.0)
        } else {
            d
        }
    })
}

/// Where a tolerance stops on the cached ladder.
enum Stop {
    /// At this step.
    At(usize),
    /// The next step is over the budget: the worst quantity, its relative estimate, the next
    /// step's unknowns.
    Budget(usize, String, f64, usize),
    /// The cache ends first.
    Uncached(usize),
    /// The ladder's estimates meet the tolerance at this step, whose twin is not cached.
    NoTwin(usize),
}

impl CachedStep {
    /// The twin's estimates of this step, `None` when it is not cached (`--twin K`).
    fn twinned(&self, cache: &Cache) -> Option<capstan::problem::Assessment> {
        let twin = cache.twins.get(&self.step)?;
        Some(assess_twin(&self.scaled(true), &twin.scaled(true)))
    }
}

fn stop(cache: &Cache, target: &AccuracyTarget) -> Stop {
    let mut seen = Vec::new();
    for (k, s) in cache.steps.iter().enumerate() {
        if s.unknowns > target.max_unknowns {
            let a = assess(&seen);
            let (q, w) = a.worst.unwrap_or_default();
            return Stop::Budget(k, q, w, s.unknowns);
        }
        seen.push(s.scaled(cache.ladder != "hp"));
        if target.met(k, &assess(&seen)) {
            if cache.ladder == "hp" {
                return Stop::At(k);
            }
            // the transition-graded ladder: the stop's twin has the last word (`contact_to`)
            match s.twinned(cache) {
                None => return Stop::NoTwin(k),
                Some(a)
                    if a.worst
                        .as_ref()
                        .is_some_and(|(_, w)| *w <= target.tolerance) =>
                {
                    return Stop::At(k);
                }
                Some(_) => {}
            }
        }
    }
    // past the cache: the next step's size from the ladder itself
    let n = cache.steps.len();
    let next = Scene::default()
        .build()
        .and_then(|p| Ok(cache.problem(&p, n)?.unknowns()));
    match next {
        Ok(u) if u > target.max_unknowns => {
            let (q, w) = assess(&seen).worst.unwrap_or_default();
            Stop::Budget(n, q, w, u)
        }
        _ => Stop::Uncached(n),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (mut solve, mut reference_step, mut live, mut path) =
        (None, None, None, "docs/data/contact_ladder.json".to_owned());
    let mut elements: Option<usize> = None;
    let (mut ladder, mut graded): (Option<String>, Option<String>) = (None, None);
    let mut face_layers = 0;
    let mut twin_steps: Vec<usize> = Vec::new();
    let mut tolerances: Vec<f64> = Vec::new();
    let mut i = 0;
    while i < args.len() {
        let next = args.get(i + 1).cloned().unwrap_or_default();
        match args[i].as_str() {
            "--solve" => solve = next.parse::<usize>().ok(),
            "--reference-step" => reference_step = next.parse::<usize>().ok(),
            "--live" => live = next.parse::<f64>().ok(),
            "--reference-elements" => elements = next.parse::<usize>().ok(),
            "--cache" => path = next,
            "--ladder" => ladder = Some(next),
            "--graded-reference" => graded = Some(next),
            "--face-layers" => face_layers = next.parse::<usize>().unwrap_or(0),
            "--twin" => twin_steps.extend(next.split(',').filter_map(|x| x.parse::<usize>().ok())),
            a => {
                tolerances.extend(a.parse::<f64>().ok());
                i += 1;
                continue;
            }
        }
        i += 2;
    }
    if tolerances.is_empty() {
        tolerances = vec![1e-3, 1e-4, 1e-5];
    }
    let mut cache: Cache = std::fs::read_to_string(&path)
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok())
        .unwrap_or_default();
    let scene = Scene::default();
    if let Some(l) = ladder {
        if !cache.steps.is_empty() && cache.ladder != l {
            return Err(format!("{path} caches the {} ladder, not {l}", cache.ladder).into());
        }
        cache.ladder = l;
    }
    if let Some(last) = solve {
        cache.scene = "Scene::default() (the paper's body, ratio 2, default probes)".to_owned();
        let base = scene.build()?;
        let probes = probes(&scene);
        if cache.ladder != "hp" && cache.first_pass.is_none() {
            let first = base.transition_first_pass();
            let (t, c) = (Instant::now(), cpu_seconds());
            let solved = first.solve()?;
            cache.transitions = solved.transitions();
            let mut step = solve_step(usize::MAX, &first, &probes)?;
            // the first pass is solved once: its time is the first solve's
            step.seconds = t.elapsed().as_secs_f64();
            step.cpu_seconds = cpu_seconds() - c - step.cpu_seconds;
            eprintln!("first pass: transitions {:?}", cache.transitions);
            cache.first_pass = Some(step);
        }
        for k in cache.steps.len()..=last {
            let problem = cache.problem(&base, k)?;
            let step = solve_step(k, &problem, &probes)?;
            cache.steps.push(step);
            // after every step: a long run interrupted keeps what it solved
            std::fs::write(&path, serde_json::to_string_pretty(&cache)? + "\n")?;
        }
    }
    for k in twin_steps {
        // the twin of cached step k: its problem (graded toward the transitions step k - 1
        // located) with rows toward the contact face
        if cache.ladder != "hp" && k < cache.steps.len() && !cache.twins.contains_key(&k) {
            let problem = cache.problem(&scene.build()?, k)?.transition_twin()?;
            let mut twin = solve_step(k, &problem, &probes(&scene))?;
            twin.step = k;
            cache.twins.insert(k, twin);
            std::fs::write(&path, serde_json::to_string_pretty(&cache)? + "\n")?;
        }
    }
    if let Some(e) = elements {
        // the order-6 step with its grading, `e` elements along x2
        let mut problem = scene.build()?.accuracy_step(4)?;
        problem.body.n2 = 6 * e + 1;
        let name = format!("p6-{e}x14");
        if let std::collections::btree_map::Entry::Vacant(v) = cache.references.entry(name) {
            v.insert(solve_step(usize::MAX, &problem, &probes(&scene))?);
            std::fs::write(&path, serde_json::to_string_pretty(&cache)? + "\n")?;
        }
    }
    if let Some(spec) = graded {
        // `P,E2,E3[,STEP]`: order P on E2 x E3 cells graded toward the transitions of the cached
        // step STEP (default the last): located by a fine solve, not the first pass; with
        // `--face-layers M` also M rows toward the face (`Problem::face_graded`), graded toward
        // the transitions of the cached reference `graded-p(P-1)-E2xE3-fM` when there is one
        // (the order below it, located with the rows: the first pass is off by its 1e-6)
        let f: Vec<usize> = spec.split(',').filter_map(|x| x.parse().ok()).collect();
        let (p, e2, e3) = (f[0], f[1], f[2]);
        let k = f.get(3).copied().unwrap_or(cache.steps.len() - 1);
        let name = if face_layers > 0 {
            format!("graded-p{p}-{e2}x{e3}-f{face_layers}")
        } else {
            format!("graded-p{p}-{e2}x{e3}")
        };
        if !cache.references.contains_key(&name) {
            let base = scene.build()?;
            let below = format!("graded-p{}-{e2}x{e3}-f{face_layers}", p.saturating_sub(1));
            let at = match cache.references.get(&below).filter(|_| face_layers > 0) {
                Some(r) => {
                    eprintln!(
                        "{name}: graded toward {below}'s transitions {:?}",
                        r.located
                    );
                    r.located.clone()
                }
                None => {
                    let at = cache.problem(&base, k)?.solve()?.transitions();
                    eprintln!("{name}: graded toward step {k}'s transitions {at:?}");
                    at
                }
            };
            let (layers, ratio) = capstan::problem::DEFAULT_TRANSITION_GRADING;
            let mut problem = base
                .corner_mesh(p, [e2, e3])
                .graded_toward(at, layers, ratio)?
                .face_graded(face_layers)?;
            problem.body.settings.corner_layers = capstan::problem::transition_corner_layers(p);
            let step = solve_step(usize::MAX, &problem, &probes(&scene))?;
            cache.references.insert(name, step);
            std::fs::write(&path, serde_json::to_string_pretty(&cache)? + "\n")?;
        }
    }
    if !cache.steps.is_empty() {
        // every step's values, for the record
        for s in &cache.steps {
            eprintln!(
                "step {} {:?} {}: slip {:.10} stick [{:.10}, {:.10}] v2 {:.10e} probe0 {:.10}",
                s.step,
                s.grid,
                s.unknowns,
                s.values["slip_measure"],
                s.values.get("stick_from").copied().unwrap_or(f64::NAN),
                s.values.get("stick_to").copied().unwrap_or(f64::NAN),
                s.values["max_abs_v2"],
                s.values["normal_stress_probe_0"]
            );
        }
    }
    // the reference: `--reference-step K`, else the finest graded reference cached (one with
    // rows toward the face before one without: h28-ref), else the last step
    let graded_reference = cache
        .references
        .iter()
        .filter(|(n, _)| n.starts_with("graded-"))
        .max_by_key(|(n, s)| (n.contains("-f"), s.unknowns))
        .map(|(n, s)| (n.clone(), s.clone()));
    if let Some((n, _)) = &graded_reference {
        println!("reference {n}");
    }
    let Some(reference) = reference_step
        .and_then(|k| cache.steps.get(k))
        .or(graded_reference.as_ref().map(|(_, s)| s))
        .or(cache.steps.last())
    else {
        return Err(format!("no cached ladder in {path}: run with --solve LAST").into());
    };
    let wp: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(
        "docs/work-precision/contact/contact-reference.json",
    )?)?;
    println!(
        "reference: ladder step {}, grid {:?}, {} unknowns ({:.1} s CPU); WP: {}",
        reference.step, reference.grid, reference.unknowns, reference.cpu_seconds, wp["method"]
    );
    println!(
        "| tol | stop (grid, unknowns) | CPU / wall (load) | quantity | value | estimate (rel) | rule | true error (rel) | est / true | vs p 6 240 x 14: true, est / true | old rule est / true | ladder's rule est / true |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for &tol in &tolerances {
        let target = AccuracyTarget::new(tol)?;
        let k = match stop(&cache, &target) {
            Stop::At(k) => k,
            Stop::Budget(k, q, w, u) => {
                let cpu: f64 = cache.steps[..k].iter().map(|s| s.cpu_seconds).sum();
                println!(
                    "| {tol:.0e} | not reached: step {k} ({u} unknowns) is over the budget {}; at step {} the worst is {q} at {w:.1e} ({cpu:.1} s CPU spent) |",
                    target.max_unknowns,
                    k - 1
                );
                continue;
            }
            Stop::Uncached(n) => {
                println!("| {tol:.0e} | not reached on the {n} cached steps |");
                continue;
            }
            Stop::NoTwin(k) => {
                println!(
                    "| {tol:.0e} | step {k} meets it along the ladder; its twin is not cached (--twin {k}) |"
                );
                continue;
            }
        };
        let steps: Vec<_> = cache.steps[..=k]
            .iter()
            .map(|s| s.scaled(cache.ladder != "hp"))
            .collect();
        let ladder_assessment = assess(&steps);
        let s = &cache.steps[k];
        // the estimates the target reports: the stop's twin's on the graded ladder
        let a = s
            .twinned(&cache)
            .unwrap_or_else(|| ladder_assessment.clone());
        // the time of a tolerance: every step to the stop and the stop's twin
        let solved: Vec<&CachedStep> = cache.steps[..=k]
            .iter()
            .chain(cache.twins.get(&k))
            .collect();
        let cpu: f64 = solved.iter().map(|s| s.cpu_seconds).sum();
        let wall: f64 = solved.iter().map(|s| s.seconds).sum();
        let load = solved.iter().map(|s| s.load_average).fold(0.0, f64::max);
        for (name, q) in &steps[k] {
            let ladder_ratio = ladder_assessment
                .estimates
                .get(name)
                .map_or(f64::NAN, |e| e.error / q.scale);
            let e = a.estimates.get(name);
            let est = e.map_or(f64::NAN, |e| e.error / q.scale);
            let rule = e.map_or("-".to_owned(), |e| match (e.rule, e.rate) {
                (Rule::Richardson, Some(r)) => format!("richardson r = {r:.3}"),
                (Rule::LadderRate, Some(r)) => format!("ladder-rate rho = {r:.3}"),
                (Rule::Twin, _) => "twin".to_owned(),
                _ => "last-change".to_owned(),
            });
            let truth = (q.value - reference.values[name]).abs() / q.scale;
            let other = cache
                .references
                .get("p6-240x14")
                .and_then(|r| r.values.get(name).copied())
                .or_else(|| wp["values"][name].as_f64());
            let wp_cell = other.map_or("-".to_owned(), |v| {
                let t = (q.value - v).abs() / q.scale;
                format!("{t:.1e}, {:.2}", est / t)
            });
            let values: Vec<f64> = steps.iter().map(|s| s[name].value).collect();
            let old = old_estimate(&values).map_or(f64::NAN, |o| o / q.scale / truth);
            println!(
                "| {tol:.0e} | {k} ({:?}, {}) | {cpu:.1} s / {wall:.0} s ({load:.0}) | {name} | {:.10} | {est:.1e} | {rule} | {truth:.1e} | {:.2} | {wp_cell} | {old:.1} | {:.2} |",
                s.grid,
                s.unknowns,
                q.value,
                est / truth,
                ladder_ratio / truth
            );
        }
    }
    if let Some(tol) = live {
        let mut scene = Scene::default();
        scene.accuracy.tol = Some(tol);
        let target = scene.accuracy.target()?.expect("accuracy.tol is set");
        let t = Instant::now();
        let (_, _, estimate, report) = contact_to(&scene, &target, &mut SilentObserver)?;
        let k = report.steps.len() - 1;
        let cached = match stop(&cache, &target) {
            Stop::At(c) => Some(c),
            _ => None,
        };
        let steps: Vec<_> = cache.steps[..=k]
            .iter()
            .map(|s| s.scaled(cache.ladder != "hp"))
            .collect();
        let a = cache.steps[k]
            .twinned(&cache)
            .unwrap_or_else(|| assess(&steps));
        let worst = estimate
            .quantities
            .iter()
            .map(|(n, e)| {
                let c = a.estimates[n].error;
                (e.unwrap_or(f64::NAN) - c).abs() / c
            })
            .fold(0.0, f64::max);
        println!(
            "live contact_to at {tol:.0e}: stopped at step {k} (cache: {cached:?}) in {:.1} s wall; estimates against the cache's: largest relative difference {worst:.1e}",
            t.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
