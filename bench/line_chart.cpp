// A line chart from a CSV, for the benchmark scripts that measure with the command line:
//
//   line_chart CHART.png DATA.csv TITLE X_LABEL Y_LABEL [log]
//
// DATA.csv: a header, then rows "series,x,y"; each series' points are joined in file order.
// "log" puts both axes on log scales.
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include "viz/charts.h"

int main(int argc, char** argv) {
  if (argc < 6) {
    std::cerr << "usage: line_chart CHART.png DATA.csv TITLE X_LABEL Y_LABEL [log]\n";
    return 1;
  }
  try {
    std::ifstream in(argv[2]);
    if (!in) {
      std::cerr << "line_chart: cannot read " << argv[2] << "\n";
      return 1;
    }
    rad::LineChart chart;
    chart.title = argv[3];
    chart.x_label = argv[4];
    chart.y_label = argv[5];
    chart.log_x = chart.log_y = argc > 6 && std::string(argv[6]) == "log";
    chart.legend = rad::LineChart::Corner::top_left;
    std::map<std::string, size_t> index;
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      std::string name, x, y;
      if (!std::getline(fields, name, ',') || !std::getline(fields, x, ',') ||
          !std::getline(fields, y, ',')) {
        std::cerr << "line_chart: " << argv[2] << ": not series,x,y: " << line << "\n";
        return 1;
      }
      if (!index.count(name)) {
        index[name] = chart.series.size();
        chart.series.push_back({name, {}, {}});
      }
      chart.series[index[name]].x.push_back(std::stod(x));
      chart.series[index[name]].y.push_back(std::stod(y));
    }
    rad::write_chart_png(argv[1], chart);
  } catch (const std::exception& e) {
    std::cerr << "line_chart: " << argv[2] << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
