#pragma once
/// Charts and heat maps as PNG, drawn with VTK's 2D chart classes (vtkChartXY,
/// vtkChartHistogram2D) in an offscreen render window (offscreen_display.h: starts Xvfb when
/// there is no X display).
#include <filesystem>
#include <string>
#include <vector>

namespace rad {

/// One curve: points (x[i], y[i]) joined in order, with markers.
struct ChartSeries {
  std::string name;
  std::vector<double> x, y;
};

struct LineChart {
  std::string title, x_label, y_label;
  bool log_x = false,
       log_y = false;  ///< Points with a non-positive coordinate on a log axis are left out.
  std::vector<ChartSeries> series;
  int width = 900, height = 600;
  /// Where the legend goes, inside the plot: pick the corner the curves leave empty.
  enum class Corner { top_left, top_right, bottom_left, bottom_right } legend = Corner::top_right;
};

/// Draws the chart and writes it as an RGB PNG of width x height pixels, atomically. Series
/// with no drawable point are left out (a chart with none still gets its axes). Throws Error.
void write_chart_png(const std::filesystem::path& file, const LineChart& chart);

/// A scalar image as a heat map: `values` row by row from the top, width x height, coloured
/// from 0 (dark blue) to `max_value` (dark red; larger values are clamped; NaN is grey), with
/// a colour bar titled `legend`, axes in pixels and a title. The PNG is `scale` times the image
/// in each direction plus room for the colour bar and labels. Throws Error.
struct HeatMap {
  int width = 0, height = 0;
  std::vector<double> values;
  double max_value = 1;
  std::string title, legend;
};
void write_heat_map_png(const std::filesystem::path& file, const HeatMap& map);

/// The PNG size write_heat_map_png gives `map` (for callers and tests).
std::pair<int, int> heat_map_png_size(const HeatMap& map);

}  // namespace rad
