"""What the peer scripts of `capstan bench work-precision` share: the Lamé problem's
command-line arguments, capstan's repeat rule, plane-strain Lamé parameters, and the
peak-memory probe (/proc/self)."""


def vm_kib(field):
    """A /proc/self/status field in KiB (VmRSS, VmHWM); 0 where it cannot be read."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def reset_peak():
    """Resets VmHWM to the current resident set (Linux); False where it cannot."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def add_lame_args(ap):
    """The Lamé cylinder (r 1-2, E 10, nu 0.3, p 1) and the repeat rule of capstan's runs:
    every level at least --repeat-min times, then until --repeat-budget seconds of run time
    or --repeat-max runs."""
    ap.add_argument("--radius", type=float, default=1.0)
    ap.add_argument("--thickness", type=float, default=1.0)
    ap.add_argument("--young", type=float, default=10.0)
    ap.add_argument("--poisson", type=float, default=0.3)
    ap.add_argument("--pressure", type=float, default=1.0)
    add_repeat_args(ap)


def add_repeat_args(ap):
    """The repeat rule of capstan's runs: every level at least --repeat-min times, then until
    --repeat-budget seconds of run time or --repeat-max runs."""
    ap.add_argument("--repeat-min", type=int, default=2)
    ap.add_argument("--repeat-max", type=int, default=5)
    ap.add_argument("--repeat-budget", type=float, default=1.0)


def fastest(a, once, seconds):
    """The fastest of the runs `once()` the repeat rule in `a` asks for (`seconds(run)` is a
    run's time), and how many were made."""
    best, runs, spent = None, 0, 0.0
    while runs < a.repeat_min or (runs < a.repeat_max and spent < a.repeat_budget):
        r = once()
        runs += 1
        spent += seconds(r)
        if best is None or seconds(r) < seconds(best):
            best = r
    return best, runs


def lame_parameters(young, poisson):
    """(lambda, mu) of plane strain (as scikit-fem's `lame_parameters`)."""
    return (
        young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
        young / (2.0 * (1.0 + poisson)),
    )
