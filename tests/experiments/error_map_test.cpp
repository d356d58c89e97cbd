// Error maps and charts: the relative error statistics against values worked by hand, and the
// PNGs (charts, heat maps) read back with VTK's reader: size and more than one colour.
#include "experiments/error_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "formats/image_io.h"
#include "scene/error.h"
#include "tests/scratch_dir.h"
#include "tests/viz/png_inspect.h"
#include "viz/charts.h"
#include "viz/error_heat_map.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

TEST(ErrorMap, RelativeErrorOnTheBrightestChannelByHand) {
  Image reference(2, 2), image(2, 2);
  reference.pixels = {Rgb(1, 2, 4), Rgb(1, 1, 1), Rgb(0, 0, 0), Rgb(2, 0, 0)};
  image.pixels = {Rgb(1.2, 2, 4), Rgb(1, 1, 0.5), Rgb(5, 5, 5), Rgb(2, 0, 0)};
  const ErrorMap map = relative_error_map(image, reference);
  // Pixel 0: |0.2| / 4 = 0.05; pixel 1: 0.5 / 1; pixel 2: reference 0, not compared; pixel 3: 0.
  ASSERT_EQ(map.relative.size(), 4u);
  EXPECT_DOUBLE_EQ(map.relative[0], 0.05);
  EXPECT_DOUBLE_EQ(map.relative[1], 0.5);
  EXPECT_TRUE(std::isnan(map.relative[2]));
  EXPECT_DOUBLE_EQ(map.relative[3], 0.0);
  EXPECT_EQ(map.stats.pixels, 3u);
  EXPECT_EQ(map.stats.skipped, 1u);
  EXPECT_DOUBLE_EQ(map.stats.max, 0.5);
  EXPECT_DOUBLE_EQ(map.stats.mean, 0.55 / 3);
  EXPECT_DOUBLE_EQ(map.stats.rms, std::sqrt((0.05 * 0.05 + 0.25) / 3));
}

TEST(ErrorMap, AFloorLeavesOutTheDarkPixelsByHand) {
  // Brightest channels 4, 1, 0, 2: their mean over the positive ones is 7 / 3. A floor of 0.5
  // (7 / 6) leaves out pixel 1 (1 <= 7 / 6) besides pixel 2 (0).
  Image reference(2, 2), image(2, 2);
  reference.pixels = {Rgb(1, 2, 4), Rgb(1, 1, 1), Rgb(0, 0, 0), Rgb(2, 0, 0)};
  image.pixels = {Rgb(1.2, 2, 4), Rgb(1, 1, 0.5), Rgb(5, 5, 5), Rgb(2, 0, 0)};
  const ErrorMap map = relative_error_map(image, reference, 0.5);
  EXPECT_TRUE(std::isnan(map.relative[1]));
  EXPECT_EQ(map.stats.pixels, 2u);
  EXPECT_EQ(map.stats.skipped, 2u);
  EXPECT_DOUBLE_EQ(map.stats.mean, 0.025);
}

TEST(ErrorMap, NanInTheImageIsAnInfiniteErrorAndSizesMustMatch) {
  Image reference(1, 1), image(1, 1);
  reference.pixels[0] = Rgb(1, 1, 1);
  image.pixels[0] = Rgb(std::numeric_limits<double>::quiet_NaN(), 1, 1);
  EXPECT_TRUE(std::isinf(relative_error_map(image, reference).stats.max));
  EXPECT_THROW(relative_error_map(Image(2, 1), reference), Error);
}

TEST(ErrorMap, WritesTheMapAsExrAndAHeatMapWithAColourBar) {
  const fs::path dir = test::scratch_dir("viz_heat_map");
  Image reference(40, 30), image(40, 30);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      reference.at(x, y) = Rgb::Constant(1.0);
      image.at(x, y) = Rgb::Constant(1.0 + 0.01 * x);  // error grows to the right
    }
  }
  const ErrorMap map = relative_error_map(image, reference);
  write_error_map_exr(dir / "map.exr", map);
  write_error_heat_map(dir / "map.png", map, "test map");
  const Image back = read_exr(dir / "map.exr");
  ASSERT_EQ(back.width, 40);
  ASSERT_EQ(back.height, 30);
  EXPECT_NEAR(back.at(39, 5).x(), 0.39, 1e-6);
  EXPECT_NEAR(back.at(0, 5).x(), 0.0, 1e-12);
  const test::PngSummary png = test::inspect_png(dir / "map.png");
  HeatMap heat;
  heat.width = 40;
  heat.height = 30;
  const auto [width, height] = heat_map_png_size(heat);
  EXPECT_EQ(png.width, width);
  EXPECT_EQ(png.height, height);
  // The ramp has 40 error levels; with the colour bar, axes and text, many colours.
  EXPECT_GT(png.colours, 40u);
}

TEST(Charts, LineChartPngHasTheRequestedSizeAndItsCurves) {
  const fs::path dir = test::scratch_dir("viz_chart");
  LineChart chart;
  chart.title = "test";
  chart.x_label = "x";
  chart.y_label = "y";
  chart.log_x = chart.log_y = true;
  chart.width = 640;
  chart.height = 480;
  chart.series = {{"a", {0.0, 0.1, 1, 10}, {5, 1, 0.1, 0.01}}, {"b", {1, 2, 3}, {1, 2, 3}}};
  write_chart_png(dir / "chart.png", chart);
  const test::PngSummary png = test::inspect_png(dir / "chart.png");
  EXPECT_EQ(png.width, 640);
  EXPECT_EQ(png.height, 480);
  EXPECT_GT(png.colours, 2u);
  // Nothing drawable (non-positive values on log axes) still gives a chart with its axes.
  chart.series = {{"c", {0.0}, {-1.0}}};
  write_chart_png(dir / "empty.png", chart);
  EXPECT_EQ(test::inspect_png(dir / "empty.png").width, 640);
}

}  // namespace
}  // namespace rad
