//! Progress bars (indicatif) for sweeps and figure runs: drawn on stderr only when it is a
//! terminal and the run is not `--quiet`; hidden otherwise, so pipes and CI logs stay clean.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};

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
