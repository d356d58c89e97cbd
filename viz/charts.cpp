#include "viz/charts.h"

#include <vtkAxis.h>
#include <vtkChartHistogram2D.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkColorLegend.h>
#include <vtkColorTransferFunction.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

#include "scene/error.h"
#include "viz/offscreen_display.h"

namespace rad {
namespace {

/// Colour-blind-safe line colours (Okabe and Ito 2008), cycled.
constexpr unsigned char kPalette[][3] = {{0, 114, 178},   {213, 94, 0},  {0, 158, 115},
                                         {204, 121, 167}, {230, 159, 0}, {86, 180, 233},
                                         {0, 0, 0},       {240, 228, 66}};

/// Renders the view offscreen at width x height on white and writes the frame as a PNG.
void write_view_png(const std::filesystem::path& file, vtkContextView* view, int width,
                    int height) {
  vtkRenderWindow* window = view->GetRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  view->GetRenderer()->SetBackground(1, 1, 1);
  write_window_png(file, window);
}

void style_axis(vtkAxis* axis, const std::string& title, bool log) {
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(16);
  axis->GetLabelProperties()->SetFontSize(13);
  if (log) axis->SetLogScale(true);
}

}  // namespace

void write_chart_png(const std::filesystem::path& file, const LineChart& chart) {
  ensure_display();
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartXY> xy;
  view->GetScene()->AddItem(xy);
  xy->SetTitle(chart.title);
  xy->GetTitleProperties()->SetFontSize(18);
  style_axis(xy->GetAxis(vtkAxis::BOTTOM), chart.x_label, chart.log_x);
  style_axis(xy->GetAxis(vtkAxis::LEFT), chart.y_label, chart.log_y);
  xy->SetShowLegend(true);
  const bool left =
      chart.legend == LineChart::Corner::top_left || chart.legend == LineChart::Corner::bottom_left;
  const bool top =
      chart.legend == LineChart::Corner::top_left || chart.legend == LineChart::Corner::top_right;
  xy->GetLegend()->SetHorizontalAlignment(left ? vtkChartLegend::LEFT : vtkChartLegend::RIGHT);
  xy->GetLegend()->SetVerticalAlignment(top ? vtkChartLegend::TOP : vtkChartLegend::BOTTOM);
  xy->GetLegend()->GetLabelProperties()->SetFontSize(14);

  // The tables must outlive the render: the plots keep references.
  std::vector<vtkSmartPointer<vtkTable>> tables;
  int drawn = 0;
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const ChartSeries& series = chart.series[s];
    vtkNew<vtkDoubleArray> xs, ys;
    xs->SetName(chart.x_label.c_str());
    ys->SetName(series.name.c_str());
    for (size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i) {
      const double x = series.x[i], y = series.y[i];
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      if ((chart.log_x && x <= 0) || (chart.log_y && y <= 0)) continue;
      xs->InsertNextValue(x);
      ys->InsertNextValue(y);
    }
    if (xs->GetNumberOfTuples() == 0) continue;
    auto table = vtkSmartPointer<vtkTable>::New();
    table->AddColumn(xs);
    table->AddColumn(ys);
    tables.push_back(table);
    // A single point gets a marker alone (VTK refuses a line through fewer than 2 points).
    vtkPlot* line = xy->AddPlot(xs->GetNumberOfTuples() >= 2 ? vtkChart::LINE : vtkChart::POINTS);
    line->SetInputData(table, 0, 1);
    line->SetLabel(series.name);
    const unsigned char* rgb = kPalette[drawn % std::size(kPalette)];
    line->SetColor(rgb[0], rgb[1], rgb[2], 255);
    line->SetWidth(2.5);
    if (auto* points = vtkPlotPoints::SafeDownCast(line)) {
      points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      points->SetMarkerSize(8);
    }
    ++drawn;
  }
  write_view_png(file, view, chart.width, chart.height);
}

std::pair<int, int> heat_map_png_size(const HeatMap& map) {
  // At least ~480 pixels for the image itself, plus margins for the axes and the colour bar.
  const int scale = std::max(
      1, static_cast<int>(std::ceil(480.0 / std::max(1, std::max(map.width, map.height)))));
  return {map.width * scale + 260, map.height * scale + 120};
}

void write_heat_map_png(const std::filesystem::path& file, const HeatMap& map) {
  if (map.width <= 0 || map.height <= 0 ||
      map.values.size() != static_cast<size_t>(map.width) * map.height) {
    throw Error(file.string() + ": heat map has no pixels");
  }
  ensure_display();
  vtkNew<vtkImageData> image;
  image->SetDimensions(map.width, map.height, 1);
  image->AllocateScalars(VTK_DOUBLE, 1);
  auto* values = static_cast<double*>(image->GetScalarPointer());
  const double top = map.max_value > 0 ? map.max_value : 1;
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      // VTK's image row 0 is the bottom row.
      const double v = map.values[static_cast<size_t>(y) * map.width + x];
      values[static_cast<size_t>(map.height - 1 - y) * map.width + x] =
          std::isnan(v) ? v : std::min(v, top);
    }
  }
  // A perceptually ordered ramp: dark blue, cyan, yellow, dark red.
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(0.0, 0.05, 0.05, 0.35);
  colours->AddRGBPoint(0.33 * top, 0.0, 0.65, 0.85);
  colours->AddRGBPoint(0.67 * top, 0.98, 0.85, 0.1);
  colours->AddRGBPoint(top, 0.6, 0.0, 0.0);
  colours->SetNanColor(0.6, 0.6, 0.6);
  colours->ClampingOn();

  vtkNew<vtkContextView> view;
  vtkNew<vtkChartHistogram2D> chart;
  view->GetScene()->AddItem(chart);
  chart->SetInputData(image);
  chart->SetTransferFunction(colours);
  chart->SetTitle(map.title);
  chart->GetTitleProperties()->SetFontSize(16);
  style_axis(chart->GetAxis(vtkAxis::BOTTOM), "x (pixels)", false);
  style_axis(chart->GetAxis(vtkAxis::LEFT), "y (pixels from the bottom)", false);
  if (auto* legend = vtkColorLegend::SafeDownCast(chart->GetLegend())) {
    legend->SetTitle(map.legend);
    legend->GetLabelProperties()->SetFontSize(12);
  }
  const auto [width, height] = heat_map_png_size(map);
  write_view_png(file, view, width, height);
}

}  // namespace rad
