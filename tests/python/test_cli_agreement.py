"""Every API function on the default scene agrees with `capstan <command> --json` to the last
digit: the parsed JSON objects are equal (floats compared exactly), wall times aside."""

import json

import numpy as np

import capstan
from conftest import without_timings


def same(python_result, cli_json):
    assert without_timings(python_result.to_dict()) == without_timings(cli_json)


def test_tension_matches_cli(cli):
    same(capstan.tension(capstan.Scene()), cli("tension"))


def test_infer_mu_matches_cli_for_each_cheap_model(cli):
    scene = capstan.Scene({"membrane.t_max": 2.75})
    for model in ["capstan", "membrane"]:
        same(
            capstan.infer_mu(scene, model=model),
            cli("infer-mu", "--model", model, "--set", "membrane.t_max=2.75"),
        )


def test_contact_matches_cli(cli):
    r = capstan.contact(capstan.Scene())
    same(r, cli("contact"))
    # the arrays are numpy arrays of the JSON's values, bit for bit
    assert isinstance(r.contact.v2, np.ndarray)
    assert r.contact.v2.tolist() == r.to_dict()["contact"]["v2"]
    assert r.contact.state.dtype.kind == "i"
    assert json.loads(r.to_json())["capstan_version"] == capstan.__version__
    # the converging quantities with their estimated errors (one grid level coarser)
    assert r.estimated_error.method == "one-level-coarser"
    assert 0 < r.estimated_error.quantities["slip_measure"] < 1e-2
    assert r.slip_measure < r.contact_measure


def test_threshold_matches_cli(cli):
    same(capstan.threshold(capstan.Scene()), cli("threshold"))


def test_threshold_to_an_accuracy_target_matches_cli(cli):
    r = capstan.threshold(capstan.Scene({"accuracy.tol": 1e-3}))
    same(r, cli("threshold", "--tol", "1e-3"))
    assert r.accuracy.chosen.method == "fem-qp"
    assert r.estimated_error.quantities["threshold_ratio"] < 1e-3 * r.threshold_ratio


def test_sweep_matches_cli(cli):
    expected = cli("sweep", "--param", "loads.tau_max", "--from", "1", "--to", "2", "--steps", "3")
    same(capstan.sweep(capstan.Scene(), "loads.tau_max", [1.0, 1.5, 2.0]), expected)


def test_sweep_of_a_rebuilt_key_matches_cli(cli):
    scene = capstan.Scene({"grid.n2": 41, "grid.n3": 9})
    expected = cli(
        "sweep", "--set", "grid.n2=41", "--set", "grid.n3=9",
        "--param", "body.poisson", "--from", "0.1", "--to", "0.3", "--steps", "2",
    )
    same(capstan.sweep(scene, "body.poisson", [0.1, 0.3]), expected)


def test_geometry_at_the_cli_points_matches_cli(cli):
    expected = cli("geometry")
    r = capstan.geometry(capstan.Scene(), expected["x2"]).to_dict()
    for key, value in expected.items():
        assert r[key] == value, key
    # the tensors hold the CLI's components
    assert [m[1][1] for m in r["first_form"]] == expected["a22"]
    assert [c[1][1][1] for c in r["christoffel"]] == expected["christoffel_222"]


def test_scene_from_toml_file_text_and_dict_are_one_scene(tmp_path):
    text = "[body]\npoisson = 0.3\n[grid]\nn2 = 41\n"
    path = tmp_path / "s.toml"
    path.write_text(text)
    a = capstan.Scene.from_toml(path)
    b = capstan.Scene.from_toml(text)
    c = capstan.Scene({"body": {"poisson": 0.3}, "grid.n2": 41})
    d = capstan.Scene()
    d.set("body.poisson", 0.3)
    d.set("grid.n2", 41)
    assert a == b == c == d
    assert a.get("body.poisson") == 0.3
    assert capstan.Scene.from_toml(a.to_toml()) == a


def test_example_scene_file_matches_cli(cli):
    path = "examples/scenes/capstan_ellipse.toml"
    import conftest

    same(capstan.tension(capstan.Scene.from_toml(conftest.ROOT / path)), cli("tension", path))


def test_graded_fem_qp_contact_matches_cli(cli):
    keys = {
        "discretisation.method": "fem-qp",
        "discretisation.order": 4,
        "discretisation.grading": 0.4,
        "discretisation.layers": 2,
        "grid.n2": 65,
        "grid.n3": 17,
    }
    r = capstan.contact(capstan.Scene(keys))
    same(r, cli("contact", *[a for k, v in keys.items() for a in ("--set", f"{k}={v}")]))
    # the resolved scene records the grading (provenance)
    scene = r.to_dict()["scene"]["discretisation"]
    assert scene["grading"] == 0.4 and scene["layers"] == 2


def test_membrane_path_matches_cli(cli):
    keys = {
        "friction.law": "exact-coulomb",
        "obstacle.shape": "cylinder",
        "membrane.theta0": 0.0,
        "membrane.nodes": 201,
        "loads.path": [2.0, 1.2, 2.0],
    }
    r = capstan.membrane_path(capstan.Scene(keys))
    same(
        r,
        cli(
            "membrane-path",
            "--set", "friction.law=exact-coulomb",
            "--set", "obstacle.shape=cylinder",
            "--set", "membrane.theta0=0",
            "--set", "membrane.nodes=201",
            "--set", "loads.path=[2.0, 1.2, 2.0]",
        ),
    )
    assert r.profiles["tension"].shape == (3, 201)
    assert r.theta.shape == (201,)
    # the loop closes: reloading to 2 restores the loaded state
    assert r.steps[2].end_displacement == r.steps[0].end_displacement
    np.testing.assert_allclose(r.profiles["displacement"][2], r.profiles["displacement"][0], rtol=1e-12)
    assert set(np.unique(r.profiles["state"])) <= {0.0, 1.0}


def test_contact_path_matches_cli(cli):
    keys = {
        "friction.law": "exact-coulomb",
        "body.thickness": 0.25,
        "grid.n2": 41,
        "grid.n3": 5,
        "loads.path": [1.0, 2.0, 1.5, 2.0],
    }
    r = capstan.contact_path(capstan.Scene(keys))
    same(
        r,
        cli(
            "contact-path",
            "--set", "friction.law=exact-coulomb",
            "--set", "body.thickness=0.25",
            "--set", "grid.n2=41",
            "--set", "grid.n3=5",
            "--set", "loads.path=[1.0, 2.0, 1.5, 2.0]",
        ),
    )
    assert len(r.steps) == 4
    # the loop: unloading lowers the end displacement, reloading restores it
    assert r.steps[2].end_displacement < r.steps[1].end_displacement
    np.testing.assert_allclose(r.steps[3].end_displacement, r.steps[1].end_displacement, rtol=1e-9)
    assert all(step.dissipation >= -1e-15 for step in r.steps)  # >= 0 to round-off
    assert r.solver_choice.nonlinear == "full-newton"
