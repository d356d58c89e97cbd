#include "experiments/global_accuracy.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "scene/error.h"

namespace rad {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

/// The labels of the points file's rows, in order: the last comment line above each row.
std::vector<std::string> row_labels(const std::filesystem::path& points) {
  std::ifstream in(points);
  std::vector<std::string> labels;
  std::string line, comment;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      comment = line.substr(line.find_first_not_of("# ") == std::string::npos
                                ? line.size()
                                : line.find_first_not_of("# "));
      continue;
    }
    if (header) {  // the header row (read_points_csv has checked the file)
      header = false;
      if (!std::isdigit(static_cast<unsigned char>(line[0])) && line[0] != '-' && line[0] != '.')
        continue;
    }
    labels.push_back(comment);
    comment.clear();
  }
  return labels;
}

}  // namespace

std::vector<ReferencePoint> read_reference(const std::filesystem::path& points,
                                           const std::filesystem::path& reference) {
  const std::vector<ProbePoint> probe = read_points_csv(points);
  const std::vector<std::string> labels = row_labels(points);
  std::ifstream in(reference);
  if (!in) throw InputError(reference.string() + ": cannot open");
  std::string line;
  std::getline(in, line);
  std::map<std::string, size_t> column;
  const std::vector<std::string> names = split(line);
  for (size_t i = 0; i < names.size(); ++i) column[names[i]] = i;
  for (const char* name : {"E_r", "E_g", "E_b", "se_r", "se_g", "se_b"}) {
    if (!column.count(name))
      throw InputError(reference.string() + ": line 1: no column " + name +
                       " (write it with radiosity probe --method pathtrace)");
  }
  std::vector<ReferencePoint> out;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = split(line);
    const std::string where = reference.string() + ": line " + std::to_string(number);
    if (out.size() >= probe.size()) throw InputError(where + ": more rows than " + points.string());
    ReferencePoint r;
    r.point = probe[out.size()];
    r.label = out.size() < labels.size() ? labels[out.size()] : "";
    try {
      for (int c = 0; c < 3; ++c) {
        r.value[c] = std::stod(fields.at(column.at(std::string("E_") + "rgb"[c])));
        r.standard_error[c] = std::stod(fields.at(column.at(std::string("se_") + "rgb"[c])));
      }
    } catch (const std::exception&) {
      throw InputError(where + ": a missing or malformed number");
    }
    out.push_back(std::move(r));
  }
  if (out.size() != probe.size())
    throw InputError(reference.string() + ": " + std::to_string(out.size()) + " rows for " +
                     std::to_string(probe.size()) + " points in " + points.string());
  return out;
}

AccuracyReport compare_to_reference(const std::vector<ReferencePoint>& reference,
                                    const std::vector<Rgb>& values) {
  if (values.size() != reference.size()) throw Error("compare_to_reference: sizes differ");
  AccuracyReport r;
  double squares = 0, sum = 0, se_squares = 0;
  int count = 0;
  r.point_errors.assign(reference.size(), Rgb::Zero());
  for (size_t i = 0; i < reference.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double want = reference[i].value[c];
      if (!(want > 0)) continue;
      const double e = values[i][c] / want - 1;
      r.point_errors[i][c] = e;
      squares += e * e;
      sum += e;
      se_squares += std::pow(reference[i].standard_error[c] / want, 2);
      ++count;
      if (!(std::abs(e) <= r.largest)) r.largest = std::abs(e), r.worst = static_cast<int>(i);
    }
  }
  if (count > 0) {
    r.rms = std::sqrt(squares / count);
    r.mean = sum / count;
    r.mean_standard_error = std::sqrt(se_squares) / count;
  }
  // Each point's mean error over its channels, then their spread over the points.
  std::vector<double> per_point;
  for (size_t i = 0; i < reference.size(); ++i) {
    double point_sum = 0;
    int channels = 0;
    for (int c = 0; c < 3; ++c) {
      if (!(reference[i].value[c] > 0)) continue;
      point_sum += r.point_errors[i][c];
      ++channels;
    }
    if (channels > 0) per_point.push_back(point_sum / channels);
  }
  const size_t n = per_point.size();
  if (n > 1) {
    double mean = 0, squares_about = 0;
    for (const double e : per_point) mean += e / static_cast<double>(n);
    for (const double e : per_point) squares_about += (e - mean) * (e - mean);
    r.points_standard_error = std::sqrt(squares_about / static_cast<double>(n - 1) / n);
  }
  return r;
}

}  // namespace rad
