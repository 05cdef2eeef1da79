// Height files through OpenImageIO: a float TIFF and a 16-bit PNG written here are read back with
// the right orientation and scale; NaN heights, extra channels and too-small grids are refused
// with the file named; cropping keeps whole tiles from the south-west corner.
#include "terrain_lod/height_field.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "util/errors.h"

namespace ra::lod {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("ra-height-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

// Writes `values` (row 0 = the northern edge, as images are stored) as a width x height image.
void write_image(const std::string& path, int width, int height, int channels, OIIO::TypeDesc type,
                 const std::vector<float>& values) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  const OIIO::ImageSpec spec(width, height, channels, type);
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data())) << out->geterror();
  out->close();
}

std::string error_of(const std::string& path) {
  try {
    read_height_file(path, 10, 1);
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(HeightFile, FloatTiffIsReadNorthUpAndScaled) {
  const int w = 5, h = 3;
  std::vector<float> v(w * h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) v[r * w + c] = float(100 * r + c) + 0.25f;  // row r, column c
  const std::string path = temp_path("heights.tif");
  write_image(path, w, h, 1, OIIO::TypeDesc::FLOAT, v);
  const HeightField f = read_height_file(path, 30, 2);
  EXPECT_EQ(f.nx, 5);
  EXPECT_EQ(f.ny, 3);
  EXPECT_EQ(f.spacing, 30);
  // file row 0 (north) is j = ny - 1; heights are value x height_scale
  EXPECT_DOUBLE_EQ(f.at(0, 2), 2 * 0.25);
  EXPECT_DOUBLE_EQ(f.at(4, 2), 2 * 4.25);
  EXPECT_DOUBLE_EQ(f.at(3, 0), 2 * 203.25);
  EXPECT_NE(f.source.find("float heights"), std::string::npos) << f.source;
  fs::remove(path);
}

TEST(HeightFile, SixteenBitPngIsNormalised) {
  const std::string path = temp_path("heights.png");
  // 0, 1/2 (rounded to 16 bits) and 1 of the full range
  write_image(path, 3, 1, 1, OIIO::TypeDesc::UINT16, {0.0f, 0.5f, 1.0f});
  const HeightField f = read_height_file(path, 1, 1000);
  ASSERT_EQ(f.nx, 3);
  EXPECT_DOUBLE_EQ(f.at(0, 0), 0);
  EXPECT_NEAR(f.at(1, 0), 500, 1000.0 / 65535);
  EXPECT_NEAR(f.at(2, 0), 1000, 1e-9);
  fs::remove(path);
}

TEST(HeightFile, BadFilesAreNamed) {
  const std::string nan_path = temp_path("nan.tif");
  write_image(nan_path, 3, 2, 1, OIIO::TypeDesc::FLOAT,
              {1, 2, 3, 4, std::numeric_limits<float>::quiet_NaN(), 6});
  EXPECT_EQ(error_of(nan_path), nan_path + ": pixel (1, 1) is nan: heights must be finite numbers");
  const std::string inf_path = temp_path("inf.tif");
  write_image(inf_path, 2, 1, 1, OIIO::TypeDesc::FLOAT, {std::numeric_limits<float>::infinity(), 0});
  EXPECT_EQ(error_of(inf_path), inf_path + ": pixel (0, 0) is infinite: heights must be finite numbers");
  const std::string rgb_path = temp_path("rgb.png");
  write_image(rgb_path, 1, 1, 3, OIIO::TypeDesc::UINT8, {0, 0, 0});
  EXPECT_EQ(error_of(rgb_path), rgb_path + ": a height file needs exactly one channel, this one has 3");
  EXPECT_EQ(error_of(temp_path("missing.tif")).rfind(temp_path("missing.tif") + ": cannot read", 0), 0u);
  for (const std::string& p : {nan_path, inf_path, rgb_path}) fs::remove(p);
}

TEST(HeightFile, CropKeepsWholeTilesFromTheSouthWest) {
  HeightField f;
  f.nx = 40;
  f.ny = 20;
  f.spacing = 5;
  f.source = "grid";
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) f.z.push_back(1000.0 * j + i);
  const HeightField c = crop_to_tiles(f, 17, 0, 0);  // tiles of 16 cells: 2 x 1 fit
  EXPECT_EQ(c.nx, 33);
  EXPECT_EQ(c.ny, 17);
  EXPECT_DOUBLE_EQ(c.at(32, 16), 16032);
  EXPECT_NE(c.source.find("cropped from 40 x 20 to 33 x 17 vertices (2 x 1 tiles)"), std::string::npos)
      << c.source;
  EXPECT_EQ(crop_to_tiles(f, 17, 1, 1).nx, 17);
  try {
    crop_to_tiles(f, 257, 0, 0);
    FAIL() << "no error";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()), "grid is 40 x 20 vertices: a tile needs 257 x 257");
  }
}

}  // namespace
}  // namespace ra::lod
