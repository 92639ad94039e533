"""A callback sees every iteration (the Newton residuals fall); an exception in it, or Ctrl-C,
stops the solve; the GIL is released while it runs."""

import _thread
import threading
import time

import pytest

import capstan

SMALL = {"grid.n2": 41, "grid.n3": 9}


def test_callback_sees_newton_residuals_fall():
    seen = []
    r = capstan.contact(capstan.Scene(), callback=seen.append)
    newton = [p for p in seen if p["stage"] == "condensed-newton"]
    assert len(newton) >= r.newton_iterations
    residuals = [p["residual"] for p in newton]
    assert residuals[-1] < 1e-8 * residuals[0]
    assert residuals[-1] == min(residuals)
    assert all(p["stick"] + p["slip"] == len(r.contact.x2) for p in newton if p["stick"] is not None)


def test_full_newton_reports_to_the_callback():
    seen = []
    capstan.contact(capstan.Scene({**SMALL, "solver.nonlinear": "full-newton"}), callback=seen.append)
    stages = {p["stage"] for p in seen}
    assert "newton" in stages or "condensed-newton" in stages


def test_exception_in_callback_stops_the_solve():
    class Stop(Exception):
        pass

    def stop(p):
        if p["iteration"] == 2:
            raise Stop

    with pytest.raises(Stop):
        capstan.contact(capstan.Scene(SMALL), callback=stop)


def test_ctrl_c_raises_keyboard_interrupt():
    # interrupt_main() is what Ctrl-C does: the next signal check raises KeyboardInterrupt
    def ctrl_c(p):
        if p["iteration"] == 1:
            _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        capstan.contact(capstan.Scene(SMALL), callback=ctrl_c)
    # and the package still works afterwards
    assert capstan.contact(capstan.Scene(SMALL)).converged


def test_ctrl_c_from_another_thread_returns_at_once():
    # the 601 x 81 solve takes ~10 s here; Ctrl-C at 0.3 s returns within the 50 ms signal poll
    # (the solve itself stops at its next iteration, in the background)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    t = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        capstan.contact(capstan.Scene({"grid.n2": 601, "grid.n3": 81}))
    assert time.perf_counter() - t < 2.0


def test_solve_releases_the_gil():
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    th = threading.Thread(target=count)
    th.start()
    try:
        capstan.contact(capstan.Scene())
    finally:
        done.set()
        th.join()
    assert len(ticks) > 20


def test_membrane_path_reports_every_semismooth_iteration():
    scene = capstan.Scene(
        {
            "friction.law": "exact-coulomb",
            "obstacle.shape": "cylinder",
            "membrane.theta0": 0.0,
            "membrane.nodes": 101,
            "loads.path": [2.0, 1.5],
        }
    )
    seen = []
    r = capstan.membrane_path(scene, callback=seen.append)
    # the start of each step and every iteration, with the active set of the 101 nodes
    assert len(seen) == len(r.steps) + sum(step.iterations for step in r.steps)
    assert all(p["stage"] == "membrane" for p in seen)
    assert all(p["stick"] + p["slip"] <= 101 for p in seen)

    def fail(_):
        raise RuntimeError("stop")

    with pytest.raises(RuntimeError):
        capstan.membrane_path(scene, callback=fail)
