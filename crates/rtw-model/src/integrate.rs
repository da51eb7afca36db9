//! Runge–Kutta integrators with dense output.

/// Integration method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Dormand–Prince 5(4), adaptive, 4th-order dense output.
    Dp54,
    /// Dormand–Prince 8(5,3), adaptive, 7th-order dense output.
    Dop853,
    /// Classic RK4 with a fixed step `h` (cubic Hermite dense output).
    Rk4 { h: f64 },
}

/// Dense output of one step on `[t0, t1]`.
#[derive(Clone, Copy, Debug)]
pub struct Dense<const N: usize> {
    pub t0: f64,
    pub t1: f64,
    pub y0: [f64; N],
    pub y1: [f64; N],
}

impl<const N: usize> Dense<N> {
    /// The interpolated state at `t ∈ [t0, t1]`.
    pub fn eval(&self, t: f64, out: &mut [f64; N]) {
        let _ = (t, out);
        todo!()
    }
}
