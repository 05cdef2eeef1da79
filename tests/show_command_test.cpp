// End-to-end tests of `renderaudit show`: the PNG of one primitive (read back with OpenImageIO),
// its record, and the errors for a bad platform, kind, view, index or run directory.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdio>

#include <filesystem>
#include <memory>
#include <sstream>

#include "triage/image_legend.h"
#include "rundir/records_reader.h"
#include "triage/primitive_image.h"
#include "rundir/experiment.h"
#include "metrics/records.h"
#include "geometry/reference_rasterizer.h"
#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

// One view, 64 x 64 px (shown whole, 8 image px per window pixel: 512 x 512).
std::string experiment(const std::string& platforms, const std::string& extra = "") {
  return "seed = 7\nplatforms = [" + platforms +
         "]\n[views]\norientations = 1\nfov_deg = [60]\nwindows = [64]\nnear = 0.01\nfar = 10.0\n"
         "[primitives]\n"
         "points = 4\nlines = 4\ntriangles = 20\n" +
         extra;
}

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> pixels;
  ra::triage::Rgb8 at(int x, int y) const {
    const unsigned char* p = &pixels[(std::size_t(y) * width + x) * channels];
    return {p[0], p[1], p[2]};
  }
};

Image read_image(const std::string& path) {
  Image im;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return im;
  const OIIO::ImageSpec& spec = in->spec();
  im.width = spec.width, im.height = spec.height, im.channels = spec.nchannels;
  im.pixels.resize(std::size_t(im.width) * im.height * im.channels);
  in->read_image(0, 0, 0, im.channels, OIIO::TypeDesc::UINT8, im.pixels.data());
  return im;
}

// Window pixels (blocks of `scale` image px) whose block has a pixel of `colour`, with a block
// interior pixel (not the grid border) checked so the red outline cannot hide a block.
int blocks_with(const Image& im, int scale, ra::triage::Rgb8 colour) {
  int n = 0;
  for (int by = 0; by < im.height / scale; ++by)
    for (int bx = 0; bx < im.width / scale; ++bx) {
      bool found = false;
      for (int i = 1; i < scale && !found; ++i)
        for (int j = 1; j < scale && !found; ++j)
          found = im.at(bx * scale + j, by * scale + i) == colour;
      n += found;
    }
  return n;
}

// The top left `width` x `height` pixels of an image: the picture of the window pixels, without
// the legend under it.
Image picture(const Image& whole, int width, int height) {
  Image im;
  im.width = width, im.height = height, im.channels = whole.channels;
  for (int y = 0; y < height; ++y)
    im.pixels.insert(im.pixels.end(), whole.pixels.begin() + std::ptrdiff_t(y) * whole.width * whole.channels,
                     whole.pixels.begin() + (std::ptrdiff_t(y) * whole.width + width) * whole.channels);
  return im;
}

// The legend under the picture (rows from `top` down).
Image legend(const Image& whole, int top) {
  Image im;
  im.width = whole.width, im.height = whole.height - top, im.channels = whole.channels;
  im.pixels.assign(whole.pixels.begin() + std::ptrdiff_t(top) * whole.width * whole.channels,
                   whole.pixels.end());
  return im;
}

int pixels_with(const Image& im, ra::triage::Rgb8 colour) {
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += im.at(x, y) == colour;
  return n;
}

// The value printed for `field` in show's record block ("  pixels           37").
std::string field(const std::string& output, const std::string& name) {
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key, value;
    if (words >> key >> value && key == name) return value;
  }
  return "";
}

// Runs the tiny experiment once for all the tests of this file.
const std::string& reference_run() {
  static const std::string run = [] {
    const std::string dir = fresh_dir("show_run");
    write_text(dir + "/e.toml", experiment("\"reference\""));
    const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 1 -q");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    return dir + "/run";
  }();
  return run;
}

// The largest true-visible triangle of the run, and its record.
ra::metrics::Record largest_triangle(const std::string& run) {
  ra::metrics::Record best;
  for (const auto& e : fs::directory_iterator(run + "/records"))
    if (ra::rundir::is_records_file_name(e.path().filename().string()))
      ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record& r) {
        if (r.kind == "triangle" && r.visibility == ra::metrics::Visibility::kTrueVisible &&
            r.pixels > best.pixels)
          best = r;
      });
  return best;
}

TEST(ShowCommand, ATriangleOnTheReferenceIsGreyWithARedOutline) {
  const std::string run = reference_run();
  const ra::metrics::Record rec = largest_triangle(run);
  ASSERT_GT(rec.pixels, 10) << "the experiment should have a triangle with some pixels";
  const std::string png = fs::path(run).parent_path().string() + "/shown/t.png";
  const Outcome o = run_renderaudit("show " + run +
                                    " --platform reference --kind triangle --view 1 "
                                    "--index " +
                                    std::to_string(rec.index) + " --out " + png);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const Image whole = read_image(png);
  EXPECT_NE(o.output.find("wrote " + png + " (512 x " + std::to_string(whole.height) +
                          " px: window pixels x 0-63, y 0-63 of "
                          "64 x 64, 8 px each, in the top 512 x 512; the legend under them)"),
            std::string::npos)
      << o.output;
  // The record of this rendering is the run's record.
  EXPECT_EQ(field(o.output, "visibility"), "true-visible") << o.output;
  EXPECT_EQ(field(o.output, "pixels"), std::to_string(rec.pixels)) << o.output;
  EXPECT_EQ(field(o.output, "ref_diff"), "0") << o.output;
  EXPECT_NE(field(o.output, "te_u"), "") << o.output;
  EXPECT_EQ(field(o.output, "pe"), "") << "point metrics do not apply to a triangle";

  ASSERT_EQ(whole.width, 512);
  // the legend's 5 rows under the picture, in text sized to it (no inset at 8 px a pixel)
  ASSERT_GE(whole.height, 512 + 5 * ra::triage::legend_font_size(512));
  ASSERT_EQ(whole.channels, 3);
  const Image im = picture(whole, 512, 512);
  // The legend shows every class's colour, and text (dark pixels that are not a swatch's).
  const Image key = legend(whole, 512);
  for (const ra::triage::Rgb8 c : {ra::triage::kBothColor, ra::triage::kPlatformOnlyColor,
                                  ra::triage::kReferenceOnlyColor, ra::triage::kForbiddenColor,
                                  ra::triage::kIdealColor})
    EXPECT_GT(pixels_with(key, c), 0);
  int text = 0;
  for (int y = 0; y < key.height; ++y)
    for (int x = 40; x < key.width; ++x) text += key.at(x, y).r < 128;
  EXPECT_GT(text, 200) << "no legend text";
  // Every lit pixel is a grey block; nothing is platform-only or reference-only on the reference.
  EXPECT_EQ(blocks_with(im, 8, ra::triage::kBothColor), rec.pixels);
  EXPECT_EQ(pixels_with(im, ra::triage::kPlatformOnlyColor), 0);
  EXPECT_EQ(pixels_with(im, ra::triage::kReferenceOnlyColor), 0);
  // A 1-px line cannot cover a block's 7 x 7 interior: every other block shows white.
  EXPECT_EQ(blocks_with(im, 8, ra::triage::kUnlitColor), 64 * 64 - rec.pixels);
  // The outline of a triangle lighting more than 10 pixels is longer than 3 window pixels.
  EXPECT_GT(pixels_with(im, ra::triage::kIdealColor), 3 * 8);
  // Blocks of 8 px carry a grid: a darker border.
  const ra::triage::Rgb8 b = ra::triage::kBothColor;
  EXPECT_GT(pixels_with(im, ra::triage::Rgb8{uint8_t(b.r * 4 / 5), uint8_t(b.g * 4 / 5),
                                            uint8_t(b.b * 4 / 5)}),
            0);
}

TEST(ShowCommand, PlatformOnlyAndReferenceOnlyPixelsHaveTheirColours) {
  // The faulty platform (reference base) draws every primitive one pixel to the right: each run
  // of a row gains a platform-only pixel at its right end and loses a reference pixel at its left.
  const std::string dir = fresh_dir("show_faulty");
  fs::create_directories(dir + "/run");
  write_text(dir + "/run/experiment.toml",
             experiment("\"faulty\"", "[faults]\nshift_fraction = 1.0\n"));
  // A triangle of some size away from the window's right edge, so no shifted pixel falls off.
  const ra::rundir::Experiment exp = ra::rundir::load_experiment(dir + "/run/experiment.toml");
  ra::geometry::PixelSet ref;
  uint64_t index = 0;
  for (; index < 20; ++index) {
    ref = ra::geometry::rasterize_reference(
        exp.views[0], ra::geometry::make_primitive(exp.seed, ra::geometry::Kind::kTriangle, index));
    bool inside = ref.size() >= 20;
    for (const ra::geometry::PixelRun& r : ref.runs()) inside = inside && r.x_end < 64;
    if (inside) break;
  }
  ASSERT_LT(index, 20u) << "no suitable triangle under this seed";
  const int64_t runs = int64_t(ref.runs().size());

  const Outcome o = run_renderaudit("show " + dir + "/run -p faulty -k triangle -v 1 -i " +
                                    std::to_string(index) + " --scale 4");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string png = dir + "/run/show/faulty.triangle.v1." + std::to_string(index) + ".png";
  const Image whole = read_image(png);
  ASSERT_GE(whole.width, ra::triage::kLegendMinWidth);  // widened for the legend's explanations
  const Image im = picture(whole, 256, 256);  // --scale 4 on the whole 64 x 64 window
  // Of the 2 x runs differing pixels, those GL forbids (centres beyond the snapping allowance of
  // every edge: metrics/conformance.h) are black where lit and hatched green where missing, the
  // others orange or blue.
  const int black = blocks_with(im, 4, ra::triage::kForbiddenColor) +
                    blocks_with(im, 4, ra::triage::kMissingColor);
  EXPECT_GT(black, 0);
  EXPECT_EQ(field(o.output, "violating_pixels"), std::to_string(black)) << o.output;
  EXPECT_EQ(field(o.output, "conformance"), "violation") << o.output;
  EXPECT_EQ(blocks_with(im, 4, ra::triage::kPlatformOnlyColor) + blocks_with(im, 4, ra::triage::kReferenceOnlyColor) +
                black,
            2 * runs);
  EXPECT_EQ(blocks_with(im, 4, ra::triage::kBothColor), ref.size() - runs);
  EXPECT_EQ(field(o.output, "ref_diff"), std::to_string(2 * runs)) << o.output;
  // The terminal gives the picture's legend: one count per colour.
  EXPECT_NE(o.output.find("  lit by both: " + ra::triage::pixels_text(ref.size() - runs) + "\n"),
            std::string::npos)
      << o.output;
  // The black and green blocks are the forbidden ones and the missing ones, each counted on its
  // own row.
  long long forbidden = -1, missing = -1;
  const std::size_t f = o.output.find("  forbidden by GL: "), m = o.output.find("  missing: ");
  ASSERT_NE(f, std::string::npos) << o.output;
  ASSERT_NE(m, std::string::npos) << o.output;
  ASSERT_EQ(std::sscanf(o.output.c_str() + f, "  forbidden by GL: %lld", &forbidden), 1);
  ASSERT_EQ(std::sscanf(o.output.c_str() + m, "  missing: %lld", &missing), 1);
  EXPECT_EQ(forbidden + missing, black) << o.output;
  EXPECT_EQ(o.output.find("black = pixels GL forbids"), std::string::npos) << o.output;
}

// The line of show's legend that starts with `start`, or "".
std::string legend_line(const std::string& output, const std::string& start) {
  const std::size_t at = output.find("\n  " + start);
  return at == std::string::npos ? "" : output.substr(at + 3, output.find('\n', at + 3) - at - 3);
}

// Why: the upgrade report set an installed and an upgraded picture side by side, each of its own
// window pixels and scale, and a few pixels apart they looked the same. Each drawn --against the
// other (the other in a child process), both show the same window pixels with the same inset
// around the pixels the two draw otherwise, and say how many those are.
TEST(ShowCommand, APairDrawnAgainstEachOtherInsetsTheSamePixels) {
  const std::string dir = fresh_dir("show_against");
  fs::create_directories(dir + "/run");
  // faulty (reference base) draws every primitive one pixel to the right; 128 x 128: at the
  // default scale of 4 px a pixel, an inset
  std::string toml = experiment("\"faulty\", \"reference\"", "[faults]\nshift_fraction = 1.0\n");
  toml.replace(toml.find("windows = [64]"), 14, "windows = [128]");
  write_text(dir + "/run/experiment.toml", toml);
  const ra::rundir::Experiment exp = ra::rundir::load_experiment(dir + "/run/experiment.toml");
  uint64_t index = 0;
  ra::geometry::PixelSet ref;
  for (; index < 20; ++index) {
    ref = ra::geometry::rasterize_reference(
        exp.views[0], ra::geometry::make_primitive(exp.seed, ra::geometry::Kind::kTriangle, index));
    bool inside = ref.size() >= 20;
    for (const ra::geometry::PixelRun& r : ref.runs()) inside = inside && r.x_end < 128;
    if (inside) break;
  }
  ASSERT_LT(index, 20u) << "no suitable triangle under this seed";
  const std::string args = " -k triangle -v 1 -i " + std::to_string(index);
  const Outcome a = run_renderaudit("show " + dir + "/run -p faulty --against reference" + args +
                                    " -o " + dir + "/a.png");
  const Outcome b = run_renderaudit("show " + dir + "/run -p reference --against faulty" + args +
                                    " -o " + dir + "/b.png");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  // each row's run moved one pixel: its left end lost, a pixel past its right end gained
  const std::string n = ra::triage::pixels_text(2 * int64_t(ref.runs().size()));
  EXPECT_EQ(legend_line(a.output, "drawn otherwise"),
            "drawn otherwise by reference: " + n + " (dotted in the inset)")
      << a.output;
  EXPECT_EQ(legend_line(b.output, "drawn otherwise"),
            "drawn otherwise by faulty: " + n + " (dotted in the inset)")
      << b.output;
  const std::string framed = legend_line(a.output, "framed: window pixels");
  EXPECT_NE(framed, "") << a.output;
  EXPECT_EQ(framed, legend_line(b.output, "framed: window pixels")) << b.output;
  // the same window pixels at the same scale
  const std::string shown_a = a.output.substr(a.output.find("window pixels x "), 60);
  EXPECT_EQ(shown_a, b.output.substr(b.output.find("window pixels x "), 60));
  // the inset's dots in both PNGs, under the picture
  for (const std::string& png : {dir + "/a.png", dir + "/b.png"}) {
    const Image im = read_image(png);
    EXPECT_GT(pixels_with(legend(im, 512), ra::triage::kMarkerColor), 0) << png;
  }
  // a platform against itself says so
  const Outcome self = run_renderaudit("show " + dir + "/run -p faulty --against faulty" + args);
  EXPECT_EQ(self.exit_code, 2) << self.output;
  EXPECT_NE(self.output.find("--against faulty is the platform drawn"), std::string::npos)
      << self.output;
}

TEST(ShowCommand, BadRequestsSayWhatIsAllowed) {
  const std::string run = reference_run();
  const std::string base = "show " + run + " ";
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"-p swrast -k triangle -v 1 -i 0", "unknown platform 'swrast' (allowed: osmesa-llvmpipe, "},
      {"-p reference -k quad -v 1 -i 0", "unknown kind 'quad' (allowed: point, line, triangle)"},
      {"-p reference -k triangle -v 2 -i 0",
       "view 2 out of range (allowed: 1 to 1: " + run + "/experiment.toml has 1 view)"},
      {"-p reference -k triangle -v 1 -i 20", "index 20 out of range (allowed: 0 to 19: " + run +
                                                  "/experiment.toml has 20 triangles per view)"},
  };
  for (const Case& c : cases) {
    const Outcome o = run_renderaudit(base + c.args);
    EXPECT_EQ(o.exit_code, 2) << c.args << "\n" << o.output;
    EXPECT_NE(o.output.find("renderaudit: " + c.message), std::string::npos) << o.output;
  }
  // an index is read as written: -1 and a number past 2^64 - 1 do not wrap to 2^64 - 1
  for (const std::string index : {"-1", "18446744073709551616", "1e3", "0x10", "''"}) {
    const Outcome o = run_renderaudit(base + "-p reference -k triangle -v 1 -i " + index);
    EXPECT_EQ(o.exit_code, 2) << index << "\n" << o.output;
    EXPECT_NE(o.output.find(": not a primitive index (allowed: a whole number from 0"),
              std::string::npos)
        << index << "\n" << o.output;
    EXPECT_EQ(o.output.find("18446744073709551615 out of range"), std::string::npos) << o.output;
  }
  const std::string missing = fresh_dir("show_missing") + "/nothing";
  const Outcome o = run_renderaudit("show " + missing + " -p reference -k point -v 1 -i 0");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("renderaudit: " + missing + ": not a run directory (no experiment.toml)"),
            std::string::npos)
      << o.output;
}

}  // namespace
