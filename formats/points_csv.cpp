#include "formats/points_csv.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <ostream>
#include <sstream>

#include "scene/error.h"
#include "scene/input_files.h"

namespace rad {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

/// Parses a whole field as a double; false when it is not one number.
bool parse_number(const std::string& field, double* value) {
  if (field.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(field.c_str(), &end);
  return end == field.c_str() + field.size();
}

}  // namespace

std::vector<ProbePoint> read_points_csv(const std::filesystem::path& file) {
  check_input_file(file, "points file");
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open points file");
  std::vector<ProbePoint> points;
  std::string line;
  bool first_row = true;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;
    const std::string where = file.string() + ":" + std::to_string(number) + ": ";
    const std::vector<std::string> fields = split_fields(text);
    double v[6];
    // A header has no number in it: a first row of 7 or 5 numbers is a malformed row, not one.
    bool any_number = false;
    double ignored = 0;
    for (const std::string& f : fields) any_number = any_number || parse_number(f, &ignored);
    if (!any_number && first_row) {
      first_row = false;
      continue;
    }
    first_row = false;
    if (fields.size() != 6) {
      throw InputError(where + "expected 6 fields x,y,z,nx,ny,nz, got " +
                       std::to_string(fields.size()));
    }
    for (size_t i = 0; i < 6; ++i) {
      if (!parse_number(fields[i], &v[i]))
        throw InputError(where + "field " + std::to_string(i + 1) + " '" + fields[i] +
                         "' is not a number");
      if (!std::isfinite(v[i]))
        throw InputError(where + "field " + std::to_string(i + 1) + " is not finite");
    }
    Vec3 n(v[3], v[4], v[5]);
    const double largest = n.cwiseAbs().maxCoeff();
    if (!(largest > 0)) throw InputError(where + "the normal (nx, ny, nz) is zero");
    // Components near the ends of the doubles (1e300, 1e-300): their squares overflow or
    // vanish, and normalized() would give (0, 0, 0). Scaled by the largest first, they do not.
    const double squared = n.squaredNorm();
    if (!std::isfinite(squared) || squared < std::numeric_limits<double>::min()) n /= largest;
    points.push_back({Vec3(v[0], v[1], v[2]), n.normalized()});
  }
  if (points.empty()) throw InputError(file.string() + ": no points");
  return points;
}

void write_probe_csv(std::ostream& out, const std::vector<ProbePoint>& points,
                     const std::vector<Rgb>& irradiance, const std::vector<double>& bound,
                     const std::vector<Rgb>* standard_error,
                     const std::vector<ApartColumns>& apart) {
  out << "x,y,z,nx,ny,nz,E_r,E_g,E_b,bound" << (standard_error ? ",se_r,se_g,se_b" : "");
  for (const ApartColumns& a : apart)
    out << "," << a.name << "_r," << a.name << "_g," << a.name << "_b";
  out << "\n";
  std::string row;
  for (size_t i = 0; i < points.size(); ++i) {
    const ProbePoint& p = points[i];
    const Rgb& e = irradiance[i];
    row.clear();
    std::vector<double> values{p.x.x(), p.x.y(), p.x.z(), p.n.x(), p.n.y(),
                               p.n.z(), e.x(),   e.y(),   e.z(),   bound[i]};
    if (standard_error) {
      const Rgb& se = (*standard_error)[i];
      values.insert(values.end(), {se.x(), se.y(), se.z()});
    }
    for (const ApartColumns& a : apart) {
      const Rgb& r = (*a.values)[i];
      values.insert(values.end(), {r.x(), r.y(), r.z()});
    }
    for (const double v : values) {
      // The shortest text that reads back to the same double; nothing for what is not finite
      // (Monte Carlo's bound: none is certified), so no NaN or inf ever reaches the file.
      if (!row.empty()) row.push_back(',');
      if (!std::isfinite(v)) continue;
      char text[32];
      const auto end = std::to_chars(text, text + sizeof(text), v).ptr;
      row.append(text, end);
    }
    row.push_back('\n');
    out << row;
  }
}

}  // namespace rad
