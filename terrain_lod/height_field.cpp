// Height fields of the terrain LOD study (height_field.h).
#include "terrain_lod/height_field.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <memory>

#include "util/errors.h"

namespace ra::lod {
namespace {

// An nx x ny field `spacing` apart whose vertex (i, j) is height(i, j); no source named yet.
template <typename Height>
HeightField sampled_field(int nx, int ny, double spacing, const Height& height) {
  HeightField f;
  f.nx = nx;
  f.ny = ny;
  f.spacing = spacing;
  f.z.resize(static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) f.z[static_cast<size_t>(j) * nx + i] = height(i, j);
  return f;
}

}  // namespace

HeightField generate_height_field(const scenes::TerrainParams& params, int nx, int ny) {
  scenes::TerrainParams p = params;
  p.size = 2;  // validate() checks size; ours is nx, ny
  scenes::validate(p);
  HeightField f = sampled_field(nx, ny, p.spacing, [&](int i, int j) {
    return scenes::terrain_height(p, i * p.spacing, j * p.spacing);
  });
  f.source = "generated terrain (seed " + std::to_string(p.seed) + ")";
  return f;
}

HeightField read_height_file(const std::string& path, double spacing, double height_scale) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw util::UserError(path + ": cannot read the height file (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec spec = in->spec();
  if (spec.nchannels != 1)
    throw util::UserError(path + ": a height file needs exactly one channel, this one has " +
                          std::to_string(spec.nchannels));
  const bool is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                        spec.format.basetype == OIIO::TypeDesc::DOUBLE ||
                        spec.format.basetype == OIIO::TypeDesc::HALF;
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height);
  // integer formats arrive normalised to [0, 1] (OIIO's convention), floats as stored
  if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw util::UserError(path + ": cannot read the height file (" + in->geterror() + ")");
  HeightField f;
  f.nx = spec.width;
  f.ny = spec.height;
  f.spacing = spacing;
  f.z.resize(pixels.size());
  for (int r = 0; r < spec.height; ++r)
    for (int c = 0; c < spec.width; ++c) {
      const float v = pixels[static_cast<size_t>(r) * spec.width + c];
      if (!std::isfinite(v))
        throw util::UserError(path + ": pixel (" + std::to_string(c) + ", " + std::to_string(r) +
                              ") is " + (std::isnan(v) ? "nan" : "infinite") +
                              ": heights must be finite numbers");
      f.z[static_cast<size_t>(spec.height - 1 - r) * f.nx + c] = double(v) * height_scale;
    }
  f.source = path + (is_float ? " (float heights" : " (integer heights, normalised") + ", x " +
             std::to_string(height_scale) + " m)";
  return f;
}

HeightField crop_to_tiles(const HeightField& field, int tile_size, int max_tiles_x, int max_tiles_y) {
  const int cells = tile_size - 1;
  int tx = (field.nx - 1) / cells, ty = (field.ny - 1) / cells;
  if (max_tiles_x > 0 && tx > max_tiles_x) tx = max_tiles_x;
  if (max_tiles_y > 0 && ty > max_tiles_y) ty = max_tiles_y;
  if (tx < 1 || ty < 1)
    throw util::UserError(field.source + " is " + std::to_string(field.nx) + " x " +
                          std::to_string(field.ny) + " vertices: a tile needs " +
                          std::to_string(tile_size) + " x " + std::to_string(tile_size));
  const int nx = tx * cells + 1, ny = ty * cells + 1;
  if (nx == field.nx && ny == field.ny) return field;
  HeightField out =
      sampled_field(nx, ny, field.spacing, [&](int i, int j) { return field.at(i, j); });
  out.source = field.source + ", cropped from " + std::to_string(field.nx) + " x " +
               std::to_string(field.ny) + " to " + std::to_string(nx) + " x " + std::to_string(ny) +
               " vertices (" + std::to_string(tx) + " x " + std::to_string(ty) + " tiles)";
  return out;
}

}  // namespace ra::lod
