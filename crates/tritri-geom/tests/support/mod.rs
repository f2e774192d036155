//! Helpers shared by the integration tests: running a check over many pairs
//! on every core, and collecting disagreements for the report.

#![allow(dead_code)]

use std::sync::Mutex;
use std::time::Instant;

/// Runs `check` on every item, split over the available cores; returns the
/// indices where it returned false (sorted) and how long it took.
pub fn failures<T: Sync>(items: &[T], check: impl Fn(&T) -> bool + Sync) -> Vec<usize> {
    let threads = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .max(1);
    let chunk = items.len().div_ceil(threads).max(1);
    let found = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for (c, part) in items.chunks(chunk).enumerate() {
            let (found, check) = (&found, &check);
            scope.spawn(move || {
                let bad: Vec<usize> = part
                    .iter()
                    .enumerate()
                    .filter(|(_, item)| !check(item))
                    .map(|(i, _)| c * chunk + i)
                    .collect();
                found.lock().unwrap().extend(bad);
            });
        }
    });
    let mut found = found.into_inner().unwrap();
    found.sort_unstable();
    found
}

/// Counts items satisfying `predicate`, in parallel.
pub fn count<T: Sync>(items: &[T], predicate: impl Fn(&T) -> bool + Sync) -> usize {
    items.len() - failures(items, predicate).len()
}

/// A stopwatch for the summaries.
pub struct Timer(Instant);

impl Timer {
    pub fn start() -> Self {
        Timer(Instant::now())
    }
    pub fn seconds(&self) -> f64 {
        self.0.elapsed().as_secs_f64()
    }
}
