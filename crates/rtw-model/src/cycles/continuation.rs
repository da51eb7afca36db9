//! The step map as a map with a parameter, for
//! [`hybrid_ode::continuation`]: the branch of a gait's limit cycle in any
//! input of docs/model.md §1, stable and unstable, and its bifurcations.
//!
//! A point of the branch is a fixed point of the step map's `n`-th power at
//! section points in one pattern of contact modes (the template's): where
//! the branch meets a change of pattern the map is not smooth and the
//! continuation stops there.

use crate::cycles::section::SectionPoint;
use crate::cycles::stepmap::{CycleOptions, Jacobian, StepMap};
use crate::{Options, Param, Params};
use hybrid_ode::continuation::{MapEval, ParamMap};

/// Relative step of the central differences in the parameter.
const PARAM_STEP: f64 = 1e-6;

/// `z ↦ Pⁿ(z)` of the step map at section points in `template`'s modes, as a
/// function of the input `param` (the other inputs, the model and the
/// map's integrator fixed).
#[derive(Clone, Debug)]
pub struct StepMapFamily {
    base: Params,
    options: Options,
    cycle: CycleOptions,
    param: Param,
    template: SectionPoint,
    n: usize,
}

impl StepMapFamily {
    /// The family through `base` in `param`, at section points in the modes
    /// of `template`, for the `n`-th power of the map.
    pub fn new(
        base: &Params,
        options: &Options,
        cycle: &CycleOptions,
        param: Param,
        template: SectionPoint,
        n: usize,
    ) -> Self {
        Self {
            base: *base,
            options: *options,
            cycle: *cycle,
            param,
            template,
            n,
        }
    }

    /// The step map at `value` of the parameter; `None` outside its range.
    fn map_at(&self, value: f64) -> Option<StepMap> {
        let mut p = self.base;
        self.param.set(&mut p, value);
        p.validate().ok()?;
        Some(StepMap::new(&p, &self.options, &self.cycle))
    }

    /// `Pⁿ(z)` at `value`, if its orbit ends in the template's modes.
    fn power(&self, value: f64, at: &SectionPoint) -> Option<Vec<f64>> {
        let steps = self.map_at(value)?.iterate(at, self.n).ok()?;
        let to = steps.last()?.to;
        (to.modes == self.template.modes).then(|| to.coords())
    }
}

impl ParamMap for StepMapFamily {
    /// `Pⁿ` and `∂Pⁿ/∂z` by the variational equations; `∂Pⁿ/∂p` by central
    /// differences of the map (two plain runs of `n` steps).
    fn eval(&mut self, z: &[f64], value: f64) -> Option<MapEval> {
        let at = self.template.with_coords(z);
        let (q, dz) =
            self.map_at(value)?
                .power_with_jacobian(&at, self.n, Jacobian::Variational)?;
        let h = PARAM_STEP * value.abs().max(1.0);
        let (plus, minus) = (self.power(value + h, &at)?, self.power(value - h, &at)?);
        Some(MapEval {
            value: q.coords(),
            dz,
            dp: plus
                .iter()
                .zip(&minus)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect(),
        })
    }
}
