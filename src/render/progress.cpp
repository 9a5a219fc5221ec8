// render: the progress line on stderr (progress.h).
#include "render/progress.h"

#include <unistd.h>

#include <cstdio>

namespace raylane {

void Progress::step() {
    if (!enabled || total == 0) return;  // no atomic per tile when nothing is shown
    const size_t n = done.fetch_add(1) + 1;
    const int percent = static_cast<int>(100 * n / total);
    int old = shown.load();
    if (percent > old && shown.compare_exchange_strong(old, percent)) {
        const double spent =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        // the pace of the first percent says little (a frame's first tiles are often sky)
        if (percent < 2) {
            std::fprintf(stderr, "\r\033[K%s: %3d%%, %.1f s", label, percent, spent);
        } else {
            const double left = spent / double(n) * double(total - n);
            std::fprintf(stderr, "\r\033[K%s: %3d%%, %.1f s, ~%.1f s left", label, percent, spent,
                         left);
        }
    }
}

void Progress::finish() {
    if (!enabled || shown.load() < 0) return;
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "\r\033[K%s: done in %.1f s\n", label, spent);
}

bool stderr_is_terminal() { return isatty(2) != 0; }

}  // namespace raylane
