// The global solution against the committed path-traced reference (issue 18): the reading of
// the reference, the measure itself against hand-made values, and the default solve of both
// accuracy scenes within the targets it reaches (bench/results/global_accuracy.md).
#include "experiments/global_accuracy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "scene/error.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "tests/scratch_dir.h"

namespace rad {
namespace {

const std::filesystem::path kData = std::filesystem::path(RAD_SOURCE_DIR) / "data";

TEST(GlobalAccuracy, ReadsTheReferenceWithItsLabelsAndRejectsAMismatch) {
  const auto r = read_reference(kData / "cornell-box/accuracy-points.csv",
                                kData / "cornell-box/accuracy-reference.csv");
  ASSERT_EQ(r.size(), 36u);
  EXPECT_EQ(r[0].label, "floor between the blocks, under the light");
  EXPECT_EQ(r[0].point.x, Vec3(278, 0, 280));
  for (const ReferencePoint& p : r) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(p.value[c], 0) << p.label;
      // The reference is converged: relative standard errors below 0.1%.
      EXPECT_LT(p.standard_error[c], 1e-3 * p.value[c]) << p.label;
    }
  }
  // The room's points against the Cornell box's reference: the counts differ.
  EXPECT_THROW(read_reference(kData / "room-window/accuracy-points.csv",
                              kData / "cornell-box/accuracy-reference.csv"),
               InputError);
  // A reference without standard errors (the local pass's CSV) is not a reference.
  const std::filesystem::path dir = test::scratch_dir("global_accuracy");
  std::ofstream(dir / "points.csv") << "x,y,z,nx,ny,nz\n0,0,0,0,0,1\n";
  std::ofstream(dir / "probe.csv") << "x,y,z,nx,ny,nz,E_r,E_g,E_b,bound\n0,0,0,0,0,1,1,1,1,0\n";
  EXPECT_THROW(read_reference(dir / "points.csv", dir / "probe.csv"), InputError);
}

TEST(GlobalAccuracy, TheMeasureOnHandMadeValues) {
  std::vector<ReferencePoint> reference(2);
  reference[0].value = Rgb(1, 2, 4);
  reference[0].standard_error = Rgb(0.01, 0.02, 0.04);
  reference[1].value = Rgb(1, 0, 1);  // no green: that channel is left out
  const AccuracyReport r = compare_to_reference(reference, {Rgb(1.1, 2, 3), Rgb(1, 5, 1.05)});
  // Errors +10%, 0, -25%; 0, (left out), +5%.
  EXPECT_NEAR(r.largest, 0.25, 1e-12);
  EXPECT_EQ(r.worst, 0);
  EXPECT_NEAR(r.mean, (0.1 - 0.25 + 0.05) / 5, 1e-12);
  EXPECT_NEAR(r.rms, std::sqrt((0.01 + 0.0625 + 0.0025) / 5), 1e-12);
  EXPECT_NEAR(r.mean_standard_error, std::sqrt(3 * 1e-4) / 5, 1e-12);
  EXPECT_NEAR(r.point_errors[1][2], 0.05, 1e-12);
  // Point means -0.05 and +0.025: about their mean -0.0125, sd = 0.075 / sqrt(2), over sqrt(2).
  EXPECT_NEAR(r.points_standard_error, 0.0375, 1e-12);
}

/// The default solve of data/<name> (or one with `settings`), gathered exactly at its accuracy
/// points.
AccuracyReport default_accuracy(const std::string& name,
                                const SolverSettings& settings = SolverSettings{}) {
  const Scene scene = load_scene(kData / name / "scene.json");
  const auto reference =
      read_reference(kData / name / "accuracy-points.csv", kData / name / "accuracy-reference.csv");
  const Solution solution = solve(RayCaster(scene), settings);
  const LocalPass pass(scene, faces_from_solution(scene, solution), Method::hemisphere);
  std::vector<Rgb> values;
  for (const ReferencePoint& r : reference)
    values.push_back(pass.gather(r.point.x, r.point.n, 0).irradiance);
  const AccuracyReport report = compare_to_reference(reference, values);
  std::cout << name << ": RMS " << report.rms << ", largest " << report.largest << " (point "
            << report.worst << "), mean " << report.mean << "\n";
  return report;
}

TEST(GlobalAccuracy, TheDefaultSolveOfTheCornellBoxIsWithinTheTargets) {
  const AccuracyReport r = default_accuracy("cornell-box");
  EXPECT_LE(r.rms, 0.01);
  EXPECT_LE(r.largest, 0.02);
  EXPECT_LE(std::abs(r.mean), 0.003);
  for (size_t i = 0; i < r.point_errors.size(); ++i) {
    // The two points within 5 mm of a concave edge are the largest (measured 1.4% and 1.5%);
    // the rest are within 0.7%.
    if (i == 10 || i == 17) continue;
    EXPECT_LE(r.point_errors[i].cwiseAbs().maxCoeff(), 0.01) << "point " << i;
  }
}

TEST(GlobalAccuracy, TheDefaultSolveOfTheRoomIsWithinTheTargets) {
  const AccuracyReport r = default_accuracy("room-window");
  EXPECT_LE(r.rms, 0.01);
  EXPECT_LE(r.largest, 0.02);
  EXPECT_LE(std::abs(r.mean), 0.003);
}

TEST(GlobalAccuracy, TheHierarchicalSolverIsWithinTheTargetsAndItsRefinementIsWhy) {
  // The hierarchical solver (radiosity/hierarchical_solver.h) against the same reference and
  // the same targets as the progressive solver above. Measured: Cornell box RMS 0.39%, largest
  // 1.89% (point 17, the ceiling's corner); the room RMS 0.25%, largest 0.80%; unrefined, the
  // Cornell box is off by RMS 4.8%. Each piece of its refinement was taken out in turn (at
  // 56a75bd) and the Cornell box's largest error grew past the target: the corner test where
  // no neighbour plane fits (5.1%), the sources opened near a split receiver (5.3%), the second
  // sweep after a refinement (2.1%), the cluster links handed down with the patch links
  // (2.2%). The hidden sources measured again by new leaves show in the room: without them
  // its largest error is 1.37% (the Cornell box's 1.83%), so the room is held to 1%.
  SolverSettings settings;
  settings.method = SolverSettings::Method::hierarchical;
  const AccuracyReport refined = default_accuracy("cornell-box", settings);
  EXPECT_LE(refined.rms, 0.01);
  EXPECT_LE(refined.largest, 0.02);
  const AccuracyReport room = default_accuracy("room-window", settings);
  EXPECT_LE(room.rms, 0.01);
  EXPECT_LE(room.largest, 0.01);
  settings.refine_threshold = 0;
  const AccuracyReport unrefined = default_accuracy("cornell-box", settings);
  EXPECT_LT(refined.rms, 0.2 * unrefined.rms);
  EXPECT_LT(refined.largest, 0.2 * unrefined.largest);
}

}  // namespace
}  // namespace rad
