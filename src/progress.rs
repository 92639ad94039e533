//! Progress bars (indicatif) for sweeps and figure runs: drawn on stderr only when it is a
//! terminal and the run is not `--quiet`; hidden otherwise, so pipes and CI logs stay clean.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::time::{Duration, Instant};

use capstan_elasticity::solvers::{Observer, Progress};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

static QUIET: AtomicBool = AtomicBool::new(false);
static VERBOSITY: AtomicU8 = AtomicU8::new(0);

/// Sets the global `--quiet` and `-v` flags (called once by the command line).
pub fn set_flags(quiet: bool, verbosity: u8) {
    QUIET.store(quiet, Ordering::Relaxed);
    VERBOSITY.store(verbosity, Ordering::Relaxed);
}

/// Whether `--quiet` was given.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// How many `-v` were given.
pub fn verbosity() -> u8 {
    VERBOSITY.load(Ordering::Relaxed)
}

/// Prints `message` on stderr when `-v` was given at least `level` times.
pub fn note(level: u8, message: &str) {
    if verbosity() >= level && !quiet() {
        eprintln!("{message}");
    }
}

/// A bar of `len` steps labelled `what`; hidden when `quiet`, when `--quiet` was given or when
/// stderr is not a terminal.
pub fn bar(len: usize, what: &str, quiet: bool) -> ProgressBar {
    let bar = ProgressBar::new(len as u64);
    if quiet || self::quiet() || !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
        return bar;
    }
    let style = ProgressStyle::with_template(&format!(
        "{what} {{bar:30}} {{pos}}/{{len}} {{msg}} [{{elapsed_precise}}, eta {{eta}}]"
    ))
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}

/// After this long a solve shows a progress spinner (on a terminal, without `--quiet`).
const SPINNER_AFTER: Duration = Duration::from_secs(2);

/// One line of an iterative solve's progress, as `-v` prints it:
/// `condensed-newton   3  residual 1.234e-07  step 1  stick 12  slip 229`.
///
/// Set-up phases print their work instead: `set-up  condensation 1200/2500`.
pub fn progress_line(p: &Progress<f64>) -> String {
    if let Some(w) = p.work {
        return format!(
            "{:<16} {} {}/{}",
            p.stage.name(),
            w.phase.name(),
            w.done,
            w.total
        );
    }
    let mut line = format!(
        "{:<16} {:>4}  residual {:.3e}  step {:.3}",
        p.stage.name(),
        p.iteration,
        p.residual_norm,
        p.step_length
    );
    if let Some(a) = p.active {
        line += &format!("  stick {}  slip {}", a.stick, a.slip);
        if a.separated > 0 {
            line += &format!("  separated {}", a.separated);
        }
    }
    line
}

/// The command line's observer of iterative solves: with `-v` one [`progress_line`] per
/// iteration on stderr; otherwise, on a terminal and without `--quiet`, a spinner with the
/// latest iteration once the solve has run for two seconds; nothing with `--quiet`.
#[derive(Debug)]
pub struct CliObserver {
    start: Instant,
    spinner: Option<ProgressBar>,
    lines: bool,
    spin: bool,
}

impl CliObserver {
    /// An observer for a solve starting now, following the global flags.
    pub fn new() -> Self {
        let lines = verbosity() >= 1 && !quiet();
        Self {
            start: Instant::now(),
            spinner: None,
            lines,
            spin: !lines && !quiet() && std::io::stderr().is_terminal(),
        }
    }
}

impl Default for CliObserver {
    fn default() -> Self {
        Self::new()
    }
}

impl Observer<f64> for CliObserver {
    fn iteration(&mut self, p: &Progress<f64>) {
        if self.lines {
            eprintln!("{}", progress_line(p));
        } else if self.spin && self.start.elapsed() >= SPINNER_AFTER {
            let spinner = self.spinner.get_or_insert_with(|| {
                let s = ProgressBar::new_spinner();
                s.set_style(
                    ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                        .unwrap_or_else(|_| ProgressStyle::default_spinner()),
                );
                s.enable_steady_tick(Duration::from_millis(200));
                s
            });
            spinner.set_message(progress_line(p));
        }
    }
}

impl Drop for CliObserver {
    fn drop(&mut self) {
        if let Some(s) = self.spinner.take() {
            s.finish_and_clear();
        }
    }
}
