//! How a branch's end is named from the orbits on its two sides
//! ([`super::locate_end`]): a closest approach or an event's slope that shrank
//! to zero (grazing), a new event that appears with no slope (grazing), two
//! events that coincide (corner).

use super::{Approach, Orbit};
use crate::plant::rtw::GuardKind;

/// Among `near`'s closest approaches and events, the one that shrank most
/// from `far` (the same occurrence of the same guard in the same step),
/// below `ratio`.
pub(super) fn shrunk(near: &Orbit, far: &Orbit, ratio: f64) -> Option<Approach> {
    let same = |x: &Approach, y: &Approach| {
        x.step == y.step && x.kind == y.kind && x.at_boundary == y.at_boundary
    };
    let shrink = |a: &[Approach], b: &[Approach]| {
        a.iter()
            .enumerate()
            .filter_map(|(i, x)| {
                let k = a[..i].iter().filter(|y| same(x, y)).count();
                let y = b.iter().filter(|y| same(x, y)).nth(k)?;
                let r = x.value.abs() / y.value.abs();
                (r.is_finite() && r < ratio).then_some((r, *x))
            })
            .collect::<Vec<_>>()
    };
    shrink(&near.approaches, &far.approaches)
        .into_iter()
        .chain(shrink(&near.events, &far.events))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, a)| a)
}

/// An event of `new` that `old` does not have (beyond the occurrences of
/// its guard in its step there) and that fires with almost no slope: below
/// `ratio` of the steepest event of the same guard on the old side (a tip
/// that bounces off the ground by a vanishing height and lands again).
pub(super) fn appearing(old: &Orbit, new: &Orbit, ratio: f64) -> Option<Approach> {
    new.events
        .iter()
        .enumerate()
        .filter(|(i, x)| {
            let same = |y: &&Approach| y.step == x.step && y.kind == x.kind;
            let k = new.events[..*i].iter().filter(same).count();
            old.events.iter().filter(same).nth(k).is_none()
        })
        .filter_map(|(_, x)| {
            let steepest = old
                .events
                .iter()
                .filter(|y| y.kind == x.kind)
                .map(|y| y.value.abs())
                .fold(0.0, f64::max);
            let r = x.value.abs() / steepest;
            (r.is_finite() && r < ratio).then_some((r, *x))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, a)| a)
}

/// Two events of `o` nearest in time, if within `dt`: two in one step, or
/// the touchdown that ends a step (the section) and an event right at the
/// start of the next (a landing tip that re-sticks as it lands).
pub(super) fn corner(o: &Orbit, dt: f64) -> Option<(GuardKind, GuardKind, f64)> {
    corner_of(&o.events, o.sequence.section_modes.len(), dt)
}

/// [`corner`] of an orbit of `steps` steps with events `events`.
fn corner_of(events: &[Approach], steps: usize, dt: f64) -> Option<(GuardKind, GuardKind, f64)> {
    let within = events
        .windows(2)
        .filter(|w| w[0].step == w[1].step)
        .map(|w| (w[0].kind, w[1].kind, w[1].t - w[0].t));
    // Each step's first event, with the last event of the step before (the
    // orbit is periodic: step 0 follows the last step).
    let across = (0..steps).filter_map(|k| {
        let first = events.iter().find(|e| e.step == k)?;
        let before = (k + steps - 1) % steps;
        let last = events.iter().rev().find(|e| e.step == before)?;
        Some((last.kind, first.kind, first.t))
    });
    within
        .chain(across)
        .filter(|x| x.2.abs() <= dt)
        .min_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Tip;

    fn event(step: usize, kind: GuardKind, t: f64) -> Approach {
        Approach {
            step,
            kind,
            t,
            value: -1.0,
            at_boundary: false,
        }
    }

    /// A period-2 walk at L = 0.9 whose landing tip re-sticks 3.3e-8 s
    /// after the touchdown that ends step 0 (`rtw-scan continuation
    /// --length 0.9 --through`, φ ≈ 0.22319): the two events lie in
    /// different steps, yet they coincide — a corner.
    #[test]
    fn a_re_stick_right_after_the_sections_touchdown_is_a_corner() {
        let td = GuardKind::Touchdown {
            rod: 1,
            tip: Tip::Plus,
        };
        let stick = GuardKind::Restick { rod: 0 };
        let events = [
            event(0, GuardKind::Slip { rod: 2 }, 0.0583),
            event(0, GuardKind::LiftOff { rod: 2 }, 0.1051),
            event(0, td, 0.1965),
            event(1, stick, 3.3e-8),
            event(1, GuardKind::Slip { rod: 0 }, 0.0802),
            event(1, td, 0.2528),
        ];
        assert_eq!(corner_of(&events, 2, 1e-5), Some((td, stick, 3.3e-8)));
        // Apart by more than the tolerance: no corner.
        let mut later = events;
        later[3].t = 2e-5;
        assert_eq!(corner_of(&later, 2, 1e-5), None);
        // Step 0's first event pairs with the last step's touchdown.
        let mut first = later;
        first[0].t = 4e-8;
        assert_eq!(
            corner_of(&first, 2, 1e-5),
            Some((td, GuardKind::Slip { rod: 2 }, 4e-8))
        );
    }
}
