#pragma once
/// Hierarchical radiosity with clustering: links between receivers and sources at the coarsest
/// level that their size and distance allow (Hanrahan, Salzman and Aupperle 1991), with whole
/// clusters of patches as sources far away (Smits, Arvo and Greenberg 1994; Sillion 1995), and
/// Jacobi gathering over the links. docs/algorithms.md, "The hierarchical solver", has the
/// method and what it approximates. It carries diffuse surfaces and point lights (`radiosity
/// solve --solver hierarchical` solves other scenes progressively; SolverSettings::method).
#include <functional>
#include <string>

#include "radiosity/solver.h"

namespace rad {

/// Why solve_hierarchical() cannot take the scene yet (the first feature of it that the
/// hierarchical solver does not carry), or empty when it can.
std::string hierarchical_unsupported(const Scene& scene);

/// Meshes the caster's scene as solve() does (the same patches and elements) and solves it
/// hierarchically:
///   1. a cluster tree over the patches (median splits of their centroids);
///   2. every patch P links to the sources it sees, walked down from the root: a cluster C
///      farther from P than its size over kOpening (and seen all or none by a few rays) is
///      one link, its light taken as the flux of its patches binned by the six axis
///      directions; a patch likewise as one link at P's centroid (the exact point-to-patch form
///      factor and the shadow rays of solve()); a patch nearer than that links each of P's
///      elements to each of its own;
///   3. Jacobi sweeps B = E + rho H(B) until the power of the last sweep's change falls below
///      settings.unshot_fraction of the emitted power;
///   4. up to settings.refine_passes times, split the leaves whose radiosity misses their mesh
///      neighbours' plane, or near a contact a corner's own gather, by more than the
///      refinement limit (radiosity/refinement_limit.h); a split patch's links are handed down
///      to its leaves; sweep again.
/// Bitwise deterministic for any thread count. Throws Error when hierarchical_unsupported()
/// names something.
Solution solve_hierarchical(const RayCaster& caster, const SolverSettings& settings,
                            const std::function<void(const SolveProgress&)>& progress = {});

}  // namespace rad
