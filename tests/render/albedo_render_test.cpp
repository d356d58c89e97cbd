#include "render/albedo_render.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "scene/scene_loader.h"

namespace rad {
namespace {

class CornellAlbedo : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = load_scene(std::filesystem::path(RAD_SOURCE_DIR) / "data/cornell-box/scene.json");
    spec_ = *scene_.camera;
    spec_.width = spec_.height = 64;
  }
  Rgb reflectance(const std::string& name) const {
    for (const Material& m : scene_.materials) {
      if (m.name == name) return m.reflectance;
    }
    ADD_FAILURE() << "no material " << name;
    return Rgb::Zero();
  }
  Scene scene_;
  CameraSpec spec_;
};

TEST_F(CornellAlbedo, ShowsWallsLightAndBlocksWhereThePublishedViewHasThem) {
  const RayCaster caster(scene_);
  const Image image = render_albedo(caster, Camera(spec_));
  ASSERT_EQ(image.width, 64);
  // Left edge, middle row: the red wall (x = 556 is on the image's left).
  EXPECT_EQ(image.at(1, 32), reflectance("red"));
  EXPECT_EQ(image.at(62, 32), reflectance("green"));
  // Top centre, a little down: the light shows its emission.
  const Material& light =
      scene_.materials[scene_.polygons[scene_.objects[2].first_polygon].material];
  ASSERT_TRUE(light.is_emitter());
  EXPECT_EQ(image.at(32, 9), light.emission);  // the light spans rows 8 to 10 at 64 px
  // Centre: the back wall or a block, all white.
  EXPECT_EQ(image.at(32, 32), reflectance("white"));
}

TEST_F(CornellAlbedo, FacingShadingDarkensObliqueSurfaces) {
  const RayCaster caster(scene_);
  const Image image = render_facing(caster, Camera(spec_));
  const Rgb red = reflectance("red");
  // The red wall is seen at a grazing angle from the camera: |cos| well below 1.
  EXPECT_LT(image.at(1, 32).x(), 0.7 * red.x());
  EXPECT_GT(image.at(1, 32).x(), 0.1 * red.x());
}

TEST_F(CornellAlbedo, DoesNotDependOnThreadCount) {
  const RayCaster caster(scene_);
  Image one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_facing(caster, Camera(spec_));
  }
  many = render_facing(caster, Camera(spec_));
  ASSERT_EQ(one.pixels.size(), many.pixels.size());
  for (size_t i = 0; i < one.pixels.size(); ++i) ASSERT_EQ(one.pixels[i], many.pixels[i]) << i;
}

}  // namespace
}  // namespace rad
