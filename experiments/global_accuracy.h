#pragma once
/// The global solution against a converged reference: irradiance at chosen points, from a
/// solution through the exact local pass, against the path tracer's (issue 18's measure).
#include <filesystem>
#include <string>
#include <vector>

#include "formats/points_csv.h"

namespace rad {

/// A point with its reference irradiance and that reference's standard error.
struct ReferencePoint {
  ProbePoint point;
  Rgb value = Rgb::Zero();
  Rgb standard_error = Rgb::Zero();
  std::string label;  ///< The comment line above the point in the points file, if any
};

/// Reads the points file (rows x,y,z,nx,ny,nz; a '#' line labels the row below it) and the
/// reference written by `radiosity probe --method pathtrace` at those points (columns E_r, E_g,
/// E_b, se_r, se_g, se_b). Throws InputError naming the file and line when the files do not
/// match or a field is missing.
std::vector<ReferencePoint> read_reference(const std::filesystem::path& points,
                                           const std::filesystem::path& reference);

/// Errors relative to the reference, per point and channel: e = value / reference - 1 (points
/// where the reference is 0 in a channel are left out of that channel).
struct AccuracyReport {
  double rms = 0;      ///< Root mean square of e over points and channels
  double largest = 0;  ///< Largest |e|
  double mean = 0;     ///< Mean of e: the bias
  /// Standard error of `mean` from the reference's own (sqrt(sum se_rel^2) / count): a bias
  /// beyond a few of these is the solution's, not the reference's.
  double mean_standard_error = 0;
  /// Standard error of `mean` from the points' own scatter: with each point's error taken as
  /// the mean over its channels (channels at one point err together), the standard deviation
  /// of those over the n points / sqrt(n). A mean within a couple of these could come from
  /// which points were chosen; beyond, the solution is biased everywhere.
  double points_standard_error = 0;
  int worst = -1;                 ///< The point of the largest |e|
  std::vector<Rgb> point_errors;  ///< e per point and channel
};
AccuracyReport compare_to_reference(const std::vector<ReferencePoint>& reference,
                                    const std::vector<Rgb>& values);

}  // namespace rad
