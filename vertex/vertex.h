#pragma once
/// Module `vertex` (rad_vertex): the whole vertex-tracing method (paper 001; DESIGN.md §4), the
/// other exact gatherer, and the base of paper 000's extensions:
///  - vertex_formula.h: Stark's vertex-based form factor (001 eqs. 6-8);
///  - angular_spans.h: the picture around one traced vertex and its contribution (001 eq. 9);
///  - image_box_tree.h: the hierarchy over image-plane boxes (001 §4);
///  - interpenetration.h: where polygons pass through each other (extra visible-map edges);
///  - local_picture.h: the faces, features and candidate vertices seen from x (001 §3.1, §4.2);
///  - vertex_tracer.h: the gatherer (geometry/exact_gatherer.h): clusters, cones, the sum.
///
/// May use: scene, geometry.
#include "vertex/angular_spans.h"
#include "vertex/vertex_formula.h"
#include "vertex/vertex_tracer.h"
