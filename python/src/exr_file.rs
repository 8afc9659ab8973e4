//! `nullpath.read_exr`: an OpenEXR image's channels as NumPy arrays, read by the `exr` crate
//! that writes nullpath's images.

use exr::prelude::{read_all_flat_layers_from_file, FlatSamples};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Reads the OpenEXR image at `path` (its first layer): returns `(image, channels)`, the image
/// float32 height × width × 3 from its R, G and B channels (None if it has not all three) and
/// every other channel by name, height × width (float32, or uint32 for integer channels). An
/// image `nullpath render -o x.exr` wrote gives back exactly the pixels `Scene.render` returns.
#[pyfunction]
pub fn read_exr(py: Python<'_>, path: PathBuf) -> PyResult<(Option<Py<PyAny>>, Py<PyDict>)> {
    let image = read_all_flat_layers_from_file(&path)
        .map_err(|e| PyValueError::new_err(format!("{}: cannot read OpenEXR: {e}", path.display())))?;
    let Some(layer) = image.layer_data.first() else {
        return Err(PyValueError::new_err(format!("{}: the OpenEXR image has no layer", path.display())));
    };
    let (width, height) = (layer.size.width(), layer.size.height());
    let mut colour: [Option<Vec<f32>>; 3] = [None, None, None];
    let channels = PyDict::new(py);
    for channel in &layer.channel_data.list {
        let name = channel.name.to_string();
        let rgb = ["R", "G", "B"].iter().position(|&c| c == name);
        match (&channel.sample_data, rgb) {
            (FlatSamples::U32(samples), _) => {
                channels.set_item(name, PyArray1::from_slice(py, samples).reshape([height, width])?)?;
            }
            (samples, Some(c)) => colour[c] = Some(floats(samples)),
            (samples, None) => {
                channels.set_item(name, PyArray1::from_vec(py, floats(samples)).reshape([height, width])?)?;
            }
        }
    }
    let image = match colour {
        [Some(r), Some(g), Some(b)] => {
            let interleaved: Vec<f32> = (0..r.len()).flat_map(|i| [r[i], g[i], b[i]]).collect();
            Some(PyArray1::from_vec(py, interleaved).reshape([height, width, 3])?.into_any().unbind())
        }
        _ => None,
    };
    Ok((image, channels.unbind()))
}

/// A channel's samples as `f32` (exact for half and single floats).
fn floats(samples: &FlatSamples) -> Vec<f32> {
    match samples {
        FlatSamples::F16(values) => values.iter().map(|v| v.to_f32()).collect(),
        FlatSamples::F32(values) => values.clone(),
        FlatSamples::U32(values) => values.iter().map(|&v| v as f32).collect(),
    }
}
