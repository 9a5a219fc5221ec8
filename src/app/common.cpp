// app: helpers the commands share.
#include <tbb/info.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "core/isa.h"
#include "image/film.h"
#include "io/open_scene.h"

namespace raylane {

void add_bvh_option(CLI::App* cmd, std::string& bvh) {
    cmd->add_option("--bvh", bvh,
                    "BVH build: median (the report's median split, default) or sah (binned SAH, "
                    "for comparison)")
        ->check(CLI::IsMember({"median", "sah"}));
}

void add_isa_option(CLI::App* cmd, std::string& isa) {
    cmd->add_option("--isa", isa,
                    "instruction set of the packet path: sse4.2 (W = 4), avx2 (W = 8) or avx512 "
                    "(W = 16); default: RAYLANE_ISA, else the widest this CPU runs");
}

void add_threads_option(CLI::App* cmd, int& threads) {
    cmd->add_option("--threads", threads, "worker threads (default: all; at most the cores)")
        ->check(whole_in(1, 1024));
}

CLI::Validator finite_non_negative() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size())
                return "not a number: '" + text + "'";
            if (!std::isfinite(v) || v < 0.0) return "must be a finite number >= 0, not " + text;
            return {};
        },
        "NUMBER >= 0", "finite_non_negative");
}

CLI::Validator existing_scene_file() {
    return CLI::Validator(
        [](std::string& path) -> std::string {
            const std::string problem = scene_file_problem(path);
            return problem.empty() ? problem : path + ": " + problem;
        },
        "FILE", "existing_scene_file");
}

CLI::Validator whole_in(long long lo, long long hi) {
    const std::string range = std::to_string(lo) + " to " + std::to_string(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
                return "must be a whole number from " + range + ", not '" + text + "'";
            errno = 0;
            const long long v = std::strtoll(text.c_str(), nullptr, 10);
            if (errno == ERANGE || v < lo || v > hi)
                return "must be from " + range + ", not " + text;
            return {};
        },
        "INTEGER in " + range, "whole_in");
}

CLI::Validator whole_number() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
                return "must be a whole number >= 0 (decimal digits), not '" + text + "'";
            errno = 0;
            const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
            if (errno == ERANGE) return "too large: " + text;
            text = std::to_string(v);  // no leading zeros: CLI11 would read "010" as octal
            return {};
        },
        "INTEGER >= 0", "whole_number");
}

CLI::Validator image_output() {
    return CLI::Validator(
        [](std::string& path) -> std::string {
            if (image_format(path) == ImageFormat::none)
                return path + ": unknown image extension (use .png, .pfm or .exr)";
            std::error_code ec;
            if (std::filesystem::is_directory(path, ec)) return path + ": is a directory";
            const std::filesystem::path dir = std::filesystem::path(path).parent_path();
            if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
                return path + ": no such directory: " + dir.string();
            const std::string folder = dir.empty() ? "." : dir.string();
            if (::access(folder.c_str(), W_OK) != 0)
                return path + ": cannot write in " + folder + ": " + std::strerror(errno);
            return {};
        },
        "FILE.png|FILE.pfm|FILE.exr", "image_output");
}

namespace {

/// The edit distance of a and b (insertions, deletions, substitutions).
size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t above = row[j];
            row[j] =
                std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

}  // namespace

std::string unknown_option(const CLI::App& cmd, int argc, char** argv) {
    std::vector<std::string> known = {"--help"};
    for (const CLI::Option* option : cmd.get_options())
        for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
    for (int i = 2; i < argc; ++i) {
        const std::string word = argv[i];
        if (word == "--") break;
        if (word.rfind("--", 0) != 0) continue;
        const std::string name = word.substr(0, word.find('='));
        if (std::find(known.begin(), known.end(), name) != known.end()) continue;
        std::string nearest;
        size_t best = 3;  // suggest only a name within two edits
        for (const std::string& k : known) {
            const size_t d = edit_distance(name, k);
            if (d < best) best = d, nearest = k;
        }
        std::string message = cmd.get_name() + ": unknown option '" + name + "' (";
        if (!nearest.empty()) message += "did you mean " + nearest + "? ";
        return message + "see raylane " + cmd.get_name() + " --help)";
    }
    return {};
}

std::string version_text() {
    std::string text = std::string("raylane ") + RAYLANE_VERSION + "\n";
    try {
        text += isa_summary();
    } catch (const InputError& e) {  // RAYLANE_ISA names a set this machine does not run
        text += e.what();
    }
    return text;
}

SceneData load_command_scene(const std::string& path) {
    SceneData scene = open_scene(path);
    for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "raylane: warning: %s\n", w.c_str());
    return scene;
}

Scene load_command_scene(const std::string& path, const std::string& bvh) {
    Scene scene = Scene::load(path, bvh == "sah" ? BvhBuild::sah : BvhBuild::median);
    for (const std::string& w : scene.warnings())
        std::fprintf(stderr, "raylane: warning: %s\n", w.c_str());
    return scene;
}

}  // namespace raylane
