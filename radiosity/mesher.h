#pragma once
/// Meshing scene polygons into patches and elements.
#include <functional>
#include <vector>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace rad {

/// Subdivides every scene polygon into patches no longer than `patch_size` (scene units) along
/// an edge: a convex quad becomes an nu x nv grid (bilinear, so sub-quads stay in its plane);
/// a triangle is cut into k^2 triangles; any other polygon is triangulated first (ear clipping)
/// and each triangle cut the same way. First, polygons are cut along their contact lines
/// (radiosity/contact_cuts.h) and each piece meshed alone. Patches keep the parent's orientation
/// and normal.
/// `progress`, when given, is told the fraction of the polygons done, now and then.
std::vector<Patch> make_patches(const Scene& scene, double patch_size,
                                const std::function<void(double)>& progress = {});

/// A lower bound on the patches make_patches(scene, patch_size) makes, without making them:
/// per polygon ceil(area / patch_size^2), and at least one. (Every patch has edges no longer
/// than patch_size, so an area of at most patch_size^2; the contact cuts only add patches.)
double least_patches(const Scene& scene, double patch_size);

/// Area and area centroid of a planar 3- or 4-gon.
void element_geometry(const std::vector<Vec3>& corners, double* area, Vec3* centroid);

/// Appends the four children of element `e` (quad: 2 x 2 at edge midpoints and the bilinear
/// centre; triangle: midpoint subdivision) and links them. Children inherit radiosity.
void split_element(std::vector<Element>& elements, int e);

/// Top-level elements of every patch: each patch split `levels` times (4^levels elements).
/// Returns the whole tree (the patch-level roots are not kept: level-0 elements are the roots).
std::vector<Element> make_elements(const std::vector<Patch>& patches, int levels);

/// Longest edge of a 3- or 4-gon.
double longest_edge(const std::vector<Vec3>& corners);

}  // namespace rad
