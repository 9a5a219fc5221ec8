// app: helpers the commands share.
#include <chrono>

#include "app/commands.h"
#include "io/load_scene.h"

namespace raylane {

Scene load_scene_or_builtin(const std::string& path) {
    return path.empty() ? make_builtin_scene() : load_scene(path);
}

double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

double elapsed_ms(double start_seconds) { return 1000.0 * (now_seconds() - start_seconds); }

}  // namespace raylane
