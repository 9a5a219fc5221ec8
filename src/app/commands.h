// app: the `raylane` commands, one file each, and what they share.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "accel/bvh.h"         // build_params, for --bvh
#include "core/clock.h"        // now_seconds, elapsed_ms: the commands time their stages
#include "core/threads.h"      // worker_threads, for --threads
#include "io/open_scene.h"     // scene_file_problem, for scene arguments
#include "scene/resolution.h"  // apply_resolution, for --width and --height
#include "scene/scene.h"

namespace raylane {

/// Adds the subcommand and its options; the callback runs it and stores the exit code.
void add_render_command(CLI::App& app, int& exit_code);
void add_info_command(CLI::App& app, int& exit_code);
void add_compare_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_scene_command(CLI::App& app, int& exit_code);
void add_assemble_command(CLI::App& app, int& exit_code);

/// What `raylane --version` prints: the version, and the instruction sets compiled in, those this
/// CPU runs and the one in use (core/isa.h).
std::string version_text();

/// Adds --isa to a command: the packet path's instruction set (sse4.2, avx2, avx512), stored in
/// `isa` for main to apply.
void add_isa_option(CLI::App* cmd, std::string& isa);

/// Adds --bvh to a command: median (the report's build, the default) or sah (binned SAH, a
/// comparison option).
void add_bvh_option(CLI::App* cmd, std::string& bvh);
/// Adds --threads to a command: 1 to 1024 worker threads (0, the default, is all).
void add_threads_option(CLI::App* cmd, int& threads);
/// Checks that an option's value is a finite number >= 0 (CLI::Range lets NaN through and
/// prints its bounds in full).
CLI::Validator finite_non_negative();
/// Checks that an integer option's value is a whole number in decimal digits from lo to hi: "4.5"
/// is refused as not a whole number, 0 as out of range (CLI::Range says "not in range" for both).
CLI::Validator whole_in(long long lo, long long hi);
/// Checks that an option's value is a whole number >= 0 in decimal digits that fits 64 bits, and
/// passes it on without leading zeros (CLI11 itself reads "010" as octal and clamps larger
/// values). Use it with transform(): check() would pass on the original text.
CLI::Validator whole_number();
/// Checks that a scene argument names a file (scene_file_problem's words when it does not).
CLI::Validator existing_scene_file();
/// Checks, before any work, that an image path can be written: a .png, .pfm or .exr extension
/// (any case), not a directory, in a directory that exists and that this user may write in.
CLI::Validator image_output();

/// "render: unknown option '--sp' (did you mean --spp? see raylane render --help)" for the first
/// word of argv[2..] that starts with "--" and names no option of `cmd` (before a lone "--");
/// empty when every one is known.
std::string unknown_option(const CLI::App& cmd, int argc, char** argv);

/// The scene a command works on (io/open_scene.h's open_scene), its warnings printed on stderr.
SceneData load_command_scene(const std::string& path);
/// The same as the public API's raylane::Scene with its BVHs built by --bvh `bvh`.
Scene load_command_scene(const std::string& path, const std::string& bvh);

}  // namespace raylane
