#pragma once
// When a loop is worth a parallel region.

#include <cstddef>

namespace scour {

/// The element count from which a loop of light work (a few nanoseconds an element: a copy, a
/// clamp, a check of marks) takes a parallel region; below it the loop runs on the calling
/// thread. Opening a region wakes the other threads, and under OMP_WAIT_POLICY=passive (they
/// sleep between regions) that costs about 50 µs on a 2-core machine (docs/performance.md, "the
/// price of a parallel region"): more than such a loop's whole work below this size. Each loop
/// that uses it gives the same bits at any thread count, so the choice changes no result.
constexpr size_t kParallelFrom = 32768;

}  // namespace scour
