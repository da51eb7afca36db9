//! Following a gait as a parameter moves: the step map as a family, the
//! places where a branch's contact-mode sequence changes, and the branch
//! continued segment by segment through those changes.

pub(crate) mod continuation;
pub(crate) mod nonsmooth;
pub(crate) mod segments;
