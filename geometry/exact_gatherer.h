#pragma once
/// The one small interface of the two exact gatherers (hemisphere projection, 004 §3, in
/// hemisphere/; vertex tracing, 001, in vertex/), through which the local pass drives either
/// (localpass/local_pass.h). A gather at a point x with unit normal n runs in steps: each step
/// names faces that radiate and the faces that may hide them; after it, the session holds the
/// exact irradiance from every face that has radiated so far.
#include <memory>
#include <optional>
#include <vector>

#include "geometry/vec.h"

namespace rad {

/// The running total of a gather session.
struct ExactGatherTotal {
  Rgb irradiance = Rgb::Zero();  ///< Exact H from the faces radiated so far [W/m^2].
  /// Form factor covered by their visible parts, where the method knows it (hemisphere).
  std::optional<double> covered;
};

/// One gather at one point. Not thread-safe; one per point and thread.
class ExactGatherSession {
 public:
  virtual ~ExactGatherSession() = default;
  /// Lets the faces of `radiating` radiate their exitance, seen through everything that may
  /// hide them: each face that may hide part of one of them must be in `radiating` or
  /// `occluders` of this call (the local pass's culling lists them). Faces radiate once: a face
  /// radiated by an earlier step must not radiate again. Returns the total so far.
  virtual ExactGatherTotal step(const std::vector<int>& radiating,
                                const std::vector<int>& occluders) = 0;
  /// Faces projected or traced so far, counted with repetition across steps where a method
  /// starts each step afresh (vertex tracing): the work done.
  virtual int projected() const = 0;
};

/// An exact gatherer over a fixed list of faces (geometry/emitting_face.h), thread-safe.
class ExactGatherer {
 public:
  virtual ~ExactGatherer() = default;
  virtual std::unique_ptr<ExactGatherSession> start(const Vec3& x, const Vec3& n) const = 0;
  /// True when a step reuses the work of the earlier ones (the hemisphere's projection is
  /// incremental), so that small steps cost no more in total than one large one.
  virtual bool incremental() const = 0;
  /// True when ExactGatherTotal::covered is reported.
  virtual bool reports_coverage() const = 0;
  virtual int face_count() const = 0;
};

/// Exact irradiance at x from every face, each radiating its exitance from its front and
/// occluding from both sides: one step with every face radiating. Thread-safe.
inline Rgb exact_irradiance(const ExactGatherer& gatherer, const Vec3& x, const Vec3& n) {
  std::vector<int> all(static_cast<size_t>(gatherer.face_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return gatherer.start(x, n)->step(all, {}).irradiance;
}

}  // namespace rad
