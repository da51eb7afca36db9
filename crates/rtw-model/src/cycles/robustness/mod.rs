//! A gait pushed off its cycle: its sensitivity to the floor's height (the
//! gait sensitivity norm) and a slice of its basin of attraction.

pub(crate) mod basin;
pub(crate) mod gsn;
