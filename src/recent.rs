//! What was computed last, kept under its key's text: planning a scene and running it ask for the
//! same assembled beam, eigensolution and modal basis several times, and a sweep's cases share
//! them. A key is the text of what the value is computed from (its `Debug` form, whose floats
//! round-trip), so two asks share a value only if they ask the same.

use std::sync::Mutex;

/// At most `capacity` values, the one asked for longest ago dropped first.
#[derive(Debug)]
pub struct Recent<T> {
    capacity: usize,
    entries: Vec<(String, T)>,
}

impl<T: Clone> Recent<T> {
    pub const fn new(capacity: usize) -> Self {
        Recent {
            capacity,
            entries: Vec::new(),
        }
    }

    pub fn get(&self, key: &str) -> Option<T> {
        self.entries
            .iter()
            .find(|(at, _)| at == key)
            .map(|(_, value)| value.clone())
    }

    pub fn keep(&mut self, key: String, value: T) {
        if self.capacity == 0 {
            return;
        }
        if self.entries.len() == self.capacity {
            self.entries.remove(0);
        }
        self.entries.push((key, value));
    }
}

/// [`Recent`] shared by every thread of the process. A lock poisoned by a panicking thread
/// keeps nothing more and finds nothing: the value is then computed again.
#[derive(Debug)]
pub struct SharedRecent<T>(Mutex<Recent<T>>);

impl<T: Clone> SharedRecent<T> {
    pub const fn new(capacity: usize) -> Self {
        SharedRecent(Mutex::new(Recent::new(capacity)))
    }

    pub fn get(&self, key: &str) -> Option<T> {
        self.0.lock().ok().and_then(|kept| kept.get(key))
    }

    pub fn keep(&self, key: String, value: T) {
        if let Ok(mut kept) = self.0.lock() {
            kept.keep(key, value);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The capacity bounds what is kept, and the oldest goes first.
    #[test]
    fn the_oldest_value_goes_first() {
        let mut r = Recent::new(2);
        r.keep("a".into(), 1);
        r.keep("b".into(), 2);
        r.keep("c".into(), 3);
        assert_eq!(
            (r.get("a"), r.get("b"), r.get("c")),
            (None, Some(2), Some(3))
        );
        let mut none = Recent::new(0);
        none.keep("a".into(), 1);
        assert_eq!(none.get("a"), None);
    }
}
