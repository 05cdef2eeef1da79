// Building Mesa from source, without compiling Mesa: the meson command lines chosen from real
// options files of two Mesa eras, the provenance and reuse keys, and the failure paths (a failing
// configure, a failing build command, a tree that is not Mesa) leaving the cache as it was.
#include "builds/source_build.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "rundir/build_record.h"
#include "platforms/vulkan_context.h"
#include "builds/meson_plan.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;
namespace ra::builds {
namespace {

// Excerpts of meson_options.txt as Mesa 23.0-devel (2022-11) and 25.1-devel (2025-01) spell them.
const char* kOptions2022 = R"(
option(
  'platforms',
  type : 'array',
  value : ['auto'],
  choices : [
    'auto', 'x11', 'wayland', 'haiku', 'android', 'windows',
  ],
  description : 'window systems to support. If this is set to `auto`, all platforms applicable will be enabled.'
)
option(
  'gallium-drivers',
  type : 'array',
  value : ['auto'],
  choices : [
    'auto', 'kmsro', 'radeonsi', 'r300', 'r600', 'nouveau', 'freedreno',
    'swrast', 'v3d', 'vc4', 'etnaviv', 'tegra', 'i915', 'svga', 'virgl',
    'panfrost', 'iris', 'lima', 'zink', 'd3d12', 'asahi', 'crocus'
  ],
  description : 'List of gallium drivers to build. (swrast: softpipe and llvmpipe)'
)
option('vulkan-drivers', type : 'array', value : ['auto'],
  choices : ['auto', 'amd', 'broadcom', 'freedreno', 'intel', 'swrast', 'virtio-experimental'])
option(
  'shared-glapi',
  type : 'combo',
  value : 'auto',
  choices : ['auto', 'true', 'false', 'enabled', 'disabled'],
  description : 'Whether to build a shared or static glapi. Defaults to false on Windows, true elsewhere'
)
option('egl', type : 'combo', value : 'auto', choices : ['auto', 'true', 'false', 'enabled', 'disabled'])
option('glx', type : 'combo', value : 'auto', choices : ['auto', 'disabled', 'dri', 'xlib'])
option(
  'glvnd',
  type : 'boolean',
  value : false,   # a comment with a 'quote
  description : 'Enable GLVND support.'
)
option('osmesa', type : 'boolean', value : false, description : 'Build OSmesa.')
option('llvm', type : 'feature', description : 'Build with LLVM support.')
option('shared-llvm', type : 'feature', value : 'auto')
)";

const char* kOptions2025 = R"(
option('platforms', type : 'array', value : ['auto'], choices : ['auto', 'x11', 'wayland'])
option(
  'gallium-drivers',
  type : 'array',
  value : ['auto'],
  choices : [
    'auto', 'radeonsi', 'r300', 'r600', 'nouveau', 'freedreno',
    'swrast', 'v3d', 'vc4', 'etnaviv', 'tegra', 'i915', 'svga', 'virgl',
    'panfrost', 'iris', 'lima', 'zink', 'd3d12', 'asahi', 'crocus', 'all',
    'softpipe', 'llvmpipe',
  ],
)
option('vulkan-drivers', type : 'array', value : ['auto'], choices : ['auto', 'amd', 'swrast'])
option('egl', type : 'feature', value : 'auto')
option('glx', type : 'combo', value : 'auto', choices : ['auto', 'disabled', 'dri', 'xlib'])
option(
  'glvnd',
  type : 'feature',
  deprecated: {'true': 'enabled', 'false': 'disabled'},
  description : 'Enable GLVND support.'
)
option('llvm', type : 'feature')
option('shared-llvm', type : 'feature', value : 'auto')
)";

bool has(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

MesonPlanInputs inputs(const char* options, const std::string& glslang) {
  MesonPlanInputs in;
  in.options = parse_meson_options(options);
  in.source_dir = "/src";
  in.build_dir = "/b";
  in.prefix = "/p";
  in.native_file = "/n.ini";
  in.glslang_version = glslang;
  return in;
}

TEST(MesonPlan, ParsesTypesAndChoicesOfBothEras) {
  const auto o22 = parse_meson_options(kOptions2022);
  ASSERT_EQ(o22.size(), 10u);
  EXPECT_EQ(o22.at("glvnd").type, "boolean");
  EXPECT_EQ(o22.at("shared-glapi").type, "combo");
  EXPECT_EQ(o22.at("gallium-drivers").choices.size(), 22u);
  EXPECT_TRUE(has(o22.at("gallium-drivers").choices, "swrast"));
  EXPECT_FALSE(has(o22.at("gallium-drivers").choices, "llvmpipe"));
  const auto o25 = parse_meson_options(kOptions2025);
  EXPECT_EQ(o25.at("glvnd").type, "feature");
  EXPECT_TRUE(has(o25.at("gallium-drivers").choices, "llvmpipe"));
  EXPECT_EQ(o25.count("osmesa"), 0u);
}

TEST(MesonPlan, OptionsFollowTheTreeNotOneMesaVersion) {
  const MesonPlan p22 = plan_meson_build(inputs(kOptions2022, "12.0.0"));
  EXPECT_TRUE(has(p22.chosen, "-Dgallium-drivers=swrast"));
  EXPECT_TRUE(has(p22.chosen, "-Dglvnd=true"));      // boolean then
  EXPECT_TRUE(has(p22.chosen, "-Dosmesa=true"));
  EXPECT_TRUE(has(p22.chosen, "-Dshared-glapi=enabled"));
  EXPECT_TRUE(has(p22.chosen, "-Degl=enabled"));     // combo with enabled
  EXPECT_TRUE(has(p22.chosen, "-Dglx=disabled"));
  EXPECT_TRUE(has(p22.chosen, "-Dvulkan-drivers="));  // glslang 12.0: no lavapipe, said
  ASSERT_FALSE(p22.notes.empty());
  EXPECT_NE(p22.notes[0].find("lavapipe not built: glslang 12.0.0 is older than 12.2"),
            std::string::npos);
  const MesonPlan p25 = plan_meson_build(inputs(kOptions2025, "15.1.0"));
  EXPECT_TRUE(has(p25.chosen, "-Dgallium-drivers=llvmpipe,softpipe"));
  EXPECT_TRUE(has(p25.chosen, "-Dglvnd=enabled"));
  EXPECT_TRUE(has(p25.chosen, "-Dvulkan-drivers=swrast"));
  EXPECT_FALSE(has(p25.chosen, "-Dosmesa=true"));     // the tree has no such option
  EXPECT_FALSE(has(p25.chosen, "-Dshared-glapi=enabled"));
  // Every option passed is one the tree declares.
  const auto o25 = parse_meson_options(kOptions2025);
  for (const std::string& c : p25.chosen) {
    const std::string name = c.substr(2, c.find('=') - 2);
    EXPECT_EQ(o25.count(name), 1u) << c;
  }
  // The command line: the tree, the prefix, one LLVM, a release build, then the chosen options.
  const std::vector<std::string> head = {"meson", "setup", "/b", "/src", "--native-file", "/n.ini",
                                         "--prefix", "/p", "--libdir", "lib/x86_64-linux-gnu",
                                         "--buildtype", "release", "-Db_ndebug=true"};
  EXPECT_EQ(std::vector<std::string>(p25.setup.begin(), p25.setup.begin() + long(head.size())), head);
  EXPECT_EQ(native_file_text("/usr/bin/llvm-config-15"),
            "[binaries]\nllvm-config = '/usr/bin/llvm-config-15'\ncmake = '/bin/false'\n");
}

TEST(MesonPlan, GlslangVersionsForLavapipe) {
  EXPECT_FALSE(glslang_builds_lavapipe(""));
  EXPECT_FALSE(glslang_builds_lavapipe("12.0.0"));
  EXPECT_FALSE(glslang_builds_lavapipe("11.13.0"));
  EXPECT_TRUE(glslang_builds_lavapipe("12.2.0"));
  EXPECT_TRUE(glslang_builds_lavapipe("15.1.0"));
}

TEST(SourceBuild, MissingPackagesAreNamedFromMesonsWords) {
  EXPECT_EQ(missing_package_hint("Run-time dependency libdrm found: NO (tried pkgconfig)\n"
                                 "meson.build:1780:13: ERROR: Dependency \"libdrm\" not found"),
            "libdrm-dev");
  EXPECT_EQ(missing_package_hint("ERROR: Program 'bison' not found or not executable"), "bison");
  EXPECT_EQ(missing_package_hint("Python (3.x) mako module >= 0.8.0 required to build mesa."),
            "python3-mako");
  EXPECT_EQ(missing_package_hint("Compiling C object src/foo.c.o\nall fine"), "");
}

TEST(SourceBuild, NamesAndKeysFollowCommitAndOptions) {
  SourceIdentity id;
  id.git = true;
  id.commit = "ef5f9c99e054aaaaaaaaaaaaaaaaaaaaaaaaaaaaaa";
  SourceBuildOptions o;
  EXPECT_EQ(source_build_name(id, o), "mesa-ef5f9c99e054");
  const std::string key = source_build_key(id, o);
  SourceBuildOptions other = o;
  other.meson_options = {"-Dgallium-drivers=softpipe"};
  EXPECT_NE(source_build_key(id, other), key);
  EXPECT_EQ(source_build_name(id, other).rfind("mesa-ef5f9c99e054-", 0), 0u);
  SourceIdentity next = id;
  next.commit[0] = '0';
  EXPECT_NE(source_build_key(next, o), key);
  SourceIdentity tree;
  tree.version = "22.3.6";
  tree.debian_version = "22.3.6-1+deb12u1";
  EXPECT_EQ(source_build_name(tree, o), "mesa-22.3.6-src");
  SourceIdentity dirty = id;
  dirty.dirty = true;
  EXPECT_EQ(source_build_name(dirty, o), "mesa-ef5f9c99e054-dirty");
}

class SourceBuildDirs : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("ra-source-build-" + std::to_string(::getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "cache" / "kept");
    std::ofstream(root_ / "cache" / "kept" / "build.json") << "{\"name\": \"kept\"}\n";
  }
  void TearDown() override { fs::remove_all(root_); }
  std::vector<std::string> cache_listing() const {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(root_ / "cache"))
      out.push_back(e.path().lexically_relative(root_ / "cache").string());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path root_;
};

TEST_F(SourceBuildDirs, AFailingConfigureLeavesTheCacheAsItWas) {
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  std::ofstream(tree / "meson.build") << "project('mesa', 'c')\ndependency('renderaudit-no-such-library')\n";
  std::ofstream(tree / "VERSION") << "99.0.0-devel\n";
  const auto before = cache_listing();
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.probe = false;
  if (std::system("meson --version >/dev/null 2>&1") != 0 ||
      !fs::exists(o.llvm_config))
    GTEST_SKIP() << "meson or LLVM 15 not installed (scripts/install-mesa-build-deps.sh)";
  try {
    build_from_source(o);
    FAIL() << "a configure that fails was accepted";
  } catch (const util::UserError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("the configure (meson setup) step failed"), std::string::npos) << m;
    EXPECT_NE(m.find("renderaudit-no-such-library"), std::string::npos) << m;
    EXPECT_NE(m.find("the build cache is unchanged"), std::string::npos) << m;
  }
  EXPECT_EQ(cache_listing(), before);
}

TEST_F(SourceBuildDirs, MissingMesonIsNamedWithTheSetUpStep) {
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  std::ofstream(tree / "meson.build") << "project('mesa', 'c')\n";
  const auto before = cache_listing();
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.meson = (root_ / "no-such-meson").string();  // as on a machine without it
  try {
    build_from_source(o);
    FAIL() << "a build without meson was attempted";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("is not installed: scripts/install-mesa-build-deps.sh "
                                         "installs what a Mesa build needs"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(cache_listing(), before);
}

TEST_F(SourceBuildDirs, ABuildCommandInstallsProbesNothingAndIsReused) {
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  ASSERT_EQ(std::system(("git -C " + tree.string() + " init -q && git -C " + tree.string() +
                         " -c user.email=t@t -c user.name=t commit -q --allow-empty -m one")
                            .c_str()),
            0);
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.probe = false;
  o.build_command = "mkdir -p \"$RENDERAUDIT_BUILD_PREFIX/lib/x86_64-linux-gnu\" && "
                    "echo built > \"$RENDERAUDIT_BUILD_PREFIX/lib/x86_64-linux-gnu/marker.so\"";
  const SourceBuildResult first = build_from_source(o);
  EXPECT_FALSE(first.reused);
  EXPECT_TRUE(fs::exists(first.build.dir + "/lib/x86_64-linux-gnu/marker.so"));
  EXPECT_TRUE(fs::exists(first.build.dir + "/build.json"));
  const SourceBuildResult second = build_from_source(o);
  EXPECT_TRUE(second.reused);
  EXPECT_EQ(second.build.dir, first.build.dir);
  // A failing command: the cache keeps what it had, nothing half-built appears.
  const auto before = cache_listing();
  o.build_command = "echo compile error >&2; exit 3";
  o.reuse = false;
  try {
    build_from_source(o);
    FAIL() << "a failing build command was accepted";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("compile error"), std::string::npos) << e.what();
  }
  EXPECT_EQ(cache_listing(), before);
}

TEST_F(SourceBuildDirs, AFileGitDoesNotTrackMakesABuildNotItsCommits) {
  // Why: an untracked meson.options (what a checkout that failed half-way leaves) was built into
  // the cached build of the commit, which every later night and bisection then reused.
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  ASSERT_EQ(std::system(("git -C " + tree.string() + " init -q && git -C " + tree.string() +
                         " -c user.email=t@t -c user.name=t commit -q --allow-empty -m one")
                            .c_str()),
            0);
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.probe = false;
  o.build_command = "mkdir -p \"$RENDERAUDIT_BUILD_PREFIX/lib/x86_64-linux-gnu\"";
  std::ofstream(tree / "meson.options") << "option('stale', type: 'boolean')\n";
  o.ref = "HEAD";
  try {
    build_from_source(o);
    FAIL() << "a tree with an untracked file was built for --ref";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("has 1 untracked file (meson.options)"), std::string::npos)
        << e.what();
  }
  o.ref = "";  // as it is: built, but not under the commit's name and never reused
  const std::string tainted = build_from_source(o).build.name;  // not held: replaced below
  EXPECT_NE(tainted.find("-dirty"), std::string::npos) << tainted;
  EXPECT_FALSE(build_from_source(o).reused);
  fs::remove(tree / "meson.options");
  const rundir::BuildRecord clean = build_from_source(o).build;
  EXPECT_EQ(clean.name.find("-dirty"), std::string::npos) << clean.name;
  EXPECT_TRUE(build_from_source(o).reused);
  // A build that does not record a clean tree (made before the record) is built again.
  nlohmann::json j = nlohmann::json::parse(util::read_file(clean.dir + "/build.json"));
  EXPECT_EQ(j["source_build"]["clean"], true);
  j["source_build"].erase("clean");
  util::write_file_atomic(clean.dir + "/build.json", j.dump());
  EXPECT_FALSE(build_from_source(o).reused);
}

TEST_F(SourceBuildDirs, ABuildAProcessDrawsWithIsNotReplaced) {
  // Why: `builds build --rebuild` moved a build aside under a night that drew with it.
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  ASSERT_EQ(std::system(("git -C " + tree.string() + " init -q && git -C " + tree.string() +
                         " -c user.email=t@t -c user.name=t commit -q --allow-empty -m one")
                            .c_str()),
            0);
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.probe = false;
  o.build_command = "mkdir -p \"$RENDERAUDIT_BUILD_PREFIX/lib/x86_64-linux-gnu\"";
  std::shared_ptr<BuildInUse> night = build_from_source(o).in_use;
  ASSERT_TRUE(night);
  o.reuse = false;
  try {
    build_from_source(o);
    FAIL() << "a build drawn with was replaced";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("is in use: a process draws with it now"),
              std::string::npos)
        << e.what();
  }
  night.reset();
  EXPECT_FALSE(build_from_source(o).reused);
}

TEST_F(SourceBuildDirs, ATreeWithoutGitIsKeyedOnItsContent) {
  // Why: a source package's tree was keyed on VERSION and its patch list, so applying the patches
  // reused the unpatched build.
  const fs::path tree = root_ / "mesa-25.0.7";
  fs::create_directories(tree / "src");
  std::ofstream(tree / "VERSION") << "25.0.7\n";
  std::ofstream(tree / "src" / "lp_setup_line.c") << "int guard_band = 1;\n";
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.probe = false;
  o.build_command = "mkdir -p \"$RENDERAUDIT_BUILD_PREFIX/lib/x86_64-linux-gnu\" && "
                    "cp src/lp_setup_line.c \"$RENDERAUDIT_BUILD_PREFIX/lib/x86_64-linux-gnu/\"";
  const SourceBuildResult first = build_from_source(o);
  EXPECT_FALSE(first.reused);
  EXPECT_TRUE(build_from_source(o).reused);
  std::ofstream(tree / "src" / "lp_setup_line.c") << "int guard_band = 0;\n";  // the patch
  const SourceBuildResult patched = build_from_source(o);
  EXPECT_FALSE(patched.reused);
  EXPECT_EQ(util::read_file(patched.build.dir + "/lib/x86_64-linux-gnu/lp_setup_line.c"),
            "int guard_band = 0;\n");
  // The hash is of the files: a lock file or a renamed file count as they should.
  const std::string hash = tree_content_hash(tree.string());
  std::ofstream(tree / ".lock") << "process 1 (builds build)\n";
  EXPECT_EQ(tree_content_hash(tree.string()), hash);
  fs::rename(tree / "src" / "lp_setup_line.c", tree / "src" / "lp_setup_tri.c");
  EXPECT_NE(tree_content_hash(tree.string()), hash);
}

TEST_F(SourceBuildDirs, AnIncrementalFolderRebuildsOnlyWhatTheCommitChanged) {
  // Why: a bisection step rebuilt Mesa from nothing (7-10 minutes on 2 cores); one meson folder
  // kept across commits compiles only the files a commit touched, and every commit keeps its own
  // install in the cache.
  if (std::system("meson --version >/dev/null 2>&1") != 0 ||
      std::system("ninja --version >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "meson or ninja not installed (scripts/install-deps.sh installs them)";
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  std::ofstream(tree / "meson.build")
      << "project('mesa', 'c')\nshared_library('OSMesa', 'one.c', 'two.c', install: true)\n";
  std::ofstream(tree / "one.c") << "int one(void) { return 1; }\n";
  std::ofstream(tree / "two.c") << "int two(void) { return 2; }\n";
  const std::string git = "git -C " + tree.string() + " -c user.email=t@t -c user.name=t ";
  ASSERT_EQ(std::system(("git -C " + tree.string() + " init -q && " + git + "add -A && " + git +
                         "commit -q -m one")
                            .c_str()),
            0);
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.probe = false;
  o.incremental = true;
  o.jobs = 1;
  o.llvm_config = "/bin/true";  // the project asks for no LLVM
  std::vector<std::string> said;
  const auto say = [&](const std::string& s) { said.push_back(s); };
  const SourceBuildResult first = build_from_source(o, say);
  ASSERT_FALSE(first.reused);
  std::ofstream(tree / "two.c") << "int two(void) { return 22; }\n";
  ASSERT_EQ(std::system((git + "commit -q -am two").c_str()), 0);
  said.clear();
  const SourceBuildResult second = build_from_source(o, say);
  EXPECT_NE(second.build.dir, first.build.dir);
  EXPECT_TRUE(std::any_of(said.begin(), said.end(), [](const std::string& s) {
    return s.find("reusing the incremental build folder") != std::string::npos;
  }));
  const std::string log = util::read_file(second.build.dir + "/build.log");
  EXPECT_NE(log.find("two.c"), std::string::npos) << log;
  EXPECT_EQ(log.find("one.c"), std::string::npos) << "one.c was compiled again:\n" << log;
  // Both commits' installs stay in the cache, each its own.
  for (const SourceBuildResult* r : {&first, &second}) {
    bool has_library = false;
    for (const auto& e : fs::recursive_directory_iterator(r->build.dir))
      has_library |= e.path().filename().string().rfind("libOSMesa.so", 0) == 0;
    EXPECT_TRUE(has_library) << r->build.dir;
  }
}

// --llvm-config goes into meson's native file: a path that is not an executable file, or holds a
// line break and a second entry, is refused naming the option before anything is configured, and
// a path with quotes and backslashes is written as one meson string.
TEST_F(SourceBuildDirs, AnLlvmConfigThatIsNotAnExecutableFileIsRefused) {
  if (std::system("ninja --version >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ninja not installed (scripts/install-mesa-build-deps.sh)";
  const fs::path tree = root_ / "mesa";
  fs::create_directories(tree);
  std::ofstream(tree / "meson.build") << "project('mesa', 'c')\n";
  const fs::path fake_meson = root_ / "meson";  // answers --version, as an installed meson would
  std::ofstream(fake_meson) << "#!/bin/sh\necho 1.4.0\n";
  fs::permissions(fake_meson, fs::perms::owner_all);
  const fs::path evil = root_ / "evil.sh";
  std::ofstream(evil) << "#!/bin/sh\ntouch " << (root_ / "pwned").string() << "\n";
  fs::permissions(evil, fs::perms::owner_all);
  const fs::path plain = root_ / "plain";
  std::ofstream(plain) << "not a program\n";
  const auto before = cache_listing();
  SourceBuildOptions o;
  o.source = tree.string();
  o.cache = (root_ / "cache").string();
  o.meson = fake_meson.string();
  o.probe = false;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {root_.string() + "/x'\nc = '" + evil.string(), "holds a control character"},
      {root_.string(), "is not an executable file"},
      {plain.string(), "is not an executable file"},
      {(root_ / "none").string(), "is missing"}};
  for (const auto& [path, says] : cases) {
    o.llvm_config = path;
    try {
      build_from_source(o);
      ADD_FAILURE() << "--llvm-config " << path << " was accepted";
    } catch (const util::UserError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("--llvm-config '"), std::string::npos) << m;
      EXPECT_NE(m.find(says), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
  EXPECT_EQ(cache_listing(), before);
  EXPECT_FALSE(fs::exists(root_ / "pwned"));
  EXPECT_EQ(native_file_text("/opt/it's\\llvm\nc = '/evil.sh"),
            "[binaries]\nllvm-config = '/opt/it\\'s\\\\llvm\\x0ac = \\'/evil.sh'\n"
            "cmake = '/bin/false'\n");
}

TEST_F(SourceBuildDirs, AMesonPrefixIsABuildFolderAndItsLavapipeIsFound) {
  // The layout `meson install` makes: lib/<multiarch>, share/vulkan/icd.d naming the library by
  // the prefix it was built for (here a temporary folder that no longer exists).
  const fs::path prefix = root_ / "cache" / "mesa-src";
  fs::create_directories(prefix / "lib/x86_64-linux-gnu");
  std::ofstream(prefix / "lib/x86_64-linux-gnu/libEGL_mesa.so.0") << "";
  std::ofstream(prefix / "lib/x86_64-linux-gnu/libvulkan_lvp.so") << "";
  EXPECT_EQ(rundir::build_library_dir(prefix.string()),
            (prefix / "lib/x86_64-linux-gnu").string());
  EXPECT_EQ(platforms::resolve_icd_library(prefix.string(),
                                           "/tmp/gone/install/lib/x86_64-linux-gnu/libvulkan_lvp.so"),
            (prefix / "lib/x86_64-linux-gnu/libvulkan_lvp.so").string());
  // A Debian package unpacked: usr/lib/<multiarch>, the ICD naming /usr/lib/...
  const fs::path deb = root_ / "cache" / "mesa-deb";
  fs::create_directories(deb / "usr/lib/x86_64-linux-gnu");
  std::ofstream(deb / "usr/lib/x86_64-linux-gnu/libvulkan_lvp.so") << "";
  EXPECT_EQ(platforms::resolve_icd_library(deb.string(), "/usr/lib/x86_64-linux-gnu/libvulkan_lvp.so"),
            (deb / "usr/lib/x86_64-linux-gnu/libvulkan_lvp.so").string());
  EXPECT_THROW(platforms::resolve_icd_library(deb.string(), "/elsewhere/libvulkan_other.so"),
               util::UserError);
}

}  // namespace
}  // namespace ra::builds
