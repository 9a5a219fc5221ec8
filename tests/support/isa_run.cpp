// Test support: `isa_run SET PROGRAM ARGS...` runs a test program compiled for one instruction
// set when this CPU runs the set, and otherwise says so and exits with 77, which ctest reports
// as a skipped test. The program cannot check for itself: its static initialisers, compiled for
// the set, run before main.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "core/isa.h"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: isa_run SET PROGRAM [ARGS...]\n");
        return 2;
    }
    const std::string_view set = argv[1];
    for (raylane::Isa isa : raylane::all_isas) {
        if (set != raylane::isa_name(isa)) continue;
        if (!raylane::cpu_runs(isa)) {
            std::printf("skipped: this CPU does not run %s (it runs: %s)\n", argv[1],
                        raylane::runnable_isa_names().c_str());
            return 77;
        }
        ::execv(argv[2], argv + 2);
        std::fprintf(stderr, "isa_run: %s: %s\n", argv[2], std::strerror(errno));
        return 2;
    }
    std::fprintf(stderr, "isa_run: unknown instruction set '%s'\n", argv[1]);
    return 2;
}
