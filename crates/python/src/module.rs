//! The PyO3 module: `Scene`, the solves, errors as Python exceptions, progress as a callback.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, mpsc};
use std::time::Duration;

use capstan::CliError;
use capstan::api;
use capstan::elasticity::contact::ContactErrorKind;
use capstan::elasticity::solvers::{Observer, Progress};
use capstan::output::to_json_string;
use capstan::provenance::Stamped;
use capstan::scene::Scene;
use pyo3::exceptions::{PyKeyboardInterrupt, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// What went wrong, as the Python exception classes of `capstan._errors` name it.
fn raise(py: Python<'_>, class: &str, message: String) -> PyErr {
    let made = py
        .import("capstan._errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.call1((message.clone(),)));
    match made {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// A facade error as its Python exception: bad input `InvalidInputError` (a `ValueError`), no
/// equilibrium `NoEquilibriumError`, no convergence `NotConvergedError`, an interrupted solve
/// `KeyboardInterrupt`, anything else `CapstanError`; the message is the Rust error's text.
fn to_py(py: Python<'_>, e: &CliError) -> PyErr {
    if let CliError::Contact(c) = e
        && c.kind() == ContactErrorKind::Interrupted
    {
        return PyKeyboardInterrupt::new_err(e.to_string());
    }
    let class = match e.exit_code() {
        2 => "InvalidInputError",
        3 => "NoEquilibriumError",
        4 => "NotConvergedError",
        _ => "CapstanError",
    };
    raise(py, class, e.to_string())
}

/// How long the waiting interpreter sleeps between two checks for Ctrl-C.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `f` on a worker thread while this (the interpreter's) thread waits without the GIL and
/// checks for signals every [`SIGNAL_POLL`] and once more when the result arrives. Ctrl-C raises
/// `KeyboardInterrupt` at once (or when a solve shorter than one poll returns) and sets
/// the stop flag `f` receives: an observed solve stops at its next iteration, anything else
/// finishes in the background and is discarded. A panic becomes a `CapstanError` rather than
/// crossing the boundary.
fn run<T: Send + 'static>(
    py: Python<'_>,
    f: impl FnOnce(&AtomicBool) -> Result<T, CliError> + Send + 'static,
) -> PyResult<T> {
    let stop = Arc::new(AtomicBool::new(false));
    let (tx, rx) = mpsc::channel();
    let flag = Arc::clone(&stop);
    std::thread::Builder::new()
        .name("capstan-solve".into())
        .stack_size(64 << 20) // the main thread's size class: deep recursion in orderings
        .spawn(move || {
            let _ = tx.send(catch_unwind(AssertUnwindSafe(|| f(&flag))));
        })
        .map_err(|e| {
            raise(
                py,
                "CapstanError",
                format!("cannot start a solve thread: {e}"),
            )
        })?;
    let mut rx = rx;
    loop {
        // the receiver is not `Sync`: it goes into the GIL-free closure and comes back
        let (received, back) = py.detach(move || (rx.recv_timeout(SIGNAL_POLL), rx));
        rx = back;
        // A Ctrl-C that arrived while the solve finished within one poll still raises: the
        // result is discarded, as an interrupted `time.sleep` discards its remaining wait.
        if received.is_ok() {
            py.check_signals()?;
        }
        match received {
            Ok(Ok(Ok(t))) => return Ok(t),
            Ok(Ok(Err(e))) => return Err(to_py(py, &e)),
            Ok(Err(panic)) => {
                let what = panic
                    .downcast_ref::<&str>()
                    .map(|s| (*s).to_owned())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown".into());
                return Err(raise(
                    py,
                    "CapstanError",
                    format!("internal error (a bug in capstan, please report it): {what}"),
                ));
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    stop.store(true, Ordering::Relaxed);
                    return Err(e);
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(raise(
                    py,
                    "CapstanError",
                    "the solve thread ended without a result".into(),
                ));
            }
        }
    }
}

/// A Python value as a TOML value (bool, int, float, str, list, tuple, dict).
fn toml_value(v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if v.cast::<PyInt>().is_ok() {
        return Ok(toml::Value::Integer(v.extract::<i64>()?));
    }
    if v.cast::<PyFloat>().is_ok() {
        return Ok(toml::Value::Float(v.extract::<f64>()?));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(toml::Value::String(s.to_cow()?.into_owned()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, x) in d.iter() {
            t.insert(k.extract::<String>()?, toml_value(&x)?);
        }
        return Ok(toml::Value::Table(t));
    }
    if v.cast::<PyList>().is_ok() || v.cast::<PyTuple>().is_ok() {
        let items: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
        return Ok(toml::Value::Array(
            items.iter().map(toml_value).collect::<PyResult<_>>()?,
        ));
    }
    // numpy scalars and other numbers: an integer if it is one, else a float
    if let Ok(i) = v.extract::<i64>() {
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    Err(PyTypeError::new_err(format!(
        "a scene value must be bool, int, float, str, list or dict, not {}",
        v.get_type().name()?
    )))
}

/// A validated scene: every key of the command line's scene files, defaults filled in.
#[pyclass(name = "Scene", module = "capstan._capstan", subclass, from_py_object)]
#[derive(Clone)]
struct PyScene {
    scene: Scene,
}

#[pymethods]
impl PyScene {
    /// `Scene()` is the default scene (the paper's section 3); `Scene({"body": {"poisson": 0.3}})`
    /// or `Scene({"body.poisson": 0.3})` sets keys, checked as a scene file is.
    #[new]
    #[pyo3(signature = (keys = None))]
    fn new(py: Python<'_>, keys: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut table = toml::Table::new();
        if let Some(d) = keys {
            for (k, v) in d.iter() {
                let key: String = k.extract()?;
                let value = toml_value(&v)?;
                match (key.split_once('.'), value) {
                    (Some((section, field)), value) => {
                        let entry = table
                            .entry(section.to_owned())
                            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                        if let toml::Value::Table(t) = entry {
                            t.insert(field.to_owned(), value);
                        }
                    }
                    (None, value) => {
                        table.insert(key, value);
                    }
                }
            }
        }
        let scene = Scene::from_table(table, "Scene(dict)").map_err(|e| to_py(py, &e))?;
        Ok(Self { scene })
    }

    /// Replaces this scene by TOML text, as a scene file holds it (`origin` names it in errors).
    #[pyo3(signature = (text, origin = "scene"))]
    fn _load_toml(&mut self, py: Python<'_>, text: &str, origin: &str) -> PyResult<()> {
        self.scene = Scene::from_toml_str(text, origin, &[]).map_err(|e| to_py(py, &e))?;
        Ok(())
    }

    /// Sets one key (`"body.poisson"`) to a value, checked (a `ValueError` naming key, value
    /// and allowed range); the scene is unchanged on error.
    fn set(&mut self, py: Python<'_>, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let value = toml_value(value)?;
        self.scene = self
            .scene
            .with_value(key, value, "Scene.set")
            .map_err(|e| to_py(py, &e))?;
        Ok(())
    }

    /// The resolved scene as TOML (what `--out` writes as `scene.toml`).
    fn to_toml(&self, py: Python<'_>) -> PyResult<String> {
        let table = self.scene.to_table().map_err(|e| to_py(py, &e))?;
        Ok(table.to_string())
    }

    /// The resolved scene as JSON (the `scene` key of every `--json` report).
    fn _to_json(&self, py: Python<'_>) -> PyResult<String> {
        to_json_string(&self.scene).map_err(|e| to_py(py, &CliError::from(e)))
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.scene == other.scene
    }

    fn __repr__(&self) -> String {
        let s = &self.scene;
        format!(
            "Scene(obstacle={:?}, friction.law={:?}, grid={}x{}, tau_max={})",
            s.obstacle.shape, s.friction.law, s.grid.n2, s.grid.n3, s.loads.tau_max
        )
    }
}

/// `report` with `capstan_version` and the scene, as `--json` prints it.
fn stamped<T: serde::Serialize>(report: &T, scene: &Scene) -> Result<String, CliError> {
    Ok(to_json_string(&Stamped::new(report, Some(scene)))?)
}

/// `capstan tension --json`.
#[pyfunction]
fn tension(py: Python<'_>, scene: &PyScene) -> PyResult<String> {
    let s = scene.scene.clone();
    run(py, move |_| stamped(&api::tension(&s)?, &s))
}

/// `capstan infer-mu --model MODEL --json` (`capstan`, `membrane` or `kikuchi-oden`).
#[pyfunction]
fn infer_mu(py: Python<'_>, scene: &PyScene, model: &str) -> PyResult<String> {
    use api::FrictionModel;
    let model = match model {
        "capstan" => FrictionModel::Capstan,
        "membrane" => FrictionModel::Membrane,
        "kikuchi-oden" => FrictionModel::KikuchiOden,
        other => {
            return Err(raise(
                py,
                "InvalidInputError",
                format!(
                    "model = {other:?} is not one of \"capstan\", \"membrane\", \"kikuchi-oden\""
                ),
            ));
        }
    };
    let s = scene.scene.clone();
    run(py, move |_| stamped(&api::infer_mu(&s, model)?, &s))
}

/// `capstan threshold --json`.
#[pyfunction]
fn threshold(py: Python<'_>, scene: &PyScene) -> PyResult<String> {
    let s = scene.scene.clone();
    run(py, move |_| stamped(&api::threshold(&s)?, &s))
}

/// `capstan membrane-path --json`, with the node angles and the per-step node profiles
/// (`displacement`, `slip_increment`, `tension`, `friction`, `state`: each steps x nodes,
/// row-major).
/// `callback(progress: dict)` sees every semismooth iteration (stage `membrane`, with the
/// stick/slip counts).
#[pyfunction]
#[pyo3(signature = (scene, callback = None))]
#[allow(clippy::type_complexity)] // (json, theta, [(name, values)]) as Python receives them
fn membrane_path(
    py: Python<'_>,
    scene: &PyScene,
    callback: Option<Py<PyAny>>,
) -> PyResult<(String, Vec<f64>, Vec<(String, Vec<f64>)>)> {
    let s = scene.scene.clone();
    run_observed(py, callback, move |observer| {
        let r = api::membrane_path_observed(&s, observer)?;
        let names = [
            "displacement",
            "slip_increment",
            "tension",
            "friction",
            "state",
        ];
        let profiles = names
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let values = r
                    .profiles
                    .iter()
                    .flat_map(|p| p[k].iter().copied())
                    .collect();
                ((*name).to_string(), values)
            })
            .collect();
        Ok((stamped(&r, &s)?, r.theta.clone(), profiles))
    })
}

/// `capstan contact-path --json`: the thick body along `loads.path`, each step's contact
/// fields included. `callback(progress: dict)` sees every Newton iterate of every step.
#[pyfunction]
#[pyo3(signature = (scene, callback = None))]
fn contact_path(py: Python<'_>, scene: &PyScene, callback: Option<Py<PyAny>>) -> PyResult<String> {
    let s = scene.scene.clone();
    run_observed(py, callback, move |observer| {
        stamped(&api::contact_path_observed(&s, observer)?, &s)
    })
}

/// The geometry at the points `x2`: the keys of `capstan geometry --json` and the tensors.
#[pyfunction]
fn geometry(py: Python<'_>, scene: &PyScene, x2: Vec<f64>) -> PyResult<String> {
    let s = scene.scene.clone();
    run(py, move |_| stamped(&api::geometry_at(&s, &x2)?, &s))
}

/// `capstan sweep --param PARAM --json` over `values`; with `out`, its files as `--out` writes them.
#[pyfunction]
#[pyo3(signature = (scene, param, values, out = None))]
fn sweep(
    py: Python<'_>,
    scene: &PyScene,
    param: &str,
    values: Vec<f64>,
    out: Option<std::path::PathBuf>,
) -> PyResult<String> {
    let (s, param) = (scene.scene.clone(), param.to_owned());
    run(py, move |_| {
        let fields = match &out {
            Some(dir) => Some(capstan::output::OutputDir::create(dir)?),
            None => None,
        };
        let at = api::SweepPoints::new(&param, &values).fields(fields.as_ref());
        let report = api::sweep(&s, at)?;
        if let Some(dir) = &out {
            api::write_sweep(dir, &report, &s)?;
        }
        stamped(&report, &s)
    })
}

/// Forwards progress to a Python callback (under a brief GIL acquire) and stops the solve on
/// Ctrl-C (the waiting interpreter sets `stop`) or an exception in the callback (kept in `error`
/// and raised when the solve returns).
/// [`run`] with a [`PyObserver`] over `callback` handed to `f`: where the callback raised,
/// that Python error is returned, not the solver's `Interrupted`.
fn run_observed<T: Send + 'static>(
    py: Python<'_>,
    callback: Option<Py<PyAny>>,
    f: impl FnOnce(&mut PyObserver<'_>) -> Result<T, CliError> + Send + 'static,
) -> PyResult<T> {
    let error = Arc::new(Mutex::new(None));
    let seen = Arc::clone(&error);
    let result = run(py, move |stop| {
        let mut observer = PyObserver {
            callback,
            error: seen,
            stop,
        };
        f(&mut observer)
    });
    if let Some(e) = error.lock().ok().and_then(|mut e| e.take()) {
        return Err(e);
    }
    result
}

struct PyObserver<'a> {
    callback: Option<Py<PyAny>>,
    error: Arc<Mutex<Option<PyErr>>>,
    stop: &'a AtomicBool,
}

impl PyObserver<'_> {
    fn failed(&self) -> bool {
        self.error.lock().map_or(true, |e| e.is_some())
    }
}

impl Observer<f64> for PyObserver<'_> {
    fn iteration(&mut self, p: &Progress<f64>) {
        if self.failed() {
            return;
        }
        let Some(callback) = &self.callback else {
            return;
        };
        let error = &self.error;
        Python::attach(|py| {
            let call = || -> PyResult<()> {
                let d = PyDict::new(py);
                d.set_item("stage", p.stage.name())?;
                d.set_item("iteration", p.iteration)?;
                d.set_item("residual", p.residual_norm)?;
                d.set_item("step_length", p.step_length)?;
                d.set_item("stick", p.active.map(|a| a.stick))?;
                d.set_item("slip", p.active.map(|a| a.slip))?;
                d.set_item("separated", p.active.map(|a| a.separated))?;
                d.set_item("phase", p.work.map(|w| w.phase.name()))?;
                d.set_item("done", p.work.map(|w| w.done))?;
                d.set_item("total", p.work.map(|w| w.total))?;
                callback.call1(py, (d,))?;
                Ok(())
            };
            if let Err(e) = call()
                && let Ok(mut slot) = error.lock()
            {
                *slot = Some(e);
            }
        });
    }

    fn interrupted(&mut self) -> bool {
        self.stop.load(Ordering::Relaxed) || self.failed()
    }
}

/// One whole-body array: name, components per node, little-endian `f64` bytes.
type Field = (String, usize, Vec<u8>);

/// The node positions and the point arrays of a body VTU as `(name, k, bytes)`.
fn field_bytes(points: &[[f64; 3]], arrays: &[capstan::output::DataArray]) -> Vec<Field> {
    let mut fields: Vec<Field> = vec![(
        "points".into(),
        3,
        points
            .as_flattened()
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect(),
    )];
    for a in arrays {
        let bytes = a.values.iter().flat_map(|x| x.to_le_bytes()).collect();
        fields.push((a.name.clone(), a.components, bytes));
    }
    fields
}

/// `capstan contact --json`, the whole-body fields `(name, k, bytes)` on the `n2 x n3` grid
/// (node `i2 n3 + i3`; a 3-D body: `n1 x n2 x n3`, node `(i1 n2 + i2) n3 + i3`) and the grid's
/// shape. `callback(progress: dict)` sees every iteration.
#[pyfunction]
#[pyo3(signature = (scene, callback = None, out = None))]
#[allow(clippy::type_complexity)] // (json, fields, shape) as Python receives them
fn contact<'py>(
    py: Python<'py>,
    scene: &PyScene,
    callback: Option<Py<PyAny>>,
    out: Option<std::path::PathBuf>,
) -> PyResult<(
    String,
    Vec<(String, usize, Bound<'py, PyBytes>)>,
    Vec<usize>,
)> {
    let s = scene.scene.clone();
    let r = run_observed(py, callback, move |observer| {
        let (report, run) = api::contact_observed(&s, observer)?;
        if let Some(dir) = &out {
            api::write_contact(dir, &report, &run, &s)?;
        }
        let json = stamped(&report, &s)?;
        let solved = match &run {
            api::ContactRun::Plane(solved) => solved,
            api::ContactRun::Solid { solution, model } => {
                let Some(body) = model.solid() else {
                    return Ok((json, Vec::new(), Vec::new()));
                };
                let (grid, fields, coordinates) = api::solid_fields(&s, body, solution)?;
                let vtu = capstan::output::solid_body::solid_vtu(
                    &grid,
                    &fields,
                    &coordinates,
                    &solution.contact,
                );
                let shape = if grid.is_unstructured() {
                    vec![grid.node_count()] // a mesh (fem-qp-corner): one axis of nodes
                } else {
                    vec![grid.n1(), grid.n2(), grid.n3()]
                };
                return Ok((json, field_bytes(grid.points(), vtu.point_arrays()), shape));
            }
        };
        let grid = capstan::output::body::body_grid(&solved.obstacle, &solved.fields)
            .map_err(CliError::from)?;
        let vtu = capstan::output::body::body_vtu(&grid, &solved.fields, &solved.solution.contact);
        Ok((
            json,
            field_bytes(grid.points(), vtu.point_arrays()),
            vec![grid.n2(), grid.n3()],
        ))
    });
    let (json, fields, shape) = r?;
    let fields = fields
        .into_iter()
        .map(|(n, k, b)| (n, k, PyBytes::new(py, &b)))
        .collect();
    Ok((json, fields, shape))
}

/// The version of the Rust library (`capstan_version` of every report).
#[pyfunction]
fn version() -> &'static str {
    capstan::provenance::CAPSTAN_VERSION
}

#[pymodule]
fn _capstan(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_function(wrap_pyfunction!(tension, m)?)?;
    m.add_function(wrap_pyfunction!(infer_mu, m)?)?;
    m.add_function(wrap_pyfunction!(threshold, m)?)?;
    m.add_function(wrap_pyfunction!(geometry, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(contact, m)?)?;
    m.add_function(wrap_pyfunction!(membrane_path, m)?)?;
    m.add_function(wrap_pyfunction!(contact_path, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
