#pragma once
/// How far an element's radiosity may miss before it is split, for both solvers.
#include <algorithm>

namespace rad {

inline constexpr double kDarkFloor = 0.1;
/// Measured on the Cornell box (bench/results/global_accuracy.md, point 10: the floor 2 mm
/// from the short block's front, in its umbra, where blue is a twentieth of red): path-traced,
/// the blue radiosity of the block's face falls by 40% over its lowest 3 mm and the floor's
/// by a quarter over its first 4 mm. Held to 0.1 x B_ref, the elements there stayed 4.7 mm
/// and constant across that fall, the lowest rows too bright on both sides (+2.6% at the
/// point in blue); at 0.02 they follow it (+1.4%), for 5% more elements. 0.05 reaches +1.9%;
/// 0.01 goes no further than 0.02.
inline constexpr double kContactDarkFloor = 0.02;

/// Errors are seen relative to the local brightness: the limit is `threshold` times the local
/// radiosity, clamped to [floor, 1] x `reference` (B_ref, reference_radiosity()) so that dark
/// regions are resolved but black ones are not chased forever. The floor is kDarkFloor in
/// general: a dark element is seen at a small solid angle from the brighter points around it,
/// and its error is small beside theirs. Near a contact or a concave edge (`near_contact`) it
/// is kContactDarkFloor: a point of the local pass beside the edge sees the elements next to it
/// at half its hemisphere, and in a contact shadow it is as dark as they are, so what it
/// tolerates is relative to that darkness, not to the scene's mean.
inline double refinement_limit(double threshold, double reference, double local_radiosity,
                               bool near_contact) {
  const double floor = near_contact ? kContactDarkFloor : kDarkFloor;
  return threshold * std::clamp(local_radiosity, floor * reference, reference);
}

}  // namespace rad
