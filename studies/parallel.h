// The one parallel loop of the batch-of-runs layers: sweeps, optimisations and identifications run their model runs
// through it, with the thread cap of the command line or the study file.
#pragma once

#include <cstddef>
#include <functional>

namespace turbodyn::studies {

/// Threads for a batch: the command line's `requested` if > 0, else the study file's `configured` if > 0, else all
/// cores.
int run_threads(int requested, int configured);

/// Calls body(i) for every i in [0, n), in parallel on at most `threads` threads; 0 leaves the cap to the enclosing
/// loop (all cores at the top level), so a loop inside a body shares the outer loop's threads instead of adding its
/// own. Results do not depend on the thread count as long as body(i) writes only what belongs to i. Returns when all
/// calls have returned; an exception thrown by a body is rethrown here.
void parallel_runs(std::size_t n, int threads, const std::function<void(std::size_t)>& body);

}  // namespace turbodyn::studies
