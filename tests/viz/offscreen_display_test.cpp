// The private X display: with $DISPLAY naming a server that is not there (as on CI, or after an
// ssh session ended), ensure_display() starts Xvfb and points $DISPLAY at it, and VTK renders.
#include "viz/offscreen_display.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "tests/scratch_dir.h"
#include "tests/viz/png_inspect.h"
#include "viz/charts.h"

namespace rad {
namespace {

TEST(OffscreenDisplay, ReplacesADeadDisplayWithAPrivateXvfb) {
  for (const char* dead : {":54321", ""}) {
    setenv("DISPLAY", dead, 1);
    ensure_display();
    const std::string display = std::getenv("DISPLAY");
    EXPECT_NE(display, dead);
    EXPECT_EQ(display.front(), ':') << display;
  }
  // What it set up renders: a chart of the requested size.
  const auto dir = test::scratch_dir("viz_offscreen");
  LineChart chart;
  chart.width = 320;
  chart.height = 200;
  chart.series = {{"a", {1, 2}, {1, 2}}};
  write_chart_png(dir / "chart.png", chart);
  EXPECT_EQ(test::inspect_png(dir / "chart.png").width, 320);
}

}  // namespace
}  // namespace rad
