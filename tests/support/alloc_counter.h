// Heap-allocation counting for the tests that check hot paths allocate nothing (STYLE.md; Drake's LimitMalloc
// idea). An executable that links tests/support/alloc_counter.cpp has its global operator new replaced by a
// counting one, so keep those tests in their own executable (alloc_tests).
#pragma once

namespace turbodyn::testing {

/// Number of calls of the global operator new (and new[]) since the program started, from all threads.
long allocation_count();

}  // namespace turbodyn::testing
