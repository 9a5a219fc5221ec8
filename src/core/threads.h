// core: how many worker threads a render or a batch of ray queries runs on.
#pragma once

namespace raylane {

/// The threads to run on for a request of `requested`: at most as many as this machine runs at
/// once (oneTBB would ignore more, and say so in two lines on stderr); 0 stays 0 (all).
int worker_threads(int requested);

}  // namespace raylane
