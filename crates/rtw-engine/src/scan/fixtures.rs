//! What the scan's unit tests share: a small scan and the fake simulator.

use crate::fake;
use rtw_model::{Options, Outcome, Params};
use std::time::Duration;

/// A small scan: 37 samples over ρ, α, f_n and φ, short runs.
pub(crate) const CFG: &str = r#"
seed = 11
samples = 37
[params]
length = 0.8
rho = { uniform = [1, 5] }
alpha = { uniform = [0, 0.4] }
fn = { uniform = [1.5, 5] }
zeta = 0.05
phi = { uniform = [0.05, 0.3] }
[simulation]
t_max = 2.0
"#;

/// The fake simulator, without delay.
pub(crate) fn fake_sim(p: &Params, o: &Options) -> Outcome {
    fake::simulate(p, o, Duration::ZERO)
}
