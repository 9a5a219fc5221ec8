// core: how many worker threads a render or a batch of ray queries runs on.
#include "core/threads.h"

#include <tbb/info.h>

#include <algorithm>

namespace raylane {

int worker_threads(int requested) {
    return requested > 0 ? std::min(requested, tbb::info::default_concurrency()) : requested;
}

}  // namespace raylane
