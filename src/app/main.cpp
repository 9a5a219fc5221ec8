// app: the `raylane` command line (CLI11). Input errors print one line and exit with code 2;
// Ctrl-C (SIGINT) or SIGTERM stops the render at the next tile and exits with 130 (143) without
// writing any output (a second Ctrl-C kills at once).
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

#include "app/commands.h"
#include "core/error.h"
#include "core/isa.h"
#include "core/pages.h"
#include "distribute/render_job.h"
#include "render/tiles.h"

namespace {

volatile std::sig_atomic_t stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
    stop_signal = sig;
    raylane::request_cancel();
    std::signal(sig, SIG_DFL);  // the next one terminates
}

}  // namespace

int main(int argc, char** argv) {
    raylane::keep_freed_memory();
    CLI::App app{"Raylane: a data-oriented SIMD packet ray tracer"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "help for every command");
    int exit_code = 0;
    raylane::add_render_command(app, exit_code);
    raylane::add_info_command(app, exit_code);
    raylane::add_compare_command(app, exit_code);
    raylane::add_report_command(app, exit_code);
    raylane::add_scene_command(app, exit_code);
    raylane::add_assemble_command(app, exit_code);
    app.set_version_flag("--version", [] { return raylane::version_text(); });
    // --isa on every command; the set is chosen once the whole command line is read, before
    // the command runs
    std::string isa;
    for (CLI::App* cmd : app.get_subcommands({})) raylane::add_isa_option(cmd, isa);
    app.parse_complete_callback([&isa] {
        raylane::use_isa_named(isa, "--isa");
        raylane::active_isa();  // RAYLANE_ISA, checked before any work
    });
    // CLI11 answers an unknown command word with "A subcommand is required": name it instead
    if (argc > 1 && argv[1][0] != '-') {
        std::string names;
        bool known = false;
        for (const CLI::App* cmd : app.get_subcommands({})) {
            names += (names.empty() ? "" : ", ") + cmd->get_name();
            known = known || cmd->get_name() == argv[1];
        }
        if (!known) {
            std::fprintf(stderr,
                         "raylane: unknown command '%s' (commands: %s; see raylane --help)\n",
                         argv[1], names.c_str());
            return 2;
        }
    }
    // under an MPI launcher every process meets the same bad command line: one of them says so
    const bool quiet = raylane::launched_by_mpi() && raylane::rank_from_environment() != 0;
    // an unknown --option is named (with the nearest known one) before CLI11 reads the words
    // after it as the option's value or as the scene
    if (argc > 1 && argv[1][0] != '-') {
        const std::string unknown =
            raylane::unknown_option(*app.get_subcommand(argv[1]), argc, argv);
        if (!unknown.empty()) {
            if (!quiet) std::fprintf(stderr, "raylane: %s\n", unknown.c_str());
            return 2;
        }
    }
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        if (!quiet) std::fprintf(stderr, "raylane: %s (see raylane --help)\n", e.what());
        return 2;
    } catch (const raylane::InputError& e) {
        if (!quiet) std::fprintf(stderr, "raylane: %s\n", e.what());
        return 2;
    } catch (const raylane::Cancelled&) {
        if (!quiet) std::fprintf(stderr, "raylane: interrupted; nothing written\n");
        return 128 + (stop_signal != 0 ? static_cast<int>(stop_signal) : SIGINT);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylane: error: %s\n", e.what());
        return 1;
    }
    return exit_code;
}
