// Every benchmark program runs with the heap raylane's main sets up (core/pages.h,
// keep_freed_memory), before its first benchmark.
#include "core/pages.h"

namespace {

const bool heap_kept = (raylane::keep_freed_memory(), true);

}  // namespace
