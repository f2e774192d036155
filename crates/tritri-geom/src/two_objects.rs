//! The host's work on a scene's two objects, one thread each when that
//! pays: culling, quantizing and packing one object never reads the
//! other's triangles, and the machines the project runs on have two cores
//! or more (the software baseline gives a two-thread figure as well).

use std::sync::OnceLock;

/// Below this many triangles in both objects together the two objects are
/// done one after the other on the calling thread: spawning a thread costs
/// tens of microseconds, as much as preparing a few thousand triangles.
pub const THREADED_FROM: usize = 16_384;

/// The threads [`on_both`] uses for a scene of `triangles` (both objects
/// together): 1 or 2.
pub fn threads(triangles: usize) -> usize {
    // The scene's size first, and the cores asked once per process:
    // `available_parallelism` reads the cgroup files on Linux, about 30 us
    // a call, which a small scene's whole preparation would pay again at
    // every call.
    static CORES: OnceLock<usize> = OnceLock::new();
    if triangles < THREADED_FROM
        || *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get())) < 2
    {
        1
    } else {
        2
    }
}

/// `(for_a(), for_b())`, on two threads when `triangles` (both objects'
/// together) reaches [`THREADED_FROM`] and the machine has two cores, else
/// in order on this one. The results are the same either way; only the
/// time differs.
pub fn on_both<A: Send, B: Send>(
    triangles: usize,
    for_a: impl FnOnce() -> A + Send,
    for_b: impl FnOnce() -> B + Send,
) -> (A, B) {
    if threads(triangles) == 1 {
        return (for_a(), for_b());
    }
    std::thread::scope(|scope| {
        let a = scope.spawn(for_a);
        let b = for_b();
        // A panic in `for_a` is a bug; it reaches the caller as one.
        let a = a.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
        (a, b)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_results_come_back_in_their_places_on_one_thread_or_two() {
        for triangles in [0, THREADED_FROM - 1, THREADED_FROM, 10 * THREADED_FROM] {
            let (a, b) = on_both(triangles, || vec![1u32; 3], || "b".to_string());
            assert_eq!((a, b.as_str()), (vec![1, 1, 1], "b"), "{triangles}");
        }
    }

    #[test]
    #[should_panic(expected = "a's bug")]
    fn a_panic_on_the_second_thread_reaches_the_caller() {
        on_both(THREADED_FROM, || panic!("a's bug"), || 0);
    }
}
