//! The star's geometry for drawings (rtw.draw, the animation, the HTML
//! report): every spoke's tip and connection point, and which spokes the
//! strings join, from rtw-model's own definitions, so Python draws the robot
//! without re-deriving it.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyModule;
use rtw_model::{SPOKES, STRINGS, Tip, spoke_points};

/// Tips and connection points of every spoke (a+, b+, c+, a−, b−, c−) at
/// each frame: `x`, `y`, `theta` are the rods' centres and angles in the
/// slope frame, flat in [frame, rod] order (3 values a frame); returns
/// (tips, connection points), each flat in [frame, spoke, xy] order.
#[pyfunction]
fn star_points(
    x: Vec<f64>,
    y: Vec<f64>,
    theta: Vec<f64>,
    length: f64,
    r: f64,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    if x.len() != y.len() || x.len() != theta.len() || !x.len().is_multiple_of(3) {
        return Err(PyValueError::new_err(format!(
            "x, y, theta: {}, {} and {} values are invalid: must be as many, 3 a frame (rods a, b, c)",
            x.len(),
            y.len(),
            theta.len()
        )));
    }
    let frames = x.len() / 3;
    let (mut tips, mut conns) = (
        Vec::with_capacity(12 * frames),
        Vec::with_capacity(12 * frames),
    );
    for f in 0..frames {
        let rods = std::array::from_fn(|i| ([x[3 * f + i], y[3 * f + i]], theta[3 * f + i]));
        let (t, c) = spoke_points(&rods, length, r);
        tips.extend(t.iter().flatten());
        conns.extend(c.iter().flatten());
    }
    Ok((tips, conns))
}

/// Adds `star_points`, `SPOKES` ((rod, ±1) of each spoke) and `STRINGS`
/// (the pair of spokes each string joins) to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(star_points, m)?)?;
    let spokes: Vec<(usize, i32)> = SPOKES
        .iter()
        .map(|&(i, tip)| (i, if tip == Tip::Plus { 1 } else { -1 }))
        .collect();
    m.add("SPOKES", spokes)?;
    m.add("STRINGS", STRINGS.to_vec())?;
    Ok(())
}
