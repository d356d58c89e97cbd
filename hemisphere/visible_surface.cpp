#include "hemisphere/visible_surface.h"

#include <cmath>

#include "geometry/tolerance.h"

namespace rad::hemi {

VisibleSurface::VisibleSurface() { nodes_.push_back(Node{}); }

void VisibleSurface::insert(const Occluder& occluder, const SphericalPolygon& region) {
  if (region.empty()) return;
  occluders_.push_back(occluder);
  insert_at(0, static_cast<int>(occluders_.size()) - 1, region);
}

void VisibleSurface::insert_at(int node, int occupant, const SphericalPolygon& piece) {
  if (piece.empty()) return;
  // Walk down while the piece lies on one side of each plane; copy only where a plane cuts it.
  while (!nodes_[node].leaf()) {
    const int side = piece.side_of(nodes_[node].plane);
    if (side == 0) break;
    node = side > 0 ? nodes_[node].positive : nodes_[node].negative;
  }
  if (!nodes_[node].leaf()) {
    const auto [pos, neg] = piece.split(nodes_[node].plane);
    // Children are read after the split: recursion may grow nodes_ (no references kept).
    const int positive = nodes_[node].positive, negative = nodes_[node].negative;
    insert_at(positive, occupant, pos);
    insert_at(negative, occupant, neg);
    return;
  }
  const int current = nodes_[node].occupant;
  if (current < 0) {
    carve(node, occupant, piece);
    return;
  }
  const Occluder& f = occluders_[occupant];
  const Occluder& q = occluders_[current];
  // Directions where F and Q are equally deep: c_F (n_Q . d) = c_Q (n_F . d).
  const Vec3 m = f.offset * q.normal - q.offset * f.normal;
  const double scale = std::abs(f.offset) + std::abs(q.offset);
  if (!(m.norm() > relative::kRounding * scale)) {
    // The same plane: equally deep everywhere. The lower id shows, whatever the order.
    if (f.id < q.id) carve(node, occupant, piece);
    return;
  }
  const auto [a, b] = piece.split(m.normalized());
  for (const SphericalPolygon* part : {&a, &b}) {
    if (part->empty()) continue;
    const Vec3 d = part->interior_direction();
    // The order is constant inside each part; compare along one ray through it.
    if (!(occluders_[occupant].depth(d) < occluders_[current].depth(d))) continue;
    if (nodes_[node].leaf()) {
      carve(node, occupant, *part);
    } else {
      insert_at(node, occupant, *part);  // carving the first part made the leaf a subtree
    }
  }
}

double VisibleSurface::visible_form_factor(const Occluder& occluder, const SphericalPolygon& region,
                                           const Vec3& n) const {
  return visible_at(0, occluder, region, n);
}

double VisibleSurface::visible_at(int node, const Occluder& f, const SphericalPolygon& piece,
                                  const Vec3& n) const {
  if (piece.empty()) return 0;
  while (!nodes_[node].leaf()) {  // as in insert_at
    const int side = piece.side_of(nodes_[node].plane);
    if (side == 0) break;
    node = side > 0 ? nodes_[node].positive : nodes_[node].negative;
  }
  if (!nodes_[node].leaf()) {
    const auto [pos, neg] = piece.split(nodes_[node].plane);
    return visible_at(nodes_[node].positive, f, pos, n) +
           visible_at(nodes_[node].negative, f, neg, n);
  }
  const int current = nodes_[node].occupant;
  if (current < 0) return piece.form_factor(n);  // an empty cell: it would show
  const Occluder& q = occluders_[current];
  const Vec3 m = f.offset * q.normal - q.offset * f.normal;
  const double scale = std::abs(f.offset) + std::abs(q.offset);
  // The same plane: the lower id shows, and a polygon does not hide itself.
  if (!(m.norm() > relative::kRounding * scale)) return f.id <= q.id ? piece.form_factor(n) : 0;
  const auto [a, b] = piece.split(m.normalized());
  double sum = 0;
  for (const SphericalPolygon* part : {&a, &b}) {
    if (part->empty()) continue;
    if (f.depth(part->interior_direction()) < q.depth(part->interior_direction()))
      sum += part->form_factor(n);
  }
  return sum;
}

void VisibleSurface::carve(int node, int occupant, const SphericalPolygon& piece) {
  const int previous = nodes_[node].occupant;
  SphericalPolygon rest = nodes_[node].region;  // the leaf's cell; empty leaves carry none
  int at = node;
  const size_t edges = piece.vertices().size();
  for (size_t i = 0; i < edges; ++i) {
    const Vec3 plane = piece.edge_normal(i);
    Node outside;
    if (previous >= 0) {
      auto [in, out] = rest.split(plane);
      rest = std::move(in);
      outside.occupant = out.empty() ? -1 : previous;
      outside.region = std::move(out);
    }
    const int negative = static_cast<int>(nodes_.size());
    nodes_.push_back(std::move(outside));
    const int positive = static_cast<int>(nodes_.size());
    nodes_.push_back(Node{});
    nodes_[at].plane = plane;
    nodes_[at].negative = negative;
    nodes_[at].positive = positive;
    nodes_[at].occupant = -1;
    nodes_[at].region = SphericalPolygon();
    at = positive;
  }
  nodes_[at].occupant = occupant;
  // The piece lies inside the cell, so the carved cell is the piece itself.
  nodes_[at].region = piece;
}

std::vector<Fragment> VisibleSurface::fragments() const {
  std::vector<Fragment> out;
  for (const Node& n : nodes_) {
    if (n.leaf() && n.occupant >= 0 && !n.region.empty())
      out.push_back({occluders_[n.occupant].id, n.region});
  }
  return out;
}

double VisibleSurface::covered_form_factor(const Vec3& n) const {
  double sum = 0;
  for (const Node& node : nodes_) {
    if (node.leaf() && node.occupant >= 0) sum += node.region.form_factor(n);
  }
  return sum;
}

}  // namespace rad::hemi
