// The progressive solver's adaptive refinement: elements split during shots where the shot is
// far from linear (or, near contacts, from constant), after convergence where their neighbours'
// plane misses them; new elements re-gather what has been shot.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "geometry/lambert.h"
#include "radiosity/patch_mesh.h"
#include "radiosity/progressive_solver.h"

namespace rad {

int ProgressiveSolver::refine_by_neighbours() {
  if (!refinement_enabled()) return 0;
  const ElementMesh mesh(solution_, scene_.tolerance().pad);
  std::vector<char> split(mesh.face_count(), 0);
  tbb::parallel_for(0, mesh.face_count(), [&](int f) {
    const Element& el = solution_.elements[mesh.element(f)];
    if (!splittable(mesh.element(f))) return;
    const std::optional<Rgb> fitted = mesh.neighbour_plane_at(solution_, f);
    if (!fitted) return;
    const Rgb& predicted = *fitted;
    const double miss = (el.radiosity - predicted).cwiseAbs().maxCoeff();
    split[f] =
        miss > limit(el.radiosity.cwiseMax(predicted).maxCoeff(), near_contact_[mesh.element(f)]);
  });
  std::vector<int> children;
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (split[f]) split_into(mesh.element(f), children);
  }
  if (children.empty()) return 0;
  regather(children);
  leaves_ = solution_.leaves();
  return static_cast<int>(children.size() / 4);
}

void ProgressiveSolver::split_into(int e, std::vector<int>& children) {
  split_element(elements(), e);
  const int first = elements()[e].first_child;
  back_irradiance_.resize(elements().size(), Rgb::Zero());
  buried_.resize(elements().size(), 0);
  leaf_unshot_.resize(elements().size(), Rgb::Zero());
  leaf_shot_.resize(elements().size(), Rgb::Zero());
  shooting_.resize(elements().size(), Rgb::Zero());
  shooting_node_spread_.resize(elements().size(), 0.0f);
  shot_node_spread_.resize(elements().size(), 0.0f);
  for (int c = 0; c < 4; ++c) {
    children.push_back(first + c);
    // The same density over each part: what the element held, shot and is to shoot.
    leaf_unshot_[first + c] = leaf_unshot_[e];
    leaf_shot_[first + c] = leaf_shot_[e];
    shooting_[first + c] = shooting_[e];
    back_irradiance_[first + c] = back_irradiance_[e];  // inherited, as the front's is
    const Element& child = elements()[first + c];
    buried_[first + c] = rays_.is_buried(child.centroid, solution_.patches[child.patch].normal);
    long_enough_.resize(elements().size(), 0);
    long_enough_[first + c] = longest_edge(child.corners) > min_size_;
    near_contact_.resize(elements().size(), 0);
    near_contact_[first + c] = near_a_contact(child);
  }
  ++stats().refined;
}

void ProgressiveSolver::refine_during_shot(int shooter, const Rgb& delta, int shot) {
  const Patch& source = patches()[shooter];
  const Sphere& sb = patch_bounds_[shooter];
  std::vector<int> candidates = receivers_;
  bool any_split = false;
  while (!candidates.empty()) {
    std::vector<char> split(candidates.size(), 0);
    tbb::parallel_for(size_t(0), candidates.size(), [&](size_t k) {
      const int e = candidates[k];
      const Element& el = elements()[e];
      const Rgb rho = material(el.polygon).reflectance;
      const double scale = rho.maxCoeff() * delta.cwiseAbs().maxCoeff();
      const double lim =
          limit((el.radiosity + rho.cwiseProduct(delta).cwiseProduct(ff_[e])).cwiseAbs().maxCoeff(),
                near_contact_[e]);
      if (scale <= lim || !splittable(e)) return;
      // Largest possible form factor from this element to the shooter (bounding spheres):
      // skip pairs that cannot reach the limit.
      const Sphere eb{el.centroid, near_field_.radius(e)};
      const double gap = (eb.centre - sb.centre).norm() - eb.radius - sb.radius;
      const double ff_max = form_factor_bound(source.area, gap);
      if (scale * ff_max <= lim) return;
      // Corners pulled 0.1% towards the centre so no point lies on a neighbouring polygon.
      // Near a contact, down to a sixteenth of the patch size (the patch size stays the one
      // knob of the mesh's resolution: coarse patches do not refine every concave edge to
      // the smallest element).
      const bool constant_test = near_contact_[e] && longest_edge(el.corners) > contact_size_;
      double off = 0;
      Rgb mean = Rgb::Zero();
      for (size_t c = 0; c < el.corners.size(); ++c) {
        const Vec3 x = el.corners[c] + 1e-3 * (el.centroid - el.corners[c]);
        const Rgb at_corner =
            rays_.visible_form_factor(x, solution_.patches[el.patch].normal, el.polygon, source,
                                      stream_key(shot, e, StreamKind::corner, static_cast<int>(c)));
        if (constant_test) {
          off = std::max(off, (ff_[e] - at_corner).cwiseAbs().maxCoeff());
        } else {
          mean += at_corner;
        }
      }
      if (!constant_test)
        off = (ff_[e] - mean / static_cast<double>(el.corners.size())).cwiseAbs().maxCoeff();
      split[k] = scale * off > lim;
    });
    std::vector<int> children;
    for (size_t k = 0; k < candidates.size(); ++k) {
      if (split[k]) split_into(candidates[k], children);
    }
    if (children.empty()) break;
    any_split = true;
    ff_.resize(elements().size(), Rgb::Zero());
    back_ff_.resize(elements().size(), Rgb::Zero());
    receive(children, shooter, shot);
    regather(children);
    candidates = std::move(children);
  }
  if (any_split) {
    leaves_ = solution_.leaves();
    collect_receivers();
  }
}

void ProgressiveSolver::regather(const std::vector<int>& children) {
  const int shot = stats().shots;
  std::vector<Rgb> gathered(children.size(), Rgb::Zero()), back(children.size(), Rgb::Zero());
  for (size_t j = 0; j < patches().size(); ++j) {
    if (patches()[j].shot != Rgb::Zero())
      store_.grow(static_cast<int>(j), patches().size(), children);
  }
  near_field_.grow(elements());
  tbb::parallel_for(size_t(0), children.size(), [&](size_t k) {
    const Element& el = elements()[children[k]];
    if (buried_[children[k]]) return;  // receives nothing
    const bool at_back = absorbs_at_back(el.polygon);
    const Vec3& n = solution_.patches[el.patch].normal;
    gathered[k] = rays_.point_light_irradiance(el.centroid, n);  // the lights' one shot
    if (at_back) back[k] = rays_.point_light_irradiance(el.centroid, -n);
    for (size_t j = 0; j < solution_.patches.size(); ++j) {
      const Patch& p = solution_.patches[j];
      if (p.shot == Rgb::Zero() || !culling_->may_receive(el.patch, static_cast<int>(j))) continue;
      if (is_near(children[k], static_cast<int>(j), shot_spread_[j])) {
        const int e = children[k];
        gathered[k] += near_field_.gather(
            elements(), e, static_cast<int>(j), leaf_shot_, shot_node_spread_, near_tolerance(e),
            [&](int node) { return piece_form_factor(e, node, shot); }, false);
      } else {
        gathered[k] += p.shot.cwiseProduct(stored_form_factor(
            static_cast<int>(j), children[k],
            stream_key(shot, children[k], StreamKind::regather, static_cast<int>(j))));
      }
      if (at_back) {
        back[k] += p.shot.cwiseProduct(back_ff(
            el, p, stream_key(shot, children[k], StreamKind::back, static_cast<int>(j) + 1)));
      }
    }
  });
  for (size_t k = 0; k < children.size(); ++k) {
    Element& el = elements()[children[k]];
    const Rgb rho = material(el.polygon).reflectance;
    const Rgb power = (gathered[k] - el.irradiance) * el.area;  // against what it inherited
    el.irradiance = gathered[k];
    el.radiosity = material(el.polygon).emission + rho.cwiseProduct(gathered[k]);
    stats().absorbed += (stays(el.polygon) - rho).cwiseProduct(power);
    stats().escaped -= (stays(el.polygon) + redirects(el.polygon)).cwiseProduct(power);
    stats().redirected += redirects(el.polygon).cwiseProduct(power);
    if (absorbs_at_back(el.polygon)) {
      const Rgb back_power =
          stays(el.polygon).cwiseProduct(back[k] - back_irradiance_[children[k]]) * el.area;
      back_irradiance_[children[k]] = back[k];
      stats().absorbed += back_power;
      stats().escaped -= back_power;
    }
    Patch& owner = patches()[el.patch];
    owner.unshot += rho.cwiseProduct(power) / live_area_[el.patch];
    leaf_unshot_[children[k]] += rho.cwiseProduct(power) / el.area;
  }
}

}  // namespace rad
