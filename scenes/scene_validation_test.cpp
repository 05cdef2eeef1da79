// The invariant checker catches each kind of broken scene.
#include "scenes/scene_validation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scenes/procedural_texture.h"
#include "scenes/strip_builder.h"

namespace ra::scenes {
namespace {

Scene good() {
  Scene s;
  s.kind = "test";
  s.textures.push_back(make_texture(TexturePattern::kGround, 1, 0, 2));
  SceneObject o;
  add_grid(o.mesh, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}, 2, 2, 0, 0, 1, 0, 1);
  o.bounds = enclosing_sphere(o.mesh);
  s.objects.push_back(o);
  s.layout.box_max = {4, 4, 0};
  return s;
}

bool mentions(const std::vector<std::string>& problems, const std::string& what) {
  for (const auto& p : problems)
    if (p.find(what) != std::string::npos) return true;
  return false;
}

TEST(SceneValidation, FindsEachProblem) {
  EXPECT_TRUE(scene_problems(good()).empty());
  Scene s = good();
  s.objects[0].mesh.strips[0].indices[2] = 99;
  EXPECT_TRUE(mentions(scene_problems(s), "index 99 >= 9 vertices"));
  s = good();
  s.objects[0].mesh.positions[4] = std::nanf("");
  EXPECT_TRUE(mentions(scene_problems(s), "a position is not finite"));
  s = good();
  s.objects[0].mesh.strips[1].texture = 1;
  EXPECT_TRUE(mentions(scene_problems(s), "uses texture 1 of 1"));
  s = good();
  s.objects[0].bounds.radius *= 0.9;
  EXPECT_TRUE(mentions(scene_problems(s), "outside the bounding sphere"));
  s = good();
  s.layout.box_max.x = 3;
  EXPECT_TRUE(mentions(scene_problems(s), "outside the layout box"));
  s = good();
  s.textures[0].rgba.pop_back();
  EXPECT_TRUE(mentions(scene_problems(s), "texture 0: 15 bytes for 2 x 2 texels"));
  s = good();
  s.objects[0].mesh.texcoords.pop_back();
  EXPECT_TRUE(mentions(scene_problems(s), "17 texture coordinates for 9 vertices"));
}

TEST(SceneValidation, TexturesAreSeededAndDistinct) {
  const Texture a = make_texture(TexturePattern::kFacade, 1, 2, 16);
  EXPECT_EQ(a.width, 16);
  EXPECT_EQ(a.height, 16);
  EXPECT_EQ(a.rgba.size(), 16u * 16 * 4);
  EXPECT_EQ(a.rgba, make_texture(TexturePattern::kFacade, 1, 2, 16).rgba);
  EXPECT_NE(a.rgba, make_texture(TexturePattern::kFacade, 1, 3, 16).rgba);
  EXPECT_NE(a.rgba, make_texture(TexturePattern::kFacade, 2, 2, 16).rgba);
  for (size_t i = 3; i < a.rgba.size(); i += 4) EXPECT_EQ(a.rgba[i], 255);  // opaque
  EXPECT_THROW(make_texture(TexturePattern::kRoof, 1, 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace ra::scenes
