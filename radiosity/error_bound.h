#pragma once
/// The certified bound on a radiosity solve's own error (Neumann series of the discrete
/// system; the first step of Lischinski, Smits and Greenberg 1994's bounds on the global
/// solution). The derivation, with what it assumes, is in docs/algorithms.md ("The
/// solution's own error"); in short:
///
/// The discrete system is B* = E + R F B* (+ the point lights' direct term), with R the diagonal
/// of the elements' reflectances and F the form factors the solver measured, each row summing to
/// at most 1. A shooting solver stops at B = E + R F S, having shot S and holding the unshot
/// radiosity U = B - S (per element; a source is seen as a weighted mean of its elements). Then
///   B* - S = U + R F (B* - S)                  so   |B* - S| <= max|U| / (1 - rho_max),
///   B* - B = R F (B* - S)                      so   |B* - B| <= rho_max max|U| / (1 - rho_max),
/// per channel, with rho_max the largest reflectance of the channel: the residual
/// r = E + R F B - B = R F U is at most rho_max max|U|, and the error at most |r| / (1 - rho_max).
#include <cmath>

#include "geometry/vec.h"

namespace rad {

/// max over elements of |B* - B| per channel, from the largest unshot radiosity of any element
/// and the largest reflectance of any surface (each per channel, reflectance below 1).
inline Rgb iteration_error_bound(const Rgb& largest_unshot, const Rgb& largest_reflectance) {
  Rgb bound;
  for (int c = 0; c < 3; ++c) {
    const double rho = largest_reflectance[c];
    bound[c] = rho * std::abs(largest_unshot[c]) / (1 - rho);
  }
  return bound;
}

}  // namespace rad
