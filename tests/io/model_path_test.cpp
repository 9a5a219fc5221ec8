// tests for io/model_path.cpp: search order, RAYLANE_MODEL_PATH (no folder of the source tree) and
// the not-found message.
#include "io/model_path.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/error.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

/// Sets (or unsets) RAYLANE_MODEL_PATH for one test and restores the old value.
struct ModelPathEnv {
    std::optional<std::string> saved;
    explicit ModelPathEnv(const char* value) {
        if (const char* old = std::getenv("RAYLANE_MODEL_PATH")) saved = old;
        if (value) {
            ::setenv("RAYLANE_MODEL_PATH", value, 1);
        } else {
            ::unsetenv("RAYLANE_MODEL_PATH");
        }
    }
    ~ModelPathEnv() {
        if (saved) {
            ::setenv("RAYLANE_MODEL_PATH", saved->c_str(), 1);
        } else {
            ::unsetenv("RAYLANE_MODEL_PATH");
        }
    }
};

/// A fresh temporary folder with sub-folders a, b, c; removed at the end of the test.
struct TempDirs {
    fs::path root;
    TempDirs() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        root = fs::temp_directory_path() /
               ("raylane_model_path_" + std::to_string(::getpid()) + "_" + test->name());
        fs::remove_all(root);
        for (const char* sub : {"a", "b", "c"}) fs::create_directories(root / sub);
    }
    ~TempDirs() { fs::remove_all(root); }
    std::string dir(const char* sub) const { return (root / sub).string(); }
    std::string touch(const char* sub, const char* name) const {
        fs::path file = root / sub / name;
        std::ofstream(file) << "v 0 0 0\n";
        return file.string();
    }
};

TEST(FindModel, ReturnsAnAbsoluteNameThatExists) {
    TempDirs dirs;
    const std::string file = dirs.touch("c", "abs.obj");
    EXPECT_EQ(find_model(file, dirs.dir("a")), file);
}

TEST(FindModel, LooksInTheSceneFolderFirst) {
    TempDirs dirs;
    const std::string in_scene = dirs.touch("a", "m.obj");
    dirs.touch("b", "m.obj");
    ModelPathEnv env(dirs.dir("b").c_str());
    EXPECT_EQ(find_model("m.obj", dirs.dir("a")), in_scene);
}

TEST(FindModel, SearchesModelPathFoldersInOrder) {
    TempDirs dirs;
    const std::string in_c = dirs.touch("c", "m.ply");
    {
        ModelPathEnv env((dirs.dir("b") + "::" + dirs.dir("c")).c_str());
        EXPECT_EQ(find_model("m.ply", dirs.dir("a")), in_c);
    }
    const std::string in_b = dirs.touch("b", "m.ply");
    ModelPathEnv env((dirs.dir("b") + ":" + dirs.dir("c")).c_str());
    EXPECT_EQ(find_model("m.ply", dirs.dir("a")), in_b);
}

TEST(FindModel, FindsNamesWithSubfolders) {
    TempDirs dirs;
    fs::create_directories(dirs.root / "b" / "apple");
    const std::string file = (dirs.root / "b" / "apple" / "x.obj").string();
    std::ofstream(file) << "\n";
    ModelPathEnv env(dirs.dir("b").c_str());
    EXPECT_EQ(find_model("apple/x.obj", dirs.dir("a")), file);
}

TEST(FindModel, ListsSearchFoldersInTheDocumentedOrder) {
    TempDirs dirs;
    ModelPathEnv env((dirs.dir("b") + ":" + dirs.dir("c") + ":" + dirs.dir("b")).c_str());
    std::vector<std::string> got = model_search_dirs(dirs.dir("a"));
    ASSERT_EQ(got.size(), 3u);
    EXPECT_EQ(got[0], dirs.dir("a"));
    EXPECT_EQ(got[1], dirs.dir("b"));
    EXPECT_EQ(got[2], dirs.dir("c"));  // the repeated b is listed once
    EXPECT_EQ(model_search_dirs("")[0], ".");
}

TEST(FindModel, SearchesOnlyTheSceneFolderWithoutTheVariable) {
    // The binary knows no folder of the source tree: without RAYLANE_MODEL_PATH, a model beside
    // the checkout (../shared/models) is not found from another folder.
    TempDirs dirs;
    ModelPathEnv env(nullptr);
    EXPECT_EQ(model_search_dirs(dirs.dir("a")), std::vector<std::string>{dirs.dir("a")});
    EXPECT_THROW(find_model("dragon.ply", dirs.dir("a")), InputError);
}

TEST(FindModel, NamesTheModelAndEveryFolderWhenMissing) {
    TempDirs dirs;
    ModelPathEnv env((dirs.dir("b") + ":" + dirs.dir("c")).c_str());
    std::string message;
    try {
        find_model("no_such_model.ply", dirs.dir("a"));
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        message = e.what();
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : {std::string("no_such_model.ply"), dirs.dir("a"), dirs.dir("b"),
                                    dirs.dir("c"), std::string("RAYLANE_MODEL_PATH")}) {
        EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
}

TEST(FindModel, RejectsAMissingAbsolutePathAndAnEmptyName) {
    EXPECT_THROW(find_model("/nonexistent/raylane/m.obj", "."), InputError);
    EXPECT_THROW(find_model("", "."), InputError);
}

TEST(FindModel, IgnoresFoldersWithTheModelName) {
    TempDirs dirs;
    fs::create_directories(dirs.root / "a" / "m.obj");  // a folder, not a file
    const std::string file = dirs.touch("b", "m.obj");
    ModelPathEnv env(dirs.dir("b").c_str());
    EXPECT_EQ(find_model("m.obj", dirs.dir("a")), file);
}

/// find_model's message for `name`, or "" when it finds the file.
std::string find_error(const std::string& name, const std::string& scene_dir,
                       ModelKind kind = ModelKind::mesh) {
    try {
        find_model(name, scene_dir, kind);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(FindModel, SaysWhatStandsWhereOnlySomethingElseHasTheName) {
    TempDirs dirs;
    ModelPathEnv env(nullptr);
    fs::create_directories(dirs.root / "a" / "m.obj");
    EXPECT_EQ(find_error("m.obj", dirs.dir("a")),
              (dirs.root / "a" / "m.obj").string() + ": is a folder, not a file");
    fs::create_symlink(dirs.root / "a" / "gone.ply", dirs.root / "a" / "link.ply");
    EXPECT_EQ(find_error("link.ply", dirs.dir("a")),
              (dirs.root / "a" / "link.ply").string() + ": is a link to nothing");
    if (fs::exists("/dev/null")) {
        EXPECT_EQ(find_error("/dev/null", "."),
                  "/dev/null: is not a regular file (a device, "
                  "pipe or socket)");
    }
}

TEST(FindModel, RefusesANameWithANulByte) {
    EXPECT_EQ(find_error(std::string("a\0b.obj", 7), "."),
              "a\\0b.obj: a file name must not contain a NUL byte");
}

TEST(FindModel, AMissingTextureIsAnImageWithoutTheStanfordHint) {
    TempDirs dirs;
    ModelPathEnv env(nullptr);
    fs::create_directories(dirs.root / "a");
    const std::string message = find_error("no_such.png", dirs.dir("a"), ModelKind::texture);
    EXPECT_EQ(message, "no_such.png: image not found; looked in the scene's folder " +
                           fs::canonical(dirs.root / "a").string() +
                           " (RAYLANE_MODEL_PATH is not set). Put its folder in "
                           "RAYLANE_MODEL_PATH (':'-separated)");
}

/// "looked in" names each folder by its full name (a relative scene folder such as ".." is
/// shown resolved), says where each comes from, and gives the Stanford hint for the Stanford
/// models only.
TEST(FindModel, TheNotFoundLineNamesTheRealFoldersAndHintsOnlyForStanfordModels) {
    TempDirs dirs;
    fs::create_directories(dirs.root / "a" / "b");
    fs::create_directories(dirs.root / "m");
    const std::string a = fs::canonical(dirs.root / "a").string();
    const std::string m = fs::canonical(dirs.root / "m").string();
    {
        ModelPathEnv env(m.c_str());
        const std::string chair = find_error("my_chair.obj", dirs.dir("a") + "/b/..");
        EXPECT_EQ(chair, "my_chair.obj: model not found; looked in the scene's folder " + a +
                             " and RAYLANE_MODEL_PATH's " + m +
                             ". Put its folder in RAYLANE_MODEL_PATH (':'-separated)");
        const std::string bunny = find_error("bunny.ply", dirs.dir("a"));
        EXPECT_NE(
            bunny.find("looked in the scene's folder " + a + " and RAYLANE_MODEL_PATH's " + m +
                       ". Put its folder in RAYLANE_MODEL_PATH (':'-separated), or get "
                       "it from the Stanford 3D Scanning Repository"),
            std::string::npos)
            << bunny;
        EXPECT_NE(find_error("dragon.obj", dirs.dir("a")).find("Stanford"), std::string::npos);
    }
    ModelPathEnv unset(nullptr);
    EXPECT_NE(find_error("my_chair.obj", "")
                  .find("looked in the current folder " + fs::current_path().string() +
                        " (RAYLANE_MODEL_PATH is not set)"),
              std::string::npos);
    EXPECT_EQ(find_error("/no/such/chair.obj", dirs.dir("a")),
              "/no/such/chair.obj: model not found (no such file)");
}

}  // namespace
}  // namespace raylane
