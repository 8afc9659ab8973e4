//! `[spacetime] type = "metric"`: a metric written in the scene file as expressions for its
//! components `g_ab`, in Cartesian `(t, x, y, z)` or spherical `(t, r, theta, phi)` coordinates,
//! with named parameters. Components not written are 0; `g_ab` and `g_ba` name one component and
//! may not both be given. Expression errors point at the column inside the string.

use crate::reader::{num, Node, Result, Table};
use spacetime::metric::expression::{is_name, is_reserved, Expression, Names};
use spacetime::metric::{Coordinates, UserMetric, WrittenMetric};
use spacetime::Spacetime;

/// Every key a metric table takes: its settings and each `g_ab` of either chart, both orders.
pub(super) const KEYS: &[&str] = &[
    "coordinates",
    "parameters",
    "horizon",
    "scale",
    "axis",
    "g_tt",
    "g_tx",
    "g_ty",
    "g_tz",
    "g_xt",
    "g_xx",
    "g_xy",
    "g_xz",
    "g_yt",
    "g_yx",
    "g_yy",
    "g_yz",
    "g_zt",
    "g_zx",
    "g_zy",
    "g_zz",
    "g_tr",
    "g_ttheta",
    "g_tphi",
    "g_rt",
    "g_rr",
    "g_rtheta",
    "g_rphi",
    "g_thetat",
    "g_thetar",
    "g_thetatheta",
    "g_thetaphi",
    "g_phit",
    "g_phir",
    "g_phitheta",
    "g_phiphi",
];

/// Reads the metric table: coordinates (default Cartesian), parameters, components, optional
/// `horizon` (captured where ≤ 0) and `scale` (the curvature length, default 1).
pub(super) fn metric(t: &Table<'_>) -> Result<Spacetime> {
    let coordinates = match t.get("coordinates") {
        Some(n) => {
            [Coordinates::Cartesian, Coordinates::Spherical][n.keyword("coordinates", &["cartesian", "spherical"])?]
        }
        None => Coordinates::Cartesian,
    };
    let params = parameters(t)?;
    let names = Names { variables: coordinates.names(), constants: &params };
    let components = components(t, coordinates, names)?;
    if components.is_empty() {
        return Err(t.err("a metric needs its components: g_tt, ... as expressions"));
    }
    let horizon = t.opt("horizon", |n| compile(n, names))?;
    let scale = t.or("scale", 1.0, |n| n.f64())?;
    let written = WrittenMetric::new(coordinates, components, horizon, scale);
    let at = if t.get("scale").is_some() { "scale" } else { "g_tt" };
    written.map(|m| Spacetime::Written(UserMetric(m))).map_err(|e| t.loc(at).err(e.message))
}

/// `parameters = { M = 1.0, ... }`: names that are not coordinates or functions, finite values.
fn parameters<'a>(t: &Table<'a>) -> Result<Vec<(&'a str, f64)>> {
    let Some(table) = t.get("parameters") else { return Ok(Vec::new()) };
    let mut out = Vec::new();
    for (name, n) in table.any_table()?.entries() {
        if !is_name(name)
            || is_reserved(name)
            || [Coordinates::Cartesian, Coordinates::Spherical].iter().any(|c| c.names().contains(&name))
        {
            return Err(n.err(format!("\"{name}\" cannot name a parameter (a coordinate, a function or not a name)")));
        }
        let v = n.f64()?;
        if !v.is_finite() {
            return Err(n.err(format!("must be finite, got {}", num(v))));
        }
        out.push((name, v));
    }
    Ok(out)
}

/// The written components `(a, b, g_ab)`; a component of the other chart is an error naming it.
fn components(t: &Table<'_>, coordinates: Coordinates, names: Names<'_>) -> Result<Vec<(usize, usize, Expression)>> {
    let other = match coordinates {
        Coordinates::Cartesian => Coordinates::Spherical,
        Coordinates::Spherical => Coordinates::Cartesian,
    };
    let (own, other) = (coordinates.names(), other.names());
    let key = |c: [&str; 4], a: usize, b: usize| format!("g_{}{}", c[a], c[b]);
    let pairs = || (0..4).flat_map(|a| (0..4).map(move |b| (a, b)));
    let mine: Vec<String> = pairs().map(|(a, b)| key(own, a, b)).collect();
    for foreign in pairs().map(|(a, b)| key(other, a, b)).filter(|k| !mine.contains(k)) {
        if let Some(n) = t.get(&foreign) {
            let chart = own[1..].join(", ");
            return Err(n.err(format!("{foreign} is not a component in these coordinates (t, {chart})")));
        }
    }
    let mut out = Vec::new();
    for (a, b) in pairs() {
        let Some(n) = t.get(&key(own, a, b)) else { continue };
        if b < a && t.get(&key(own, b, a)).is_some() {
            return Err(n.err(format!("same component as {}; give only one of them", key(own, b, a))));
        }
        out.push((a, b, compile(&n, names)?));
    }
    Ok(out)
}

/// One expression, its errors at their column.
fn compile(n: &Node<'_>, names: Names<'_>) -> Result<Expression> {
    Expression::compile(n.str()?, names).map_err(|e| n.err_within(e.at, e.message))
}
