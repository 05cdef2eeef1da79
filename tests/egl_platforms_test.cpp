// EGL platforms end to end: the same Mesa driver through EGL draws exactly what it draws through
// OSMesa (every record column but the timing ones), and each way an EGL platform can be missing
// stops `run` with a clear message before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "platforms/gl_context.h"
#include "platforms/platform_probe.h"
#include "tests/cli_harness.h"
#include "util/atomic_file.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string experiment(const std::string& platforms, int count) {
  const std::string n = std::to_string(count);
  return "seed = 2008\nplatforms = [" + platforms +
         "]\n[views]\norientations = 2\nfov_deg = [30, 150]\nwindows = [128, 907]\n"
         "near = 0.01\nfar = 10.0\n[primitives]\npoints = " + n + "\nlines = " + n +
         "\ntriangles = " + n + "\n[run]\nshard_size = 250\n";
}

// Records of one platform keyed by (kind, view, index): every column but platform, render_us and
// batch_size.
std::map<std::string, std::string> records_of(const std::string& run_dir,
                                              const std::string& platform) {
  std::map<std::string, std::string> out;
  for (const std::string& line : records_without_timing(run_dir)) {
    const std::size_t comma = line.find(',');
    if (line.compare(0, comma, platform) != 0) continue;
    const std::string rest = line.substr(comma + 1);
    // view is the first column after platform; kind and index are 9th and 10th
    std::vector<std::string> cells;
    for (std::size_t s = 0, e; s <= rest.size(); s = e + 1) {
      e = rest.find(',', s);
      if (e == std::string::npos) e = rest.size();
      cells.push_back(rest.substr(s, e - s));
    }
    out[cells.at(8) + "/" + cells.at(0) + "/" + cells.at(9)] = rest;
  }
  return out;
}

bool zink_installed() {
  for (const char* icd : {"/usr/share/vulkan/icd.d/lvp_icd.x86_64.json",
                          "/usr/share/vulkan/icd.d/lvp_icd.json"})
    if (fs::exists(icd)) return true;
  return false;
}

TEST(EglPlatforms, TheSameDriverThroughEglDrawsWhatItDrawsThroughOsmesa) {
  const std::string dir = fresh_dir("egl_identity");
  write_text(dir + "/e.toml", experiment("\"osmesa-llvmpipe\", \"egl-llvmpipe\", "
                                         "\"osmesa-softpipe\", \"egl-softpipe\"", 250));
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const auto& [osmesa, egl] : {std::pair<std::string, std::string>{"osmesa-llvmpipe", "egl-llvmpipe"},
                                    {"osmesa-softpipe", "egl-softpipe"}}) {
    const auto a = records_of(dir + "/run", osmesa), b = records_of(dir + "/run", egl);
    EXPECT_EQ(a.size(), 3u * 8 * 250) << osmesa;  // kinds x views x primitives
    ASSERT_EQ(a.size(), b.size()) << egl;
    std::size_t differing = 0;
    for (const auto& [key, row] : a) differing += b.count(key) == 0 || b.at(key) != row;
    EXPECT_EQ(differing, 0u) << osmesa << " vs " << egl;
  }
  // the driver file says how the context was made
  const std::string driver = ra::util::read_file(dir + "/run/drivers/egl-llvmpipe.json");
  EXPECT_NE(driver.find("EGL surfaceless (Mesa, llvmpipe)"), std::string::npos) << driver;
  EXPECT_NE(driver.find("\"renderer\": \"llvmpipe"), std::string::npos) << driver;
  // GL_TIME_ELAPSED against the CPU clock: softpipe's timer measures what the CPU waits for;
  // llvmpipe's a part of it (0.07 here), but never more than the wall time
  for (const char* p : {"osmesa-softpipe", "egl-softpipe", "osmesa-llvmpipe", "egl-llvmpipe"}) {
    const nlohmann::json j =
        nlohmann::json::parse(ra::util::read_file(dir + "/run/drivers/" + p + ".json"));
    ASSERT_TRUE(j.at("timer_over_cpu").is_number()) << p << ": " << j.dump();
    const double ratio = j["timer_over_cpu"];
    EXPECT_GT(ratio, 0) << p;
    EXPECT_LT(ratio, 1.5) << p;
    if (std::string(p).find("softpipe") != std::string::npos) {
      EXPECT_GT(ratio, 0.5) << p;
    }
  }
}

// Runs an experiment on `platform` with `env` and expects exit 2, `message` in the output and no
// run directory.
void expect_refused(const std::string& platform, const std::vector<std::string>& env,
                    const std::string& message) {
  const std::string dir = fresh_dir("egl_refused");
  write_text(dir + "/e.toml", experiment("\"" + platform + "\"", 5));
  ra::util::ChildSpec spec;
  spec.argv = split_words(std::string(RA_BINARY) + " run " + dir + "/e.toml --out " + dir + "/run");
  spec.set_env = env;
  spec.stdin_null = true;
  const ra::util::ProgramResult r = ra::util::run_program(spec);
  EXPECT_EQ(r.exit_code(), 2) << r.output;
  EXPECT_NE(r.output.find("platform(s) that cannot draw on this machine (nothing was written"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/run")) << platform;
}

TEST(EglPlatforms, AnUnknownDeviceIndexIsRefusedWithTheDevicesThereAre) {
  expect_refused("egl-device:7", {}, "egl-device:7: no EGL device 7 (this machine's EGL devices: 0:");
}

// `platforms` lists the EGL devices in a child (a parent holding NVIDIA's driver cannot fork
// probes): the child's list is the one this process finds itself.
TEST(EglPlatforms, TheDevicesListedInAChildAreTheOnesListedHere) {
  const std::vector<ra::platforms::EglDevice> child = ra::platforms::list_egl_devices_in_child();
  const std::vector<ra::platforms::EglDevice> here = ra::platforms::list_egl_devices();
  ASSERT_EQ(child.size(), here.size());
  ASSERT_FALSE(here.empty());
  for (std::size_t i = 0; i < here.size(); ++i) {
    EXPECT_EQ(child[i].index, here[i].index);
    EXPECT_EQ(child[i].extensions, here[i].extensions);
    EXPECT_EQ(child[i].drm_node, here[i].drm_node);
    EXPECT_EQ(child[i].software, here[i].software);
  }
}

TEST(EglPlatforms, AMachineWithoutLibEglIsRefusedWithThePackage) {
  expect_refused("egl-llvmpipe", {"RENDERAUDIT_LIBEGL=/nonexistent/libEGL.so.1"},
                 "egl-llvmpipe: cannot load /nonexistent/libEGL.so.1");
  expect_refused("egl-llvmpipe", {"RENDERAUDIT_LIBEGL=/nonexistent/libEGL.so.1"},
                 "apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri");
}

// A library chosen by RENDERAUDIT_LIBEGL / RENDERAUDIT_LIBOSMESA that cannot load is blamed on the
// variable, not only on a package; an extension override entry that hides nothing is refused.
TEST(EglPlatforms, TheVariableThatChoseAMissingLibraryIsNamed) {
  expect_refused("egl-llvmpipe", {"RENDERAUDIT_LIBEGL=/nonexistent/libEGL.so.1"},
                 "(/nonexistent/libEGL.so.1: cannot open shared object file: No such file or "
                 "directory), the library RENDERAUDIT_LIBEGL names; point it at an EGL library or "
                 "unset it");
  expect_refused("osmesa-llvmpipe", {"RENDERAUDIT_LIBOSMESA=/nonexistent/libOSMesa.so.8"},
                 "the library RENDERAUDIT_LIBOSMESA names; point it at an OSMesa library or "
                 "unset it");
  expect_refused("egl-llvmpipe", {"RENDERAUDIT_EGL_EXTENSION_OVERRIDE=EGL_KHR_surfaceless_context"},
                 "RENDERAUDIT_EGL_EXTENSION_OVERRIDE: entry 'EGL_KHR_surfaceless_context' does "
                 "not hide an extension");
}

// Mesa >= 25.1 has no OSMesa: the osmesa platforms say what to use instead, and `make` draws
// through EGL (platforms --embedded-default).
TEST(EglPlatforms, AMachineWithoutOsmesaIsToldToUseEgl) {
  const std::vector<std::string> no_osmesa = {"RENDERAUDIT_LIBOSMESA=/nonexistent/libOSMesa.so.8"};
  expect_refused("osmesa-llvmpipe", no_osmesa,
                 "egl-llvmpipe draws with the same driver through EGL");
  ra::util::ChildSpec spec;
  spec.argv = {RA_BINARY, "platforms", "--embedded-default"};
  spec.set_env = no_osmesa;
  spec.stdin_null = true;
  const ra::util::ProgramResult r = ra::util::run_program(spec);
  EXPECT_EQ(r.exit_code(), 0) << r.output;
  EXPECT_NE(r.output.find("egl-llvmpipe"), std::string::npos) << r.output;
  EXPECT_EQ(run_renderaudit("platforms --embedded-default").output.find("osmesa-llvmpipe"), 0u);
}

TEST(EglPlatforms, AMissingEglExtensionIsNamed) {
  expect_refused("egl-llvmpipe",
                 {"RENDERAUDIT_EGL_EXTENSION_OVERRIDE=-EGL_KHR_surfaceless_context"},
                 "egl-llvmpipe: the display lacks EGL_KHR_surfaceless_context");
  expect_refused("egl-device:0",
                 {"RENDERAUDIT_EGL_EXTENSION_OVERRIDE=-EGL_EXT_device_enumeration "
                  "-EGL_EXT_device_base"},
                 "lacks EGL_EXT_device_enumeration");
}

TEST(EglPlatforms, ZinkNeedsAVulkanDriver) {
  if (!zink_installed()) {
    expect_refused("egl-zink", {}, "mesa-vulkan-drivers libvulkan1");
    return;
  }
  // installed (mesa-vulkan-drivers): zink runs on lavapipe, itself on llvmpipe
  const std::string dir = fresh_dir("egl_zink");
  write_text(dir + "/e.toml", experiment("\"egl-zink\"", 5));
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(ra::util::read_file(dir + "/run/drivers/egl-zink.json").find("zink"),
            std::string::npos);
}

// The timing, LOD and regulation studies draw through the same layer: their smoke experiments,
// moved to EGL platforms by their experiment files, run and name the EGL context they drew with.
TEST(EglPlatforms, TheStudiesDrawThroughEglFromTheirExperimentFiles) {
  const std::string dir = fresh_dir("egl_studies");
  const std::string src = std::string(RA_SOURCE_DIR) + "/experiments/";
  const auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  write_text(dir + "/timing.toml",
             replaced(ra::util::read_file(src + "timing_smoke.toml"),
                      "platforms = [\"osmesa-llvmpipe\", \"osmesa-softpipe\"]",
                      "platforms = [\"egl-llvmpipe\"]"));
  write_text(dir + "/regulation.toml",
             replaced(ra::util::read_file(src + "regulation_smoke.toml"),
                      "platform = \"osmesa-llvmpipe\"", "platform = \"egl-softpipe\""));
  write_text(dir + "/lod.toml", replaced(ra::util::read_file(src + "lod_smoke.toml"), "[lod]\n",
                                         "[lod]\nplatform = \"egl-llvmpipe\"\n"));
  for (const char* study : {"timing", "regulation", "lod"}) {
    const Outcome o = run_renderaudit("run " + dir + "/" + study + ".toml --out " + dir + "/" +
                                      study + " --quiet");
    ASSERT_EQ(o.exit_code, 0) << study << ": " << o.output;
  }
  const nlohmann::json timing =
      nlohmann::json::parse(ra::util::read_file(dir + "/timing/timing.json"));
  ASSERT_EQ(timing.at("platforms").size(), 1u);
  EXPECT_EQ(timing["platforms"][0]["name"], "egl-llvmpipe");
  EXPECT_EQ(timing["platforms"][0]["renderer"]["backend"], "EGL surfaceless (Mesa, llvmpipe)");
  const nlohmann::json regulation =
      nlohmann::json::parse(ra::util::read_file(dir + "/regulation/regulation.json"));
  EXPECT_EQ(regulation.at("platform"), "egl-softpipe");
  EXPECT_EQ(regulation.at("render").at("renderer"), "softpipe");
  const nlohmann::json lod =
      nlohmann::json::parse(ra::util::read_file(dir + "/lod/lod_summary.json"));
  EXPECT_EQ(lod.at("platform"), "egl-llvmpipe");
  EXPECT_EQ(lod.at("gl_renderer").get<std::string>().rfind("llvmpipe", 0), 0u) << lod.dump();
}

TEST(EglPlatforms, PlatformsListsWhatCanDrawAndWhyTheRestCannot) {
  const Outcome o = run_renderaudit("platforms --json");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::size_t brace = o.output.find('{');
  ASSERT_NE(brace, std::string::npos) << o.output;
  const nlohmann::json j = nlohmann::json::parse(o.output.substr(brace, o.output.rfind('}') - brace + 1));
  std::map<std::string, nlohmann::json> by_name;
  for (const nlohmann::json& p : j.at("platforms")) by_name[p.at("name")] = p;
  for (const char* name : {"osmesa-llvmpipe", "egl-llvmpipe"}) {
    const nlohmann::json& p = by_name.at(name);
    EXPECT_TRUE(p.at("available").get<bool>()) << p.dump();
    EXPECT_EQ(p.at("renderer").get<std::string>().rfind("llvmpipe", 0), 0u) << p.dump();
    EXPECT_EQ(p.at("subpixel_bits"), 8);
    EXPECT_EQ(p.at("max_samples"), 4);
  }
  EXPECT_EQ(by_name.at("egl-softpipe").at("renderer"), "softpipe");
  EXPECT_EQ(by_name.at("egl-softpipe").at("max_samples"), 1);
  // Mesa's software device is enumerated as egl-device:0; `egl-device` wants hardware
  ASSERT_TRUE(by_name.count("egl-device:0")) << o.output;
  EXPECT_TRUE(by_name.at("egl-device:0").at("available").get<bool>());
  if (!by_name.at("egl-device").at("available").get<bool>()) {
    EXPECT_NE(by_name.at("egl-device").at("reason").get<std::string>().find("no hardware EGL device"),
              std::string::npos);
  }
}

}  // namespace

// An unset or empty XDG_RUNTIME_DIR (a session without one) makes libwayland complain through
// Mesa's Vulkan device-select layer under zink; surfaceless drawing needs no display server, and
// `platforms` prints no such line.
TEST(EglPlatforms, NoXdgRuntimeDirPrintsNothingFromZink) {
  for (const char* env : {"env XDG_RUNTIME_DIR= ", "env -u XDG_RUNTIME_DIR "}) {
    const Outcome o = run_command(env + std::string(RA_BINARY) + " platforms egl-zink");
    EXPECT_NE(o.output.find("egl-zink"), std::string::npos) << env << o.output;
    EXPECT_EQ(o.output.find("XDG_RUNTIME_DIR"), std::string::npos) << env << o.output;
  }
}
