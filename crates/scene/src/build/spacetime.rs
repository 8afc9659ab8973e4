//! `[spacetime]` and a view's `[views.NAME.spacetime]`: the metric's `type` looked up in a
//! registry of [`MetricDescriptor`]s (the physics crate's [`SPACETIMES`] unless a caller gives
//! another), each parameter key read as its descriptor says (required, or its default), and the
//! whole checked by the descriptor's constructor, whose [`ParameterError`] names the key at fault.
//! `type = "metric"`, a metric written in the file, is this crate's own ([`super::metric`]).
//!
//! [`SPACETIMES`]: spacetime::metric::SPACETIMES

use super::metric;
use crate::reader::{Node, Result, Table};
use render::geometry::Vec3;
use spacetime::metric::{parameters_of, MetricDescriptor, ParameterError, WRITTEN_NAME};
use spacetime::Spacetime;

/// The spacetime of a scene file: the metric, its symmetry axis in the world (a spinning hole's
/// spin axis; default `+y`, up) and the descriptor it was read by (`None` for a written metric),
/// which a view's `spacetime` table sets parameters by.
pub(super) struct FileSpacetime<'r> {
    pub spacetime: Spacetime,
    pub axis: Vec3,
    pub descriptor: Option<&'r MetricDescriptor>,
}

impl FileSpacetime<'static> {
    /// Flat space, for a file without `[spacetime]`.
    pub fn flat() -> Self {
        let spacetime = Spacetime::Minkowski(spacetime::Minkowski);
        FileSpacetime { descriptor: spacetime.descriptor(), spacetime, axis: Vec3::Y }
    }
}

/// The keys a descriptor's table takes besides `type`: its parameters, and `axis` when the metric
/// has one.
fn keys(d: &MetricDescriptor) -> Vec<&'static str> {
    let mut keys: Vec<&'static str> = d.parameters.iter().map(|p| p.name).collect();
    if d.oriented {
        keys.push("axis");
    }
    keys
}

/// `[spacetime]` (the node `n`), its `type` one of `spacetimes` or `"metric"`.
pub(super) fn section<'r>(n: &Node<'_>, spacetimes: &[&'r MetricDescriptor]) -> Result<FileSpacetime<'r>> {
    let keys: Vec<Vec<&'static str>> = spacetimes.iter().map(|d| keys(d)).collect();
    let mut tags: Vec<(&'static str, &[&'static str])> =
        spacetimes.iter().zip(&keys).map(|(d, k)| (d.name, k.as_slice())).collect();
    tags.push((WRITTEN_NAME, metric::KEYS));
    let (kind, t) = n.tagged("spacetime", &tags)?;
    // Only the types that have an axis read one (the others reject the key as unknown).
    let axis = if tags[kind].1.contains(&"axis") { t.or("axis", Vec3::Y, |n| n.direction())? } else { Vec3::Y };
    let Some(&d) = spacetimes.get(kind) else {
        return Ok(FileSpacetime { spacetime: metric::metric(&t)?, axis, descriptor: None });
    };
    let mut values = Vec::with_capacity(d.parameters.len());
    for p in d.parameters {
        values.push(match p.default {
            Some(default) => t.or(p.name, default, |n| n.f64())?,
            None => t.req(p.name, |n| n.f64())?,
        });
    }
    let spacetime = (d.build)(&values).map_err(|e| at_key(&t, d, e))?;
    Ok(FileSpacetime { spacetime, axis, descriptor: Some(d) })
}

/// A constructor's error at the key it names (the table itself when it names none of `d`'s).
fn at_key(t: &Table<'_>, d: &MetricDescriptor, e: ParameterError) -> crate::SceneError {
    if d.parameters.iter().any(|p| p.name == e.parameter) {
        t.loc(e.parameter).err(e.message)
    } else {
        t.err(e.to_string())
    }
}

/// The spacetime the camera table `t` sees: `file`'s, with the parameters a view's `spacetime`
/// table sets anew, each within the range [`MetricDescriptor::sliders`] offers (the preview's
/// sliders': up to three times the file's length scale) and the whole checked by the
/// descriptor's constructor as `[spacetime]` is.
pub(super) fn view_spacetime(t: &Table<'_>, file: &FileSpacetime<'_>) -> Result<Spacetime> {
    // `[camera]` takes no `spacetime` table: `[spacetime]` is its.
    let Some(n) = t.allows("spacetime").then(|| t.get("spacetime")).flatten() else {
        return Ok(file.spacetime.clone());
    };
    let names: Vec<&'static str> =
        file.descriptor.map(|d| d.parameters.iter().map(|p| p.name).collect()).unwrap_or_default();
    let table = n.table(&names)?;
    let values = table.entries().into_iter().map(|(k, v)| Ok((k, v.f64()?))).collect::<Result<Vec<_>>>()?;
    match file.descriptor {
        Some(d) => d.with_parameters(&file.spacetime, &values).map_err(|e| at_key(&table, d, e)),
        // A written metric has no parameters to set: the table, empty, changes nothing.
        None => Ok(file.spacetime.clone()),
    }
}

/// The table of spacetime types and their parameters in `docs/scene-format.md`, made from
/// `spacetimes` (and the written metric, which is this crate's): Markdown, one line per row.
pub fn spacetime_table(spacetimes: &[&MetricDescriptor]) -> String {
    let cell = |s: &str| s.replace('|', "\\|");
    let mut out = String::from("| `type` | parameters | constraint | meaning |\n|---|---|---|---|\n");
    for d in spacetimes {
        let mut parameters: Vec<String> = d
            .parameters
            .iter()
            .map(|p| {
                let default = p.default.map_or(String::new(), |v| format!(" (default {v})"));
                format!("`{}` {}{default}", p.name, p.range.describe())
            })
            .collect();
        if d.oriented {
            parameters.push("`axis` (default `[0, 1, 0]`)".to_string());
        }
        let parameters = if parameters.is_empty() { "—".to_string() } else { parameters.join(", ") };
        let constraint = d.constraint.map_or("—".to_string(), cell);
        out += &format!("| `\"{}\"` | {} | {constraint} | {} |\n", d.name, cell(&parameters), cell(d.description));
    }
    out += &format!(
        "| `\"{WRITTEN_NAME}\"` | components `g_ab` as expressions (below) | — | a metric written in the file |\n"
    );
    out += "\nA parameter without a default is required. The parameters:\n\n";
    out += "| parameter | unit | meaning | of |\n|---|---|---|---|\n";
    for (p, of) in parameters_of(spacetimes) {
        let of: Vec<String> = of.iter().map(|d| format!("`\"{}\"`", d.name)).collect();
        out += &format!("| `{}` | {} | {} | {} |\n", p.name, p.unit, cell(p.meaning), of.join(", "));
    }
    let oriented = spacetimes.iter().filter(|d| d.oriented).map(|d| d.name).chain([WRITTEN_NAME]);
    let oriented: Vec<String> = oriented.map(|name| format!("`\"{name}\"`")).collect();
    out += &format!(
        "| `axis` | direction | the chart's z axis (a hole's spin axis) in the world | {} |\n",
        oriented.join(", ")
    );
    out
}
