"""capstan from Python: friction between elastic bodies and rough rigid curved obstacles.

The functions mirror the command line (``capstan tension|infer-mu|contact|threshold|sweep|geometry|
membrane-path|contact-path --json``): the same scene keys, the same result keys, the same digits. Results are objects whose
arrays are numpy arrays; ``result.to_dict()`` and ``result.to_json()`` give what ``--json`` prints.

>>> import capstan
>>> scene = capstan.Scene({"grid.n2": 41, "grid.n3": 9})
>>> scene.set("loads.tau_max", 1.5)
>>> r = capstan.contact(scene)
>>> r.contact.x2.shape, r.fields["displacement"].shape      # doctest: +SKIP
((39,), (41, 9, 3))

Solves release the GIL; Ctrl-C stops a contact solve with KeyboardInterrupt. Bad input raises
``ValueError`` (``capstan.InvalidInputError``); no equilibrium and no convergence raise
``capstan.NoEquilibriumError`` and ``capstan.NotConvergedError`` (both ``capstan.CapstanError``).
"""

from __future__ import annotations

import json
import os
from typing import Any, Callable, Iterable, Optional

import numpy as np

from . import _capstan
from ._errors import CapstanError, InvalidInputError, NoEquilibriumError, NotConvergedError

__all__ = [
    "Scene",
    "Result",
    "ContactResult",
    "MembranePathResult",
    "tension",
    "infer_mu",
    "contact",
    "threshold",
    "sweep",
    "geometry",
    "membrane_path",
    "contact_path",
    "CapstanError",
    "InvalidInputError",
    "NoEquilibriumError",
    "NotConvergedError",
    "__version__",
]

__version__ = _capstan.version()


class Scene(_capstan.Scene):
    """A validated scene: every key of the command line's scene files, defaults filled in.

    ``Scene()`` is the default (the paper's section 3); ``Scene({"body": {"poisson": 0.3}})`` or
    ``Scene({"body.poisson": 0.3})`` sets keys; ``scene.set("body.poisson", 0.3)`` changes one.
    Keys pass through unchanged: any key a scene file accepts works here.
    """

    @classmethod
    def from_toml(cls, source: "str | os.PathLike[str]") -> "Scene":
        """A scene from a TOML file (a path) or from TOML text."""
        text, origin = str(source), "scene"
        if isinstance(source, os.PathLike) or ("\n" not in text and "=" not in text):
            with open(source, encoding="utf-8") as f:
                text, origin = f.read(), os.fspath(source)
        scene = cls()
        scene._load_toml(text, origin)
        return scene

    def get(self, key: str) -> Any:
        """The value of one key (``"body.poisson"``)."""
        section, _, field = key.partition(".")
        d = self.to_dict()
        if section not in d or field not in d[section]:
            raise InvalidInputError(f"unknown key `{key}`")
        return d[section][field]

    def to_dict(self) -> dict:
        """The resolved scene as ``{section: {key: value}}`` (the ``scene`` of ``--json``)."""
        return json.loads(self._to_json())

    def copy(self) -> "Scene":
        """An independent copy."""
        return Scene(_flatten(self.to_dict()))


def _flatten(d: dict) -> dict:
    return {f"{s}.{k}": v for s, t in d.items() for k, v in t.items()}


def _array(v: Any) -> Any:
    """A list of numbers (or of lists of numbers) as a numpy array; anything else unchanged."""
    if not isinstance(v, list) or not v:
        return v
    try:
        a = np.asarray(v)
    except ValueError:  # ragged
        return v
    return a if a.dtype.kind in "if" else v


def _wrap(v: Any) -> Any:
    if isinstance(v, dict):
        return Result._of(v)
    if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
        return [Result._of(x) for x in v]
    return _array(v)


class Result:
    """A report: attributes are the JSON keys of ``--json``, numeric lists as numpy arrays."""

    def __init__(self, text: str):
        self._json = text
        self._data = json.loads(text)

    @classmethod
    def _of(cls, data: dict) -> "Result":
        r = cls.__new__(cls)
        r._json, r._data = None, data
        return r

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return _wrap(self._data[name])
        except KeyError:
            raise AttributeError(f"no key `{name}`; keys: {', '.join(self._data)}") from None

    def __getitem__(self, key: str) -> Any:
        return _wrap(self._data[key])

    def __contains__(self, key: str) -> bool:
        return key in self._data

    def __dir__(self) -> Iterable[str]:
        return list(self._data) + ["to_dict", "to_json", "keys"]

    def keys(self) -> list:
        """The report's keys."""
        return list(self._data)

    def to_dict(self) -> dict:
        """The report as plain Python data (lists, not arrays): ``json.loads`` of ``--json``."""
        return json.loads(self.to_json())

    def to_json(self) -> str:
        """The report as the command line's ``--json`` prints it."""
        return self._json if self._json is not None else json.dumps(self._data)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(self._data)})"


class ContactResult(Result):
    """``capstan contact --json``, plus the whole-body fields.

    ``fields[name]`` is an ``(n2, n3, k)`` array at the body's nodes (``x3`` fastest in the
    grid): the arrays of ``body.vtu`` (``displacement``, ``displacement_contravariant``,
    ``displacement_physical``, ``stress``, ``stress_physical``, ``strain``, ``strain_physical``
    with ``k = 9`` row-major, ``contact_state``, ``contact_slip``, ``x2``, ``x3``) and
    ``points``, the nodes' Cartesian positions. A 3-D body (``body.dimension = 3``) gives
    ``(n1, n2, n3, k)`` arrays, with ``contact_slip_1`` and ``x1`` besides.
    """

    def __init__(self, text: str, fields: list, shape: list):
        super().__init__(text)
        self.fields = {
            name: np.frombuffer(b, dtype="<f8").reshape(*shape, k).copy()
            for name, k, b in fields
        }


def tension(scene: Scene) -> Result:
    """The membrane's tension profile (``capstan tension --json``)."""
    return Result(_capstan.tension(scene))


def infer_mu(scene: Scene, model: str = "capstan") -> Result:
    """The coefficient of friction implied by ``membrane.t_max`` (``capstan infer-mu --model``):
    ``"capstan"``, ``"membrane"`` or ``"kikuchi-oden"``."""
    return Result(_capstan.infer_mu(scene, model))


def threshold(scene: Scene) -> Result:
    """The tension ratio at which the whole contact slides (``capstan threshold --json``)."""
    return Result(_capstan.threshold(scene))


def geometry(scene: Scene, x2: "Iterable[float] | float") -> Result:
    """The obstacle's geometry at the points ``x2``: the keys of ``capstan geometry --json``
    (``mean_curvature``, ``gaussian_curvature``, ``a22``, ``b22``, ``christoffel_222``,
    ``sqrt_g_outer``) and the tensors ``first_form`` (metric ``a_ab``, shape ``(n, 2, 2)``),
    ``first_form_inverse``, ``second_form``, ``mixed_second_form``, ``christoffel``
    (``Gamma^c_ab`` as ``[c][a][b]``, ``(n, 2, 2, 2)``), ``normal``, ``point``, ``shell_metric``
    and ``shell_metric_outer`` (``g_ij`` at ``x3 = 0`` and ``x3 = body.thickness``). On a cone,
    ``development`` holds the development map of Theorem 2 at ``x1 = 1``: ``phi``, ``phi_rate``,
    ``radius`` (``rbar``), ``chi`` (``(chi1, chi2)``) and ``jacobian`` (``d chi / d x``)."""
    x = np.atleast_1d(np.asarray(x2, dtype=float)).tolist()
    return Result(_capstan.geometry(scene, x))


class MembranePathResult(Result):
    """``capstan membrane-path --json`` (``steps``: one result per load state, ``dissipation``),
    plus the node angles ``theta`` and ``profiles[name]``, a ``(steps, nodes)`` array for each of
    ``displacement``, ``slip_increment``, ``tension``, ``friction`` (force per unit length) and
    ``state`` (0 stick, 1 slip, 2 separated)."""

    def __init__(self, text: str, theta: list, profiles: list):
        super().__init__(text)
        self.theta = np.asarray(theta, dtype=float)
        n = len(self.theta)
        self.profiles = {
            name: np.asarray(values, dtype=float).reshape(-1, n) for name, values in profiles
        }


def membrane_path(
    scene: Scene, callback: Optional[Callable[[dict], Any]] = None
) -> MembranePathResult:
    """The membrane along the load path ``loads.path`` (end tensions at ``theta_max``) with a
    nonsmooth law (``friction.law = "exact-coulomb"``), each state from the previous one with
    friction on the slip increment (``capstan membrane-path --json``): belt creep, hysteresis.
    ``callback(progress)`` sees every semismooth iteration as for ``contact`` (stage
    ``"membrane"``, ``stick`` and ``slip`` counts); an exception in it is raised here.

    >>> s = capstan.Scene({"friction.law": "exact-coulomb", "obstacle.shape": "cylinder",
    ...                    "loads.path": [2.0, 1.2, 2.0]})                   # doctest: +SKIP
    >>> r = capstan.membrane_path(s)                                          # doctest: +SKIP
    >>> [step.end_displacement for step in r.steps]                           # doctest: +SKIP
    """
    return MembranePathResult(*_capstan.membrane_path(scene, callback))


def contact_path(scene: Scene, callback: Optional[Callable[[dict], Any]] = None) -> Result:
    """The thick body (2-D or 3-D) along the load path ``loads.path`` (end tractions
    ``tau_max``, ``loads.tau0`` held), the first state from rest and each later one from the
    state before it, with friction on the slip increment (``capstan contact-path --json``):
    ``steps`` (per step ``end_displacement``, ``dissipation``, ``stick_nodes``, ``slip_nodes``,
    ``slip_intervals`` and the ``contact`` arrays, whose ``slip`` and ``state`` are those of the
    step's increment) and the total ``dissipation``. ``callback(progress)`` sees every Newton
    iterate as for ``contact``; an exception in it is raised here.

    >>> s = capstan.Scene({"friction.law": "exact-coulomb", "body.thickness": 0.25,
    ...                    "grid.n2": 41, "grid.n3": 5,
    ...                    "loads.path": [1.0, 2.0, 1.5, 2.0]})                  # doctest: +SKIP
    >>> [step.end_displacement for step in capstan.contact_path(s).steps]       # doctest: +SKIP
    """
    return Result(_capstan.contact_path(scene, callback))


def contact(
    scene: Scene,
    callback: Optional[Callable[[dict], Any]] = None,
    out: "Optional[str | os.PathLike[str]]" = None,
) -> ContactResult:
    """The thick body's contact problem (``capstan contact --json``).

    ``callback(progress)`` is called after every iteration of the solve with a dict: ``stage``
    (``"condensed-newton"``, ``"continuation"``, ``"newton"``, ...), ``iteration``,
    ``residual``, ``step_length``, ``stick``, ``slip``, ``separated``. The set-up phases report
    too, with stage ``"set-up"`` and ``phase`` (``"assembly"``, ``"factorisation"``,
    ``"condensation"``), ``done`` and ``total`` (the phase's work done); other events have
    these ``None``. An exception in the callback stops the solve and propagates; so does Ctrl-C (KeyboardInterrupt). ``out`` writes the files of
    ``--out``.
    """
    text, fields, shape = _capstan.contact(scene, callback, None if out is None else os.fspath(out))
    return ContactResult(text, fields, shape)


def sweep(
    scene: Scene,
    param: str,
    values: Iterable[float],
    out: "Optional[str | os.PathLike[str]]" = None,
) -> Result:
    """One key varied over ``values`` (``capstan sweep --param --json``); ``points`` is a list
    of results, one per value. ``out`` writes the files of ``--out`` (VTU per point, PVD)."""
    v = np.atleast_1d(np.asarray(values, dtype=float)).tolist()
    return Result(_capstan.sweep(scene, param, v, None if out is None else os.fspath(out)))
