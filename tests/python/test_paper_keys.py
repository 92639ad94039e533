"""Issue 32's scene keys from Python agree with the command line to the last digit: the
membrane load expressions (``loads.f_t``, ``loads.f_n``) and the implied ``mu`` under them,
Corollary 1 (``membrane.model = "infinite"``), the paper's belt-speed rule, the cone's forms and
development map, and the thick body's ``loads.body_force`` (2-D and 3-D)."""

import capstan
from conftest import without_timings

LOADED_ELLIPSE = {
    "obstacle.shape": "ellipse",
    "obstacle.a": 2.0,
    "obstacle.b": 1.0,
    "membrane.theta0": -1.0,
    "membrane.theta_max": 1.2,
    "membrane.t0": 3.0,
    "friction.mu": 0.4,
    "loads.f_t": "0.3*sin(2*t) + 0.1",
    "loads.f_n": "-0.5*cos(t)^2 + 0.2*t",
}


def toml_literal(value):
    if isinstance(value, str):
        return '"' + value + '"'
    if isinstance(value, list):
        return "[" + ", ".join(toml_literal(v) for v in value) + "]"
    return repr(value)


def sets(keys):
    return [a for k, v in keys.items() for a in ("--set", f"{k}={toml_literal(v)}")]


def same(python_result, cli_json):
    assert without_timings(python_result.to_dict()) == without_timings(cli_json)


def test_load_expressions_match_cli(cli):
    r = capstan.tension(capstan.Scene(LOADED_ELLIPSE))
    same(r, cli("tension", *sets(LOADED_ELLIPSE)))
    assert r.to_dict()["method"] == "ode"


def test_implied_mu_under_load_expressions_matches_cli_and_round_trips(cli):
    t_max = capstan.tension(capstan.Scene(LOADED_ELLIPSE)).to_dict()["t_max"]
    keys = dict(LOADED_ELLIPSE, **{"membrane.t_max": t_max, "friction.mu": 0.9})
    r = capstan.infer_mu(capstan.Scene(keys))
    same(r, cli("infer-mu", *sets(keys)))
    assert abs(r.to_dict()["mu"] - 0.4) < 1e-10


def test_infinite_membrane_and_paper_speed_rule_match_cli(cli):
    for keys in [
        {
            "obstacle.shape": "cylinder",
            "obstacle.radius": 1.5,
            "membrane.model": "infinite",
            "membrane.theta0": 0.0,
            "membrane.theta_max": 2.0,
            "loads.gravity": 9.81,
            "loads.density": 0.1,
        },
        {
            "obstacle.shape": "ellipse",
            "obstacle.a": 2.0,
            "obstacle.b": 1.0,
            "loads.density": 0.3,
            "loads.speed": 1.0,
            "membrane.belt_speed_rule": "paper",
        },
    ]:
        same(capstan.tension(capstan.Scene(keys)), cli("tension", *sets(keys)))


def test_cone_forms_and_development_match_cli(cli):
    keys = {"obstacle.shape": "circular-cone", "obstacle.half_angle": 0.4}
    expected = cli("geometry", *sets(keys))
    r = capstan.geometry(capstan.Scene(keys), expected["x2"]).to_dict()
    for key, value in expected.items():
        assert r[key] == value, key
    assert "development" in expected


def test_body_force_contact_matches_cli(cli):
    plane = {
        "grid.n2": 41,
        "grid.n3": 9,
        "loads.body_force": ["0.05*(1 + x3)", "-0.4*cos(x2)"],
    }
    solid = {
        "body.dimension": 3,
        "discretisation.method": "fem-q1",
        "grid.n1": 3,
        "grid.n2": 21,
        "grid.n3": 5,
        "loads.body_force": ["0", "0.05*(1 + x3)", "-0.4*cos(x2)"],
    }
    for keys in [plane, solid]:
        r = capstan.contact(capstan.Scene(keys))
        same(r, cli("contact", *sets(keys)))
        assert r.to_dict()["scene"]["loads"]["body_force"] == keys["loads.body_force"]
