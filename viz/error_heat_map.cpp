#include "viz/error_heat_map.h"

#include <cmath>

#include "viz/charts.h"

namespace rad {

void write_error_heat_map(const std::filesystem::path& png, const ErrorMap& map,
                          const std::string& title, double max_value) {
  HeatMap heat;
  heat.width = map.width;
  heat.height = map.height;
  heat.values = map.relative;
  double top = max_value > 0 ? max_value : map.stats.max;
  if (!(top > 0) || !std::isfinite(top)) top = 1;
  heat.max_value = top;
  heat.title = title;
  heat.legend = "relative error";
  write_heat_map_png(png, heat);
}

}  // namespace rad
