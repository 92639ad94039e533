"""Bad input raises ValueError naming the key (the Rust error's text); failures of the physics
raise their own classes; nothing panics across the boundary."""

import pytest

import capstan


@pytest.mark.parametrize(
    "key, value",
    [
        ("body.poisson", 0.7),
        ("body.young", -1.0),
        ("grid.n2", 1),
        ("friction.mu", -0.5),
        ("obstacle.shape", "banana"),
        ("body.poissn", 0.3),
        ("nosuchtable.key", 1),
        ("grid.n3", "many"),
    ],
)
def test_bad_key_or_value_raises_value_error_naming_the_key(key, value):
    scene = capstan.Scene()
    before = scene.to_toml()
    with pytest.raises(ValueError) as e:
        scene.set(key, value)
    assert key in str(e.value) or key.split(".")[0] in str(e.value), str(e.value)
    assert isinstance(e.value, capstan.InvalidInputError)
    assert isinstance(e.value, capstan.CapstanError)
    assert scene.to_toml() == before  # unchanged on error
    with pytest.raises(ValueError, match=key.split(".")[0]):
        capstan.Scene({key: value})


def test_range_error_names_value_and_range():
    with pytest.raises(ValueError, match=r"`body.poisson` = 0.7 is outside \(-1, 1/2\)"):
        capstan.Scene({"body.poisson": 0.7})


def test_bad_toml_names_the_line():
    with pytest.raises(ValueError, match="body.poisson"):
        capstan.Scene.from_toml("[body]\npoisson = 0.9\n")


def test_unknown_model_is_a_value_error():
    with pytest.raises(ValueError, match="kikuchi"):
        capstan.infer_mu(capstan.Scene({"membrane.t_max": 2.75}), model="coulomb")


def test_missing_t_max_is_a_value_error():
    with pytest.raises(ValueError, match="membrane.t_max"):
        capstan.infer_mu(capstan.Scene())


def test_wrong_python_type_is_a_type_error():
    with pytest.raises(TypeError):
        capstan.Scene().set("body.poisson", object())


def test_no_equilibrium_has_its_own_class():
    scene = capstan.Scene({"grid.n2": 41, "grid.n3": 9, "obstacle.shape": "cylinder", "loads.tau_max": 50.0})
    with pytest.raises(capstan.NoEquilibriumError) as e:
        capstan.contact(scene)
    assert not isinstance(e.value, ValueError)
    assert isinstance(e.value, capstan.CapstanError)


def test_tension_without_limiting_equilibrium_is_no_equilibrium():
    # a membrane over a concave stretch: not convex on the contact interval
    scene = capstan.Scene(
        {"obstacle.shape": "prism", "obstacle.u": "2*sin(t)", "obstacle.v": "-cos(t)"}
    )
    with pytest.raises(capstan.CapstanError):
        capstan.tension(scene)


def test_grading_off_fem_qp_is_a_value_error_naming_the_key():
    with pytest.raises(ValueError, match="discretisation.grading"):
        capstan.contact(capstan.Scene({"discretisation.grading": 0.4}))


def test_petsc_backend_is_refused_with_the_reason_and_the_cli_route():
    # The wheel is built without the cargo feature `petsc`: a typed InvalidInputError that says
    # why and how to run a PETSc solve from Python (the CLI under mpirun).
    keys = {"solver.nonlinear": "full-newton", "solver.linear": "petsc"}
    with pytest.raises(capstan.InvalidInputError) as e:
        capstan.Scene(keys)
    text = str(e.value)
    assert "solver.linear" in text and "--features petsc" in text, text
    assert "Python package is built without it" in text and "mpirun" in text, text
    scene = capstan.Scene({"solver.nonlinear": "full-newton"})
    with pytest.raises(capstan.InvalidInputError, match="Python package is built without it"):
        scene.set("solver.linear", "petsc")
