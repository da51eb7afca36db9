//! A counting global allocator, to check that a run of your own system is
//! allocation-free as [`run`](crate::run) is: declare it as the test
//! binary's allocator and compare [`allocations`] before and after.
//!
//! ```ignore
//! #[global_allocator]
//! static ALLOC: hybrid_ode::counting::CountingAlloc = hybrid_ode::counting::CountingAlloc;
//!
//! let before = hybrid_ode::counting::allocations();
//! hybrid_ode::run(&mut system, &mut observer, 0.0, &mut y, 10.0, &opts);
//! assert_eq!(hybrid_ode::counting::allocations(), before);
//! ```
//!
//! Counts are per thread, so that tests running in parallel do not see each
//! other's allocations.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The system allocator, counting allocations and reallocations per thread.
pub struct CountingAlloc;

thread_local! {
    static ALLOCS: Cell<u64> = const { Cell::new(0) };
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for CountingAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Allocations (and reallocations) made on this thread so far, when
/// [`CountingAlloc`] is the global allocator (0 otherwise).
pub fn allocations() -> u64 {
    ALLOCS.with(|c| c.get())
}
