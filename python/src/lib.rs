//! `cycloid._cycloid`: the extension module under the Python package `cycloid`
//! (python/cycloid/), which gives it its public API, docstrings and stub. Everything here is
//! private to that package.
//!
//! The results reach Python through the results JSON's own typed documents
//! (`cycloid::report::json`): they are serialised by [`tree::Ser`] straight into Python
//! objects, every list of numbers a numpy array, so the keys, units and shapes are those of
//! `cycloid check --json` and no JSON text is written or read. The tolerance samples, the
//! profile and the fit come the same way from the documents their CSV files are written from
//! (`report::tolerance::SamplesDoc`, `report::export::ProfileDoc`, `report::fit::FitDoc`).
//! Every computation runs with the GIL released; a Rust panic becomes a Python `RuntimeError`.

mod progress;
mod tree;

use cycloid::error::{Error, ErrorKind};
use cycloid::report::json::{Contents, Document};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Arc;

/// A validated spec (the Python `cycloid.Spec` holds one).
#[pyclass(frozen, module = "cycloid._cycloid", name = "Spec")]
struct PySpec {
    spec: Arc<cycloid::spec::Spec>,
}

#[pymethods]
impl PySpec {
    /// The YAML text the spec was read from.
    #[getter]
    fn source(&self) -> &str {
        &self.spec.source
    }

    /// The path the spec was read from (errors name it; files resolve against its folder).
    #[getter]
    fn path(&self) -> &str {
        &self.spec.path
    }

    /// The spec's `name`.
    #[getter]
    fn name(&self) -> &str {
        &self.spec.name
    }

    /// The scenes' names, in spec order.
    #[getter]
    fn scene_names(&self) -> Vec<String> {
        self.spec.scenes.iter().map(|s| s.name.clone()).collect()
    }
}

/// The Python exception for `e`: `cycloid.SpecError` or `cycloid.ComputationError` (defined in
/// `cycloid._errors`), with the CLI's text of the error as its `str()`.
fn py_error(py: Python<'_>, e: &Error) -> PyErr {
    let class = match e.kind {
        ErrorKind::Computation => "ComputationError",
        _ => "SpecError",
    };
    let kind = match e.kind {
        ErrorKind::Io => "io",
        ErrorKind::Syntax => "syntax",
        ErrorKind::InvalidValue => "invalid_value",
        ErrorKind::ImpossibleDesign => "impossible_design",
        ErrorKind::Computation => "computation",
        ErrorKind::Usage => "usage",
        ErrorKind::OutputClosed => "output_closed",
    };
    let made = (|| -> PyResult<PyErr> {
        let errors = py.import("cycloid._errors")?;
        let loc = e.location.as_ref();
        let value = errors.getattr(class)?.call1((
            e.to_string(),
            kind,
            e.message.as_str(),
            e.key_path.as_deref(),
            loc.map(|l| l.file.as_str()),
            loc.map(|l| l.line),
            loc.map(|l| l.column),
        ))?;
        Ok(PyErr::from_value(value))
    })();
    made.unwrap_or_else(|err| err)
}

/// Run `work` without the GIL; its error becomes the Python exception, a panic a
/// `RuntimeError`.
fn detached<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> cycloid::Result<T> + Send,
) -> PyResult<T> {
    let outcome = py.detach(|| catch_unwind(AssertUnwindSafe(work)));
    match outcome {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(e)) => Err(py_error(py, &e)),
        Err(panic) => {
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("a panic");
            Err(PyRuntimeError::new_err(format!(
                "cycloid: internal error (a bug: please report it with the spec): {what}"
            )))
        }
    }
}

/// Read and validate the spec file at `path`.
#[pyfunction]
fn load(py: Python<'_>, path: &str) -> PyResult<PySpec> {
    let path = path.to_string();
    let spec = detached(py, move || cycloid::spec::load(&path))?;
    Ok(PySpec {
        spec: Arc::new(spec),
    })
}

/// Parse and validate spec `text`; `path` names it in errors, and the files it names resolve
/// against its folder.
#[pyfunction]
fn parse(py: Python<'_>, path: &str, text: &str) -> PyResult<PySpec> {
    let (path, text) = (path.to_string(), text.to_string());
    let spec = detached(py, move || cycloid::spec::parse(&path, &text))?;
    Ok(PySpec {
        spec: Arc::new(spec),
    })
}

/// The spec with the scalars at dotted keys replaced by YAML texts, edited in place in its
/// text and validated again.
#[pyfunction]
fn with_values(py: Python<'_>, spec: &PySpec, values: Vec<(String, String)>) -> PyResult<PySpec> {
    let spec = spec.spec.clone();
    let edited = detached(py, move || {
        let pairs: Vec<(&str, &str)> = values
            .iter()
            .map(|(k, v)| (k.as_str(), v.as_str()))
            .collect();
        cycloid::spec::edit::with_values(&spec.path, &spec.source, &pairs)
    })?;
    Ok(PySpec {
        spec: Arc::new(edited.1),
    })
}

/// The YAML text `text` as Python objects (dicts, lists, numbers, strings).
#[pyfunction]
fn yaml_to_py(py: Python<'_>, text: &str) -> PyResult<Py<PyAny>> {
    let value: serde_yaml::Value = serde_yaml::from_str(text)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    tree::to_plain_py(py, &value)
}

/// YAML text of a JSON text (the Python layer's `from_dict` writes its dict as JSON).
#[pyfunction]
fn json_to_yaml(text: &str) -> PyResult<String> {
    let value: serde_yaml::Value = serde_json::from_str(text)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    serde_yaml::to_string(&value).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// One `check` run: the engine's data, kept for `to_json`.
#[pyclass(frozen, module = "cycloid._cycloid", name = "Run")]
struct PyRun {
    run: cycloid::CheckRun,
}

impl PyRun {
    fn document(&self) -> Document<'_> {
        Document::new(&Contents::of(&self.run))
    }
}

#[pymethods]
impl PyRun {
    /// The results JSON, as `cycloid check --json` writes it.
    fn to_json(&self, py: Python<'_>) -> PyResult<String> {
        detached(py, || {
            serde_json::to_string(&self.document()).map_err(|e| Error::computation(e.to_string()))
        })
    }

    /// The results document as Python objects: numbers lists as numpy arrays.
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        tree::to_py(py, &self.document())
    }

    /// Every check passed.
    #[getter]
    fn passed(&self) -> bool {
        self.run.passed()
    }
}

/// Run `cycloid check` on `spec`: every scene, the limits, the goldens and studies; with
/// `tolerance` the tolerance study too. `progress(fraction, phase)` is called now and then.
#[pyfunction]
#[pyo3(signature = (spec, tolerance=false, progress=None))]
fn check(
    py: Python<'_>,
    spec: &PySpec,
    tolerance: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<PyRun> {
    let spec = spec.spec.clone();
    let sink = progress::Sink::new(progress);
    let run = detached(py, || {
        let options = cycloid::CheckOptions {
            writes: cycloid::engine::scene::Writes {
                json: true,
                report: false,
            },
            tolerance,
            review: None,
        };
        cycloid::check(&spec, &options, &sink)
    });
    sink.finish(py)?;
    Ok(PyRun { run: run? })
}

/// The spec's optimisation studies (the one named `study`, else all), as the results JSON's
/// `studies` records.
#[pyfunction]
#[pyo3(signature = (spec, study=None, progress=None))]
fn optimise(
    py: Python<'_>,
    spec: &PySpec,
    study: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Py<PyAny>> {
    let spec = spec.spec.clone();
    let sink = progress::Sink::new(progress);
    let results = detached(py, || {
        let run = cycloid::optimise(&spec, study.as_deref(), None, &sink)?;
        Ok(run.studies.into_iter().map(|(_, r)| r).collect::<Vec<_>>())
    });
    sink.finish(py)?;
    tree::to_py(py, &cycloid::report::json::studies(&spec, &results?))
}

/// The spec's tolerance study (`samples` and `seed` in place of the spec's): its samples
/// document (`cycloid::report::tolerance::SamplesDoc`, the columns of `--samples-csv` by name,
/// each a numpy array) and the JSON report of `--json` as text.
#[pyfunction]
#[pyo3(signature = (spec, samples=None, seed=None, progress=None))]
fn tolerance(
    py: Python<'_>,
    spec: &PySpec,
    samples: Option<usize>,
    seed: Option<u64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Py<PyAny>, String)> {
    let mut spec = (*spec.spec).clone();
    if let (Some(seed), Some(t)) = (seed, spec.tolerances.as_mut()) {
        t.seed = seed;
    }
    let sink = progress::Sink::new(progress);
    let table = detached(py, || {
        let run = cycloid::tolerance(&spec, samples, false, &sink)?;
        let report = &cycloid::report::tolerance::json;
        let json = report(&run.study, &run.summary, &run.records, None)?;
        let doc = cycloid::report::tolerance::samples(&run.study, &run.records);
        Ok((doc, json))
    });
    sink.finish(py)?;
    let (doc, json) = table?;
    Ok((tree::to_py(py, &doc)?, json))
}

/// The requirements search of `cycloid design` on the requirements file at `path`: the front,
/// per design its file name and spec text (as `--out` writes them), and `front.csv` (each
/// design's variables, figures and objectives).
#[pyfunction]
#[pyo3(signature = (path, progress=None))]
fn design(
    py: Python<'_>,
    path: &str,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Vec<(String, String)>, String)> {
    let path = path.to_string();
    let sink = progress::Sink::new(progress);
    let front = detached(py, || {
        let req = cycloid::spec::requirements::load(&path)?;
        let run = cycloid::engine::commands::design(&req, &path, &sink)?;
        let csv = cycloid::report::design::csv(&req, &run.search);
        Ok((run.specs, csv))
    });
    sink.finish(py)?;
    front
}

/// The spec's whole modified profile, chords within `tolerance_mm`: its document
/// (`cycloid::report::export::ProfileDoc`: the columns of `cycloid profile --csv`, x_mm, y_mm,
/// normal_x, normal_y, curvature_per_mm, as numpy arrays, and the output-pin holes of its DXF,
/// `holes_x_mm`, `holes_y_mm`, `hole_radius_mm`).
#[pyfunction]
fn profile(py: Python<'_>, spec: &PySpec, tolerance_mm: f64) -> PyResult<Py<PyAny>> {
    let spec = spec.spec.clone();
    let doc = detached(py, move || {
        let points = cycloid::profile(&spec, tolerance_mm)?;
        Ok(cycloid::report::export::ProfileDoc::new(&spec, &points))
    })?;
    tree::to_py(py, &doc)
}

/// Identify the disc of the spec's `measured_profile`: its document
/// (`cycloid::report::fit::FitDoc`: the estimates as (value, standard uncertainty) tuples in
/// the spec's units, the residuals, the report `cycloid fit` prints and the form-error curve of
/// `--form-csv` as numpy columns).
#[pyfunction]
fn fit(py: Python<'_>, spec: &PySpec) -> PyResult<Py<PyAny>> {
    let spec = spec.spec.clone();
    let doc = detached(py, move || {
        let id = cycloid::fit(&spec)?;
        Ok(cycloid::report::fit::document(&spec, &id))
    })?;
    tree::to_py(py, &doc)
}

#[pymodule]
fn _cycloid(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySpec>()?;
    m.add_class::<PyRun>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(parse, m)?)?;
    m.add_function(wrap_pyfunction!(with_values, m)?)?;
    m.add_function(wrap_pyfunction!(yaml_to_py, m)?)?;
    m.add_function(wrap_pyfunction!(json_to_yaml, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(optimise, m)?)?;
    m.add_function(wrap_pyfunction!(tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(profile, m)?)?;
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    m.add_function(wrap_pyfunction!(design, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
