#pragma once

#include <functional>

namespace semchain::mapping {

// Runs body(i) for i in [0, count) on up to 'threads' threads (the calling thread included),
// handing out indices one at a time. 'threads' <= 1 runs everything in order on the caller.
// body must not throw.
void ParallelFor(int count, int threads, const std::function<void(int)>& body);

// The number of threads to use for 'requested' (0 = one per hardware core).
int ResolveThreadCount(int requested);

}  // namespace semchain::mapping
