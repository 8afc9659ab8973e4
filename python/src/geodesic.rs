//! Photons from Python: `geodesic` (one photon's trajectory), `geodesics` (many photons' fates,
//! in parallel with the GIL released) and `deflections` (the scattering angles `nullpath geodesic`
//! prints). The physics is the physics crate's ([`spacetime::geodesic::from_observer`],
//! [`spacetime::scattering`]); this file only moves arrays.

use crate::spacetime::{error, PySpacetime};
use numpy::ndarray::{Array1, Array2};
use numpy::{AllowTypeChange, IntoPyArray, PyArrayLike1, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use spacetime::geodesic::from_observer::{NoLaunch, Photon, Recorded};
use spacetime::geodesic::Failure;
use spacetime::scattering::scatter;
use spacetime::{Fate, Region, Spacetime, Stepping, TraceSettings};

/// The fates' names, indexed by the codes `geodesics` returns.
pub const FATES: [&str; 4] = ["escaped", "captured", "traversed", "failed"];

fn fate_code(fate: &Fate) -> u8 {
    match fate {
        Fate::Escaped { .. } => 0,
        Fate::Captured => 1,
        Fate::Traversed { .. } => 2,
        // Nothing stops these photons (no scene); were one stopped, it did not end as asked.
        Fate::Failed(_) | Fate::Stopped => 3,
    }
}

/// The direction of an escaped or traversed photon, NaN otherwise.
fn end_direction(fate: &Fate) -> [f64; 3] {
    match fate {
        Fate::Escaped { direction } | Fate::Traversed { direction } => *direction,
        Fate::Captured | Fate::Stopped | Fate::Failed(_) => [f64::NAN; 3],
    }
}

fn failure_name(fate: &Fate) -> Option<&'static str> {
    match fate {
        Fate::Failed(Failure::OutOfSteps) => Some("out of steps (max_steps)"),
        Fate::Failed(Failure::StepUnderflow) => Some("step underflow (error control asked for too small a step)"),
        Fate::Failed(Failure::NonFinite) => Some("the state stopped being finite"),
        Fate::Escaped { .. } | Fate::Captured | Fate::Traversed { .. } | Fate::Stopped => None,
    }
}

/// The tracing settings from the keywords, each checked, the escape radius by default a
/// thousand length scales (and beyond every start).
fn settings(
    py: Python<'_>,
    spacetime: &Spacetime,
    farthest_start: f64,
    rtol: f64,
    escape_radius: Option<f64>,
    max_steps: u32,
) -> PyResult<TraceSettings> {
    if !(rtol > 0.0 && rtol < 1.0) {
        return Err(error(py, Some("rtol"), format!("rtol must be in (0, 1), got {rtol}")));
    }
    let escape_radius = escape_radius.unwrap_or((1e3 * spacetime.length_scale()).max(2.0 * farthest_start));
    if !(escape_radius.is_finite() && escape_radius > farthest_start) {
        return Err(error(
            py,
            Some("escape_radius"),
            format!(
                "escape_radius must be finite and beyond every start (farthest at {farthest_start}), \
                 got {escape_radius}"
            ),
        ));
    }
    if max_steps == 0 {
        return Err(error(py, Some("max_steps"), "max_steps must be at least 1"));
    }
    Ok(TraceSettings { stepping: Stepping::Adaptive { rtol }, escape_radius, max_steps, ..TraceSettings::default() })
}

/// The only observer photons start from: the local static one (the chart's normal observer
/// where none can stay at rest), as a camera's rays start.
fn check_observer(py: Python<'_>, observer: &str) -> PyResult<()> {
    match observer {
        "static" => Ok(()),
        other => Err(error(py, Some("observer"), format!("observer must be \"static\", got \"{other}\""))),
    }
}

fn region_of(py: Python<'_>, region: &str) -> PyResult<Region> {
    match region {
        "upper" => Ok(Region::Upper),
        "lower" => Ok(Region::Lower),
        other => Err(error(py, Some("region"), format!("region must be \"upper\" or \"lower\", got \"{other}\""))),
    }
}

/// Rows of three from an array of shape (3,) or (N, 3), named `name` in errors.
fn rows(py: Python<'_>, name: &str, array: &PyArrayLikeDyn<'_, f64, AllowTypeChange>) -> PyResult<Vec<[f64; 3]>> {
    let view = array.as_array();
    // A C-ordered (N, 3) array is read as one slice (the common case, and the one bulk calls
    // take, where walking rows of a dynamic-dimension view costs more than tracing flat rays).
    let shaped = match view.shape() {
        [3] => Some(vec![[view[[0]], view[[1]], view[[2]]]]),
        [_, 3] => Some(match view.as_slice() {
            Some(flat) => flat.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect(),
            None => view.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect(),
        }),
        _ => None,
    };
    let Some(rows) = shaped else {
        return Err(error(py, Some(name), format!("{name} must have shape (3,) or (N, 3), got {:?}", view.shape())));
    };
    if rows.iter().flatten().any(|c| !c.is_finite()) {
        return Err(error(py, Some(name), format!("{name} must be finite")));
    }
    Ok(rows)
}

/// Unit directions: each of `rows` normalised, none zero.
fn unit(py: Python<'_>, name: &str, mut rows: Vec<[f64; 3]>) -> PyResult<Vec<[f64; 3]>> {
    for r in &mut rows {
        let norm = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        if norm == 0.0 {
            return Err(error(py, Some(name), format!("{name} must not be zero")));
        }
        *r = r.map(|c| c / norm);
    }
    Ok(rows)
}

fn launch<'s>(
    py: Python<'_>,
    spacetime: &'s Spacetime,
    region: Region,
    position: [f64; 3],
    direction: [f64; 3],
) -> PyResult<Photon<'s>> {
    Photon::launch(spacetime, region, position, direction).map_err(|e| match e {
        NoLaunch::OffChart => error(py, Some("position"), format!("position {position:?} {e}")),
        NoLaunch::NotReversible => error(py, Some("spacetime"), format!("{} spacetime: {e}", spacetime.name())),
    })
}

/// The trajectory of one photon that leaves ``position`` (world coordinates, the hole at the
/// origin, a spin along z) in the ``direction`` its local static observer measures (the
/// chart's normal observer where none can stay at rest), with unit energy as that observer
/// measures it, followed forwards in time by integrating Hamilton's equations in 4-D.
///
/// Returns a dict: ``lambda``, ``t``, ``x``, ``y``, ``z`` (arrays (N,): the affine parameter
/// and the position at the start and at every accepted step), ``p`` (N, 4) the covariant
/// momenta ``p_μ``, ``hamiltonian`` (N,) ``H = ½ g^{μν} p_μ p_ν`` (zero for light), ``E``,
/// ``L_z`` and ``Q`` (N,) the constants of motion the spacetime has (``None`` otherwise: ``Q``
/// is Carter's, for Kerr's family), ``fate`` (``"escaped"``, ``"captured"``, ``"traversed"`` or
/// ``"failed"``), ``failure`` (why it failed, else ``None``), ``direction`` (its world direction
/// of travel at the escape radius, else NaN), ``steps`` and ``max_abs_hamiltonian``.
///
/// Times and momenta are in the chart in which the photon runs forwards: the spacetime's own
/// for static ones, for holes the ingoing Kerr–Schild chart, regular on the future horizon (for
/// a spinning hole its positions differ from the world's by a turn about the spin axis that
/// vanishes far away). ``rtol`` is the integrator's relative tolerance, ``escape_radius``
/// (default a thousand masses, and beyond the start) where the photon has escaped, ``max_steps``
/// where it has failed. Raises ``SpacetimeError`` naming a bad argument, and for a metric written
/// by a user, whose light cannot be followed forwards.
#[pyfunction]
#[pyo3(signature = (
    spacetime, position, direction, *,
    rtol = 1e-10, escape_radius = None, max_steps = 1_000_000, observer = "static", region = "upper",
))]
#[allow(clippy::too_many_arguments)] // Python's keywords.
pub fn geodesic<'py>(
    py: Python<'py>,
    spacetime: &PySpacetime,
    position: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    direction: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    rtol: f64,
    escape_radius: Option<f64>,
    max_steps: u32,
    observer: &str,
    region: &str,
) -> PyResult<Bound<'py, PyDict>> {
    check_observer(py, observer)?;
    let region = region_of(py, region)?;
    let [position] = single(py, "position", rows(py, "position", &position)?)?;
    let [direction] = single(py, "direction", unit(py, "direction", rows(py, "direction", &direction)?)?)?;
    let spacetime = &spacetime.inner;
    let settings = settings(py, spacetime, norm(&position), rtol, escape_radius, max_steps)?;
    let photon = launch(py, spacetime, region, position, direction)?;
    let (trace, points) = py.detach(|| {
        let mut points: Vec<Recorded> = photon.start().into_iter().collect();
        let trace = photon.record(&settings, |r| points.push(r));
        (trace, points)
    });
    let out = PyDict::new(py);
    let column = |f: &dyn Fn(&Recorded) -> f64| points.iter().map(f).collect::<Array1<f64>>();
    out.set_item("lambda", column(&|r| r.lambda).into_pyarray(py))?;
    out.set_item("t", column(&|r| r.state.x[0]).into_pyarray(py))?;
    for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
        out.set_item(axis, column(&|r| r.position[i]).into_pyarray(py))?;
    }
    let p = Array2::from_shape_fn((points.len(), 4), |(i, mu)| points[i].state.p[mu]);
    out.set_item("p", p.into_pyarray(py))?;
    out.set_item("hamiltonian", column(&|r| photon.hamiltonian(&r.state)).into_pyarray(py))?;
    let conserved: Vec<_> = points.iter().map(|r| photon.conserved(&r.state)).collect();
    let constant = |f: &dyn Fn(usize) -> Option<f64>| -> Option<Array1<f64>> {
        (0..conserved.len()).map(f).collect::<Option<Vec<f64>>>().filter(|v| !v.is_empty()).map(Array1::from)
    };
    out.set_item("E", constant(&|i| conserved[i].energy).map(|a| a.into_pyarray(py)))?;
    out.set_item("L_z", constant(&|i| conserved[i].axial).map(|a| a.into_pyarray(py)))?;
    out.set_item("Q", constant(&|i| conserved[i].carter).map(|a| a.into_pyarray(py)))?;
    out.set_item("fate", trace.fate.name())?;
    out.set_item("failure", failure_name(&trace.fate))?;
    out.set_item("direction", Array1::from(end_direction(&trace.fate).to_vec()).into_pyarray(py))?;
    out.set_item("steps", trace.steps)?;
    out.set_item("max_abs_hamiltonian", trace.max_abs_hamiltonian)?;
    Ok(out)
}

fn single(py: Python<'_>, name: &str, rows: Vec<[f64; 3]>) -> PyResult<[[f64; 3]; 1]> {
    <[[f64; 3]; 1]>::try_from(rows).map_err(|_| error(py, Some(name), format!("{name} must have shape (3,)")))
}

fn norm(v: &[f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// How many threads: all of rayon's by default, else a pool of `threads`.
fn in_pool<T: Send>(py: Python<'_>, threads: Option<usize>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    match threads {
        None => Ok(py.detach(work)),
        Some(0) => Err(error(py, Some("threads"), "threads must be at least 1")),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| error(py, Some("threads"), format!("cannot start {n} threads: {e}")))?;
            Ok(py.detach(|| pool.install(work)))
        }
    }
}

/// The fates of many photons, traced in parallel with the tracer the spacetime chooses (in the
/// ray's plane for spherical metrics, as ``nullpath bench geodesics`` and the renderer do;
/// Kerr's own stepper; 4-D Hamiltonian otherwise), the GIL released.
///
/// ``positions`` and ``directions`` have shape (3,) or (N, 3) (one row is shared by every
/// photon); each photon starts as ``geodesic``'s does. Returns a dict of arrays: ``fate`` (N,)
/// ``uint8`` codes indexing ``nullpath.FATES`` (escaped, captured, traversed, failed),
/// ``direction`` (N, 3) the world direction of travel at the escape radius (NaN for captured
/// and failed photons) and ``steps`` (N,). The same for any ``threads`` (default: all cores).
#[pyfunction]
#[pyo3(signature = (
    spacetime, positions, directions, *,
    rtol = 1e-10, escape_radius = None, max_steps = 1_000_000, observer = "static", region = "upper", threads = None,
))]
#[allow(clippy::too_many_arguments)] // Python's keywords.
pub fn geodesics<'py>(
    py: Python<'py>,
    spacetime: &PySpacetime,
    positions: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    directions: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    rtol: f64,
    escape_radius: Option<f64>,
    max_steps: u32,
    observer: &str,
    region: &str,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    check_observer(py, observer)?;
    let region = region_of(py, region)?;
    let positions = rows(py, "positions", &positions)?;
    let directions = unit(py, "directions", rows(py, "directions", &directions)?)?;
    let n = positions.len().max(directions.len());
    if ![1, n].contains(&positions.len()) || ![1, n].contains(&directions.len()) {
        return Err(error(
            py,
            Some("directions"),
            format!(
                "positions ({} rows) and directions ({} rows) must have one row or the same number",
                positions.len(),
                directions.len()
            ),
        ));
    }
    let spacetime = &spacetime.inner;
    let farthest = positions.iter().map(norm).fold(0.0, f64::max);
    let settings = settings(py, spacetime, farthest, rtol, escape_radius, max_steps)?;
    // Every start is checked before any tracing, so that an error names the row at fault.
    let at = |rows: &[[f64; 3]], i: usize| rows[if rows.len() == 1 { 0 } else { i }];
    for i in 0..positions.len() {
        launch(py, spacetime, region, positions[i], directions[0])
            .map_err(|e| error(py, Some("positions"), format!("positions, row {i}: {}", e.value(py))))?;
    }
    let mut fates = vec![0u8; n];
    let mut ends = vec![[0.0f64; 3]; n];
    let mut steps = vec![0u32; n];
    in_pool(py, threads, || {
        (&mut fates, &mut ends, &mut steps).into_par_iter().enumerate().for_each(|(i, (fate, end, step))| {
            // Every start was launched above: none fails here.
            let Ok(photon) = Photon::launch(spacetime, region, at(&positions, i), at(&directions, i)) else {
                *fate = fate_code(&Fate::Stopped);
                return;
            };
            let trace = photon.trace(&settings);
            *fate = fate_code(&trace.fate);
            *end = end_direction(&trace.fate);
            *step = trace.steps;
        });
    })?;
    let out = PyDict::new(py);
    out.set_item("fate", Array1::from(fates).into_pyarray(py))?;
    out.set_item("direction", Array2::from(ends).into_pyarray(py))?;
    out.set_item("steps", Array1::from(steps).into_pyarray(py))?;
    Ok(out)
}

/// The deflection angles (radians, positive towards the centre) of rays coming in from
/// infinity with the impact parameters ``impacts`` (N,), in the plane tilted by
/// ``inclination`` degrees from the equator: what ``nullpath geodesic --json`` prints as
/// ``deflection_rad``, from the same code (``spacetime::scattering``), in parallel. NaN for
/// rays that do not come back out. For a spinning hole positive impacts are prograde.
#[pyfunction]
#[pyo3(signature = (spacetime, impacts, inclination = 0.0, *, rtol = 1e-10, threads = None))]
pub fn deflections<'py>(
    py: Python<'py>,
    spacetime: &PySpacetime,
    impacts: PyArrayLike1<'py, f64, AllowTypeChange>,
    inclination: f64,
    rtol: f64,
    threads: Option<usize>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    if !(inclination.is_finite() && inclination.abs() <= 180.0) {
        return Err(error(
            py,
            Some("inclination"),
            format!("inclination must be in [−180, 180] degrees, got {inclination}"),
        ));
    }
    if !(rtol > 0.0 && rtol < 1.0) {
        return Err(error(py, Some("rtol"), format!("rtol must be in (0, 1), got {rtol}")));
    }
    let impacts: Vec<f64> = impacts.as_array().to_vec();
    if impacts.iter().any(|b| !b.is_finite()) {
        return Err(error(py, Some("impacts"), "impacts must be finite"));
    }
    let spacetime = &spacetime.inner;
    let (inclination_rad, stepping) = (inclination.to_radians(), Stepping::Adaptive { rtol });
    let angles = in_pool(py, threads, || {
        impacts
            .par_iter()
            .map(|&b| scatter(spacetime, b, inclination_rad, stepping).deflection_rad)
            .collect::<Vec<f64>>()
    })?;
    Ok(Array1::from(angles).into_pyarray(py))
}
