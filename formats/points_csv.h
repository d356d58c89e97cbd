#pragma once
/// Probe points in and irradiance out, as CSV (DESIGN.md §5).
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// A point where irradiance is wanted, with its receiver normal (unit length after reading).
struct ProbePoint {
  Vec3 x;
  Vec3 n;
};

/// Reads rows `x,y,z,nx,ny,nz`. A first row that is not numeric is a header; blank lines and
/// lines starting with '#' are skipped; spaces around fields are allowed. Throws InputError
/// naming file and line for a wrong field count, a field that is not a finite number, or a
/// zero normal. The normal is normalized.
std::vector<ProbePoint> read_points_csv(const std::filesystem::path& file);

/// Writes `x,y,z,nx,ny,nz,E_r,E_g,E_b,bound` with a header; each number in the shortest form
/// that reads back exactly. `bound` is the certified bound on each result's error; a value that
/// is not finite (no bound: Monte Carlo) is written as an empty field. With `standard_error`
/// (the path tracer's), three more columns se_r,se_g,se_b. Then three more per heuristic part
/// in `apart` (not covered by the bound and not in E; e.g. "refracted", 000 §4, and "glossy",
/// 003): NAME_r,NAME_g,NAME_b.
struct ApartColumns {
  std::string name;
  const std::vector<Rgb>* values;
};
void write_probe_csv(std::ostream& out, const std::vector<ProbePoint>& points,
                     const std::vector<Rgb>& irradiance, const std::vector<double>& bound,
                     const std::vector<Rgb>* standard_error = nullptr,
                     const std::vector<ApartColumns>& apart = {});

}  // namespace rad
