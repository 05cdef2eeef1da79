// Test support: a figure file is checked for what it must hold, not only for existing. A PNG must
// decode (OpenImageIO) to a plausible size with something drawn on it (a share of pixels that are
// not the background); a PDF must be a whole PDF document of plausible size.
#pragma once

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace ra::plots::testing {

inline void expect_drawn_png(const std::string& path) {
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  OIIO::ImageBuf image(path);
  ASSERT_TRUE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << path << ": " << image.geterror();
  const OIIO::ImageSpec& spec = image.spec();
  EXPECT_GE(spec.width, 300) << path;
  EXPECT_GE(spec.height, 200) << path;
  // The background is the colour of the top-left pixel; a drawn figure differs from it in at
  // least 1% of its pixels (axes, labels, bars, markers).
  std::vector<float> corner(spec.nchannels), pixel(spec.nchannels);
  image.getpixel(0, 0, corner.data());
  long differing = 0;
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      image.getpixel(x, y, pixel.data());
      for (int c = 0; c < std::min(spec.nchannels, 3); ++c)
        if (std::abs(pixel[c] - corner[c]) > 0.05f) {
          ++differing;
          break;
        }
    }
  EXPECT_GT(double(differing), 0.01 * spec.width * spec.height) << path << ": nearly blank";
}

inline void expect_whole_pdf(const std::string& path) {
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text.rfind("%PDF-", 0), 0u) << path;
  EXPECT_NE(text.find("%%EOF", text.size() > 1024 ? text.size() - 1024 : 0), std::string::npos)
      << path << ": no end-of-file marker (cut short?)";
  EXPECT_GT(text.size(), 2000u) << path;
}

}  // namespace ra::plots::testing
