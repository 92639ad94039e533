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


def one_thread():
    """One thread for the BLAS and OpenMP pools of the peer (call before importing it)."""
    import os

    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"


def fastest_solve(a, solve):
    """The fastest of the runs of `solve()` (returning `(solution, dofs, global_dofs, t)`,
    `t` the list of timed phases) that the repeat rule in `a` asks for, with the growth of the
    peak resident set over that run in MiB appended: `((solution, dofs, global_dofs, t,
    peak_mib), runs)`."""

    def once():
        reset_peak()
        base = vm_kib("VmRSS")
        gfu, dofs, global_dofs, t = solve()
        return gfu, dofs, global_dofs, t, max(vm_kib("VmHWM") - base, 0) / 1024.0

    return fastest(a, once, lambda r: sum(r[3]))


def level_record(a, m, mesh, best, runs, mesh_times, version, **extra):
    """The JSON record of one level of an NGSolve peer: `best` and `runs` from
    `fastest_solve`, `mesh_times` = (meshing, curving) seconds (not timed), the timed phases
    `t` = (setup, assemble, solve), and the script's own keys in `extra` (backend, maxh,
    error, ...)."""
    _, dofs, global_dofs, t, peak_mib = best
    record = {
        "method": f"ngsolve-p{a.order}",
        "backend": a.inverse,
        "order": a.order,
        "m": m,
        "n2": mesh.ne,
        "n3": 0,
        "elements": mesh.ne,
        "vertices": mesh.nv,
        "dofs": dofs,
        "global_dofs": global_dofs,
        "setup_seconds": t[0],
        "assemble_seconds": t[1],
        "solve_seconds": t[2],
        "seconds": sum(t),
        "mesh_seconds": mesh_times[0],
        "curve_seconds": mesh_times[1],
        "peak_mib": peak_mib,
        "repeats": runs,
        "version": version,
    }
    record.update(extra)
    return record
