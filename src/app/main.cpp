// app: the `raylane` command line (CLI11). Input errors print one line and exit with code 2.
#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
    CLI::App app{"Raylane: a data-oriented SIMD packet ray tracer"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "help for every command");
    int exit_code = 0;
    raylane::add_render_command(app, exit_code);
    raylane::add_info_command(app, exit_code);
    raylane::add_compare_command(app, exit_code);
    raylane::add_report_command(app, exit_code);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "raylane: %s (see raylane --help)\n", e.what());
        return 2;
    } catch (const raylane::InputError& e) {
        std::fprintf(stderr, "raylane: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylane: error: %s\n", e.what());
        return 1;
    }
    return exit_code;
}
