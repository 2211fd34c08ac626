//! A counting global allocator for the allocation-free tests: each thread counts its own
//! allocations (the test harness runs tests on several threads). It is a module of each
//! test binary (`tests/suite.rs`, `tests/machines.rs`), which installs it as its one global
//! allocator; a test module reads it with `use crate::counting;`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

thread_local! {
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

/// The system allocator, counting this thread's allocations and reallocations.
pub struct Counting;

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        System.alloc(l)
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        System.dealloc(p, l)
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        System.realloc(p, l, n)
    }
}

/// Allocations made by this thread so far.
pub fn count() -> usize {
    COUNT.with(|c| c.get())
}

#[cfg(test)]
mod tests {
    use super::count;
    use std::hint::black_box;
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    use std::sync::Arc;

    /// The allocator is installed: an allocation is counted (a missing `#[global_allocator]`
    /// would make every "allocates nothing" test pass for nothing).
    #[test]
    fn an_allocation_of_this_thread_is_counted() {
        let before = count();
        let v = black_box(vec![1u8; 100]);
        let after = count();
        drop(v);
        assert!(after > before, "{before} -> {after}");
    }

    /// Another thread allocating meanwhile (another test, the harness) does not change this
    /// thread's count.
    #[test]
    fn the_allocations_of_another_thread_are_not_counted() {
        let (done, stop) = (
            Arc::new(AtomicUsize::new(0)),
            Arc::new(AtomicBool::new(false)),
        );
        let other = {
            let (done, stop) = (done.clone(), stop.clone());
            std::thread::spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    black_box(vec![0u64; 16]);
                    done.fetch_add(1, Ordering::SeqCst);
                }
            })
        };
        while done.load(Ordering::SeqCst) == 0 {
            std::hint::spin_loop();
        }
        let before = count();
        let start = done.load(Ordering::SeqCst);
        while done.load(Ordering::SeqCst) < start + 1000 {
            std::hint::spin_loop();
        }
        let after = count();
        stop.store(true, Ordering::SeqCst);
        other.join().unwrap();
        assert_eq!(
            after, before,
            "another thread's 1000 allocations were counted here"
        );
    }
}
