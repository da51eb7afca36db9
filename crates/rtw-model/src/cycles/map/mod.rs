//! The step map: a touchdown on the section to the next one, its Jacobian,
//! and its fixed points with their Floquet multipliers.

pub(crate) mod limit_cycle;
pub(crate) mod section;
pub(crate) mod stepmap;
