#pragma once
/// The bounding-volume hierarchy over axis-aligned boxes in the image plane of a gather point,
/// used by vertex tracing (paper 001 §4) to find the faces around a traced vertex and the pairs
/// of edges that may appear to cross without testing all pairs. Boxes of projected vertices
/// rather than the paper's 3D bounding spheres: the projection is computed per point anyway,
/// convex faces and edges project to convex sets bounded exactly by their vertices' box, and
/// the tolerances are relative to |q| (image coordinates reach 1e8 at the image square).
#include "geometry/box_tree.h"

namespace rad {

using ImageBoxTree = BoxTree<2>;
using ImageBox = ImageBoxTree::Box;

}  // namespace rad
