// The stability report (DESIGN.md §4): seeded scene families built to be degenerate for the
// exact gatherers, each run through the hemisphere gatherer, vertex tracing and the Monte Carlo
// baseline (direct light: every polygon occludes, the lamps emit). Families with filters
// (000 §2.2) compare vertex tracing with the identity of independent removals over opaque
// hemisphere gathers (tests/filter_identity.h); families with mirrors (000 §3) run both exact
// methods through the local pass at tolerance 0, which unfolds the mirrors. Per family: the largest
// relative disagreement between the two exact methods, how many points disagree beyond 1e-9,
// Monte Carlo's error against them, NaN counts, and the seconds each method took. Prints a
// Markdown table (make stability writes bench/results/stability.md). Single-threaded, so the
// times compare methods point for point.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "hemisphere/hemisphere_gatherer.h"
#include "localpass/local_pass.h"
#include "reference/monte_carlo.h"
#include "scene/polygon_faces.h"
#include "tests/filter_identity.h"
#include "tests/random_scenes.h"
#include "vertex/vertex_tracer.h"

namespace {

using rad::Rgb;
using rad::Vec3;
using rad::test::RandomScene;
using rad::test::RandomSceneMaker;
using rad::test::SceneBuilder;
using Clock = std::chrono::steady_clock;

constexpr int kMonteCarloSamples = 4096;

struct Family {
  const char* name;
  const char* stresses;
  int scenes;
  std::function<RandomScene(RandomSceneMaker&)> make;
  /// opaque: the two gatherers as they are; filters: vertex tracing against the subset
  /// identity of opaque hemisphere gathers; mirrors: both through the local pass.
  enum class Kind { opaque, filters, mirrors } kind = Kind::opaque;
};

/// A rectangle in the plane x = at (y in [y0, y1], z in [z0, z1]), front towards +x or -x.
void wall_x(SceneBuilder& b, double at, double y0, double y1, double z0, double z1, bool plus_x,
            int material) {
  if (plus_x) {
    b.polygon({Vec3(at, y0, z0), Vec3(at, y1, z0), Vec3(at, y1, z1), Vec3(at, y0, z1)}, material);
  } else {
    b.polygon({Vec3(at, y0, z0), Vec3(at, y0, z1), Vec3(at, y1, z1), Vec3(at, y1, z0)}, material);
  }
}

/// The same in the plane y = at, front towards +y or -y.
void wall_y(SceneBuilder& b, double at, double x0, double x1, double z0, double z1, bool plus_y,
            int material) {
  if (plus_y) {
    b.polygon({Vec3(x0, at, z0), Vec3(x0, at, z1), Vec3(x1, at, z1), Vec3(x1, at, z0)}, material);
  } else {
    b.polygon({Vec3(x0, at, z0), Vec3(x1, at, z0), Vec3(x1, at, z1), Vec3(x0, at, z1)}, material);
  }
}

int mirror_material(SceneBuilder& b, RandomSceneMaker& m) {
  return b.material("mirror", Rgb::Constant(m.uniform(0, 0.1)), Rgb::Zero(), Rgb::Zero(),
                    Rgb(m.uniform(0.5, 0.9), m.uniform(0.5, 0.9), m.uniform(0.5, 0.9)));
}

/// A floor at z = 0 (split along its diagonal into two triangles), lamps above, and what
/// `add` builds; sites are added by `add` too.
RandomScene with_floor(
    RandomSceneMaker& m,
    const std::function<void(SceneBuilder&, int grey, int lamp, RandomScene&)>& add) {
  SceneBuilder b;
  const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
  const int lamp =
      b.material("lamp", Rgb::Zero(), Rgb(m.uniform(0.5, 2), m.uniform(0.5, 2), m.uniform(0.5, 2)));
  b.polygon({Vec3(-2, -2, 0), Vec3(2, -2, 0), Vec3(2, 2, 0)}, grey);
  b.polygon({Vec3(-2, -2, 0), Vec3(2, 2, 0), Vec3(-2, 2, 0)}, grey);
  RandomScene out;
  add(b, grey, lamp, out);
  out.scene = b.scene();
  return out;
}

/// A lamp facing down at height h over (cx, cy), half-size s.
void lamp_above(SceneBuilder& b, int lamp, double cx, double cy, double h, double s) {
  b.rectangle(cx - s, cx + s, cy - s, cy + s, h, true, lamp);
}

/// A lamp, a wall standing on the floor, and one site on an edge or vertex: 0 on the floor's
/// diagonal, 1 at the floor triangles' shared corner, 2 at the wall's foot.
std::function<RandomScene(RandomSceneMaker&)> on_edges(int which) {
  return [which](RandomSceneMaker& m) {
    return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
      lamp_above(b, lamp, m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(1, 2),
                 m.uniform(0.2, 0.6));
      // A wall standing on the floor along y = w, facing -y, from x = a to e.
      const double w = m.uniform(-0.5, 0.5), a = m.uniform(-1.5, -0.5), e = m.uniform(0.5, 1.5);
      b.polygon({Vec3(a, w, 0), Vec3(e, w, 0), Vec3(e, w, 1), Vec3(a, w, 1)}, grey);
      const double t = m.uniform(-1, 1);
      const Vec3 sites[3] = {Vec3(t, t, 0), Vec3(2, 2, 0), Vec3(0.5 * (a + e), w, 0)};
      out.sites = {{sites[which], Vec3::UnitZ()}};
    });
  };
}

std::vector<Family> families() {
  using C = RandomSceneMaker::Conjunction;
  const auto conjunction = [](C kind) {
    return [kind](RandomSceneMaker& m) { return m.conjunctive_scene(kind); };
  };
  return {
      {"random", "concave and interpenetrating polygons at random", 200,
       [](RandomSceneMaker& m) { return m.random_scene(); }},
      {"three_edges", "three edges at different depths through one apparent point", 60,
       conjunction(C::three_edges)},
      {"vertex_behind", "vertices exactly behind one another", 60, conjunction(C::vertex_behind)},
      {"collinear_edges", "edges on one 3D line; edges in one plane through x", 60,
       conjunction(C::collinear_edges)},
      {"coplanar", "coplanar polygons, overlapping and touching (T-junctions)", 60,
       conjunction(C::coplanar)},
      {"vertex_on_edge", "a vertex on another polygon's edge, in 3D and in projection", 60,
       conjunction(C::vertex_on_edge)},
      {"straddling", "polygons crossing the tangent plane at x", 60,
       [](RandomSceneMaker& m) {
         return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
           lamp_above(b, lamp, m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(1, 2),
                      m.uniform(0.2, 0.6));
           for (int i = 0; i < 4; ++i) {
             // Centred within 0.3 of the floor, tilted: they cut the plane z = 0 near the sites.
             const Vec3 c(m.uniform(-0.8, 0.8), m.uniform(-0.8, 0.8), m.uniform(-0.3, 0.3));
             b.polygon(m.polygon(c, m.unit(), m.uniform(0.3, 0.8)), i == 0 ? lamp : grey);
           }
           for (int i = 0; i < 3; ++i)
             out.sites.push_back({Vec3(m.uniform(-1, 1), m.uniform(-1, 1), 0), Vec3::UnitZ()});
         });
       }},
      {"edge_on", "emitters seen exactly edge-on: their plane holds x", 60,
       [](RandomSceneMaker& m) {
         return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
           const Vec3 x(m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), 0);
           out.sites.push_back({x, Vec3::UnitZ()});
           for (int i = 0; i < 3; ++i) {
             // A polygon whose plane contains x: its normal is perpendicular to c - x.
             Vec3 d;
             do d = m.unit();
             while (d.z() < 0.2);
             const Vec3 c = x + m.uniform(0.5, 1.5) * d;
             b.polygon(m.polygon(c, m.perpendicular(d), m.uniform(0.1, 0.4)), i < 2 ? lamp : grey);
           }
           lamp_above(b, lamp, 0, 0, 2, 0.3);
           // And a lamp in the tangent plane itself (z = 0), beside the site.
           b.rectangle(x.x() + 0.3, x.x() + 0.6, x.y() - 0.2, x.y() + 0.2, 0, false, lamp);
         });
       }},
      {"on_edge", "x on the edge two floor triangles share", 60, on_edges(0)},
      {"on_vertex", "x at the vertex two floor triangles share", 60, on_edges(1)},
      {"wall_foot", "x on the bottom edge of a wall standing on the floor", 60, on_edges(2)},
      {"tiny_and_huge", "polygons from 1e-4 to 1e4 in one scene", 60,
       [](RandomSceneMaker& m) {
         SceneBuilder b;
         const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
         const int lamp = b.material("lamp", Rgb::Zero(), Rgb(1, 1, 1));
         b.rectangle(-1e4, 1e4, -1e4, 1e4, 0, false, grey);  // a huge floor
         // A huge ceiling lamp far away, a tiny lamp and tiny occluders close to the site.
         b.rectangle(-1e4, 1e4, -1e4, 1e4, m.uniform(1e3, 5e3), true, lamp);
         const Vec3 x(m.uniform(-1e-3, 1e-3), m.uniform(-1e-3, 1e-3), 0);
         b.rectangle(x.x() - 1e-4, x.x() + 1e-4, x.y() - 1e-4, x.y() + 1e-4, m.uniform(1e-4, 1e-3),
                     true, lamp);
         for (int i = 0; i < 3; ++i) {
           const Vec3 c =
               x + Vec3(m.uniform(-1e-3, 1e-3), m.uniform(-1e-3, 1e-3), m.uniform(2e-4, 2e-3));
           b.polygon(m.polygon(c, m.unit(), m.uniform(1e-4, 5e-4)), grey);
         }
         RandomScene out{b.scene(), {{x, Vec3::UnitZ()}, {x + Vec3(3e-4, 0, 0), Vec3::UnitZ()}}};
         return out;
       }},
      {"many_occluders", "1000 thin triangles under a large source", 3,
       [](RandomSceneMaker& m) {
         return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
           lamp_above(b, lamp, 0, 0, 2, 1.5);
           for (int i = 0; i < 1000; ++i) {
             const Vec3 c(m.uniform(-1.5, 1.5), m.uniform(-1.5, 1.5), m.uniform(0.2, 1.8));
             const Vec3 along = m.unit(), across = m.perpendicular(along);
             const double length = m.uniform(0.2, 0.5), width = m.uniform(0.005, 0.02);
             b.polygon({c - length * along, c + length * along, c + width * across}, grey);
           }
           for (int i = 0; i < 3; ++i)
             out.sites.push_back({Vec3(m.uniform(-1, 1), m.uniform(-1, 1), 0), Vec3::UnitZ()});
         });
       }},
      {"filters_random", "filters at random: concave, interpenetrating, x on a filter", 60,
       [](RandomSceneMaker& m) {
         RandomScene r = m.random_scene();
         rad::test::make_filters(r.scene, m, 8);
         return r;
       },
       Family::Kind::filters},
      {"filters_conjunctive", "the five conjunctive families with their blockers as filters", 60,
       [](RandomSceneMaker& m) {
         RandomScene r =
             m.conjunctive_scene(static_cast<RandomSceneMaker::Conjunction>(m.integer(0, 4)));
         rad::test::make_filters(r.scene, m, 8);
         return r;
       },
       Family::Kind::filters},
      {"mirror_corner", "two mirror walls meeting in a corner (their depth-2 images coincide)", 30,
       [](RandomSceneMaker& m) {
         return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
           lamp_above(b, lamp, m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(1, 2),
                      m.uniform(0.2, 0.5));
           const int mirror = mirror_material(b, m);
           wall_x(b, 1.5, -2, 1.5, 0, 2, false, mirror);
           wall_y(b, 1.5, -2, 1.5, 0, 2, false, mirror);
           b.polygon(m.polygon(Vec3(0.5, 0.5, m.uniform(0.3, 1)), m.unit(), 0.3), grey);
           for (int i = 0; i < 3; ++i)
             out.sites.push_back({Vec3(m.uniform(-1, 1.4), m.uniform(-1, 1.4), 0), Vec3::UnitZ()});
         });
       },
       Family::Kind::mirrors},
      {"block_on_mirror", "a block standing on a mirror floor: x on its faces near the mirror", 30,
       [](RandomSceneMaker& m) {
         SceneBuilder b;
         const int grey = b.material("grey", Rgb::Constant(0.5), Rgb::Zero());
         const int lamp = b.material("lamp", Rgb::Zero(), Rgb::Ones());
         b.rectangle(-2, 2, -2, 2, 0, false, mirror_material(b, m));
         lamp_above(b, lamp, m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(1.5, 2.5),
                    m.uniform(0.2, 0.5));
         const double s = m.uniform(0.2, 0.5), h = m.uniform(0.2, 0.8);
         b.rectangle(-s, s, -s, s, h, false, grey);  // top
         wall_x(b, s, -s, s, 0, h, true, grey);
         wall_x(b, -s, -s, s, 0, h, false, grey);
         wall_y(b, s, -s, s, 0, h, true, grey);
         wall_y(b, -s, -s, s, 0, h, false, grey);
         wall_x(b, 1.9, -2, 2, 0, 2, false, grey);  // a wall the mirror shows the block on
         RandomScene out{b.scene(), {}};
         for (int i = 0; i < 3; ++i) {
           const double z = i == 0 ? 1e-9 : m.uniform(0, 0.05) * h;  // at the mirror's plane
           out.sites.push_back({Vec3(s, m.uniform(-s, s), z), Vec3::UnitX()});
         }
         out.sites.push_back({Vec3(1.9, m.uniform(-1, 1), m.uniform(0, 1)), -Vec3::UnitX()});
         return out;
       },
       Family::Kind::mirrors},
      {"concave_mirror", "an L-shaped mirror (its triangles coplanar pieces) on a wall", 30,
       [](RandomSceneMaker& m) {
         return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
           lamp_above(b, lamp, m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(1, 2),
                      m.uniform(0.2, 0.5));
           const double t = m.uniform(0.3, 0.8);
           b.polygon({Vec3(1.5, -1, 0.1), Vec3(1.5, -1, 1.5), Vec3(1.5, -1 + t, 1.5),
                      Vec3(1.5, -1 + t, 0.1 + t), Vec3(1.5, 1, 0.1 + t), Vec3(1.5, 1, 0.1)},
                     mirror_material(b, m));
           b.polygon(m.polygon(Vec3(1.0, 0, m.uniform(0.3, 1)), m.unit(), 0.2), grey);
           for (int i = 0; i < 3; ++i)
             out.sites.push_back({Vec3(m.uniform(-1, 1.4), m.uniform(-1, 1), 0), Vec3::UnitZ()});
         });
       },
       Family::Kind::mirrors},
      {"x_on_mirror_plane", "x on a wall in the mirror's plane, and on the mirror's edge", 30,
       [](RandomSceneMaker& m) {
         return with_floor(m, [&](SceneBuilder& b, int grey, int lamp, RandomScene& out) {
           lamp_above(b, lamp, m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(1, 2),
                      m.uniform(0.2, 0.5));
           const double y = m.uniform(-0.5, 0.5);
           wall_x(b, 1.5, -2, y, 0, 2, false, mirror_material(b, m));
           wall_x(b, 1.5, y, 2, 0, 2, false, grey);  // coplanar, beside it
           out.sites.push_back({Vec3(1.5, m.uniform(y, 2), m.uniform(0, 2)), -Vec3::UnitX()});
           out.sites.push_back({Vec3(1.5, y, m.uniform(0, 2)), -Vec3::UnitX()});  // the seam
           out.sites.push_back({Vec3(m.uniform(-1, 1.4), m.uniform(-1, 1), 0), Vec3::UnitZ()});
         });
       },
       Family::Kind::mirrors},
  };
}

bool has_nan(const Rgb& v) { return !v.allFinite(); }

/// max_c |a - b| / max_c |b|, or max_c |a - b| where b is 0.
double relative_difference(const Rgb& a, const Rgb& b) {
  const double scale = b.cwiseAbs().maxCoeff();
  const double d = (a - b).cwiseAbs().maxCoeff();
  return scale > 0 ? d / scale : d;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main() {
  std::printf(
      "| family | stresses | points | hemisphere vs vertex: largest rel. difference | points over "
      "1e-9 "
      "| Monte Carlo (%d rays) vs hemisphere: max / RMS rel. error | NaN (hemisphere / vertex / "
      "MC) "
      "| seconds (hemisphere / vertex / MC) |\n|---|---|---|---|---|---|---|---|\n",
      kMonteCarloSamples);
  const auto all = families();
  for (size_t f = 0; f < all.size(); ++f) {
    const Family& family = all[f];
    int points = 0, over = 0, nan_h = 0, nan_v = 0, nan_mc = 0, mc_points = 0;
    double largest = 0, mc_max = 0, mc_squares = 0, t_h = 0, t_v = 0, t_mc = 0;
    for (int s = 1; s <= family.scenes; ++s) {
      RandomSceneMaker maker(100000 * (f + 1) + s);
      const RandomScene r = family.make(maker);
      const std::vector<rad::EmittingFace> faces = rad::faces_from_polygons(r.scene);
      std::vector<int> filters;
      for (size_t p = 0; p < r.scene.polygons.size(); ++p) {
        if (r.scene.materials[r.scene.polygons[p].material].is_filter())
          filters.push_back(static_cast<int>(p));
      }
      const bool mirrors = family.kind == Family::Kind::mirrors;
      const bool opaque = family.kind == Family::Kind::opaque;
      std::optional<rad::HemisphereGatherer> hemisphere;
      std::optional<rad::VertexTracer> tracer;
      std::optional<rad::LocalPass> hemisphere_pass, vertex_pass;
      if (mirrors) {
        hemisphere_pass.emplace(r.scene, faces, rad::Method::hemisphere);
        vertex_pass.emplace(r.scene, faces, rad::Method::vertex);
      } else {
        if (opaque) hemisphere.emplace(faces, r.scene.tolerance());
        tracer.emplace(r.scene);
      }
      const rad::MonteCarloGatherer monte_carlo(r.scene, faces);
      for (size_t i = 0; i < r.sites.size(); ++i) {
        const auto& site = r.sites[i];
        ++points;
        auto start = Clock::now();
        const Rgb h = mirrors  ? hemisphere_pass->gather(site.x, site.n, 0).irradiance
                      : opaque ? hemisphere->gather(site.x, site.n).irradiance
                               : rad::test::by_subsets(r.scene, faces, filters, site.x, site.n);
        t_h += seconds_since(start);
        start = Clock::now();
        const Rgb v = mirrors ? vertex_pass->gather(site.x, site.n, 0).irradiance
                              : tracer->gather(site.x, site.n).irradiance;
        t_v += seconds_since(start);
        start = Clock::now();
        const Rgb mc = monte_carlo.gather(site.x, site.n, kMonteCarloSamples, 1000 * s + i);
        t_mc += seconds_since(start);
        nan_h += has_nan(h);
        nan_v += has_nan(v);
        nan_mc += has_nan(mc);
        const double d = has_nan(h) || has_nan(v) ? INFINITY : relative_difference(v, h);
        largest = std::max(largest, d);
        over += d > 1e-9;
        if (h.maxCoeff() > 0 && !has_nan(mc)) {
          const double e = relative_difference(mc, h);
          mc_max = std::max(mc_max, e);
          mc_squares += e * e;
          ++mc_points;
        }
      }
    }
    std::printf("| %s | %s | %d | %.2e | %d | %.2e / %.2e | %d / %d / %d | %.3f / %.3f / %.3f |\n",
                family.name, family.stresses, points, largest, over, mc_max,
                std::sqrt(mc_squares / std::max(mc_points, 1)), nan_h, nan_v, nan_mc, t_h, t_v,
                t_mc);
    std::fflush(stdout);
  }
  return 0;
}
