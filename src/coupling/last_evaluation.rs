//! A value kept with the time and state it was formed at, for the next reading of the same
//! state: the riders' contacts and inertia, asked for again by the stages, the events and the
//! observers at the states a step has met.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;

/// Values kept with the time and state (t, y) each was formed at: the last one, or the last
/// few where observers come back to times the steps met.
pub(crate) struct LastEvaluation<T> {
    kept: RefCell<VecDeque<Evaluated<T>>>,
    capacity: usize,
}

/// A value with the time and state it was formed at.
type Evaluated<T> = (f64, Vec<f64>, Rc<T>);

impl<T> LastEvaluation<T> {
    pub(crate) fn new() -> Self {
        Self::keeping(1)
    }

    /// Keeping the last `capacity` values.
    pub(crate) fn keeping(capacity: usize) -> Self {
        LastEvaluation {
            kept: RefCell::new(VecDeque::with_capacity(capacity)),
            capacity: capacity.max(1),
        }
    }

    /// The value at (t, the parts of y in order), formed by `form` unless it is one kept.
    pub(crate) fn at(&self, t: f64, y: &[&[f64]], form: impl FnOnce() -> T) -> Rc<T> {
        let mut kept = self.kept.borrow_mut();
        let same = |k: &[f64]| {
            k.len() == y.iter().map(|p| p.len()).sum::<usize>()
                && y.iter().flat_map(|p| p.iter()).zip(k).all(|(a, b)| a == b)
        };
        if let Some((_, _, v)) = kept.iter().rev().find(|(kt, k, _)| *kt == t && same(k)) {
            return v.clone();
        }
        let v = Rc::new(form());
        if kept.len() == self.capacity {
            kept.pop_front();
        }
        kept.push_back((t, y.concat(), v.clone()));
        v
    }

    /// Forget the values kept: what they depend on beside (t, y) has changed.
    pub(crate) fn forget(&self) {
        self.kept.borrow_mut().clear();
    }
}
