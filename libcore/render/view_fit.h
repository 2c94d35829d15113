// The fitted camera: a view chosen so that the water is seen, not only the walls
// that hold it. Water in a tank, behind a dam or among houses lies below the top of
// the solids around it, and a view from low above the horizon sees the outside of
// those walls only. Candidate views around the scene and above it are scored by how
// much of the water, and of the floor it spreads over, no solid hides from them;
// the rays are cast on the host against the solids' triangles (a bounding volume
// hierarchy), so that the choice is the same on every machine and every device.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/geometry.h"
#include "render/camera.h"
#include "render/render_settings.h"
#include "render/solids.h"

namespace bw::render {

// Triangles that hide what lies behind them, for segment and ray queries.
class Occluders {
 public:
  Occluders() = default;
  explicit Occluders(const TriangleSoup& soup);
  std::size_t size() const { return triangles_.size(); }
  // Whether a triangle crosses the segment from a to b, its two ends left out.
  bool blocks(const Vec3d& a, const Vec3d& b) const;
  // Ray parameter of the first triangle along origin + t * direction for t in
  // (0, t_max]; t_max when there is none.
  double first_hit(const Vec3d& origin, const Vec3d& direction, double t_max) const;

 private:
  struct Node {
    Aabb box;
    std::uint32_t first = 0, count = 0;  // a leaf's triangles; count 0: an inner node
    std::uint32_t right = 0;             // an inner node's second child (the first follows it)
  };
  std::uint32_t build(std::uint32_t first, std::uint32_t count, std::vector<Vec3d>& centroids);
  // Smallest t in (t_min, t_max) where the ray meets a triangle; t_max when none.
  // With `any`, the first one found.
  double cast(const Vec3d& origin, const Vec3d& direction, double t_min, double t_max, bool any) const;

  std::vector<std::array<Vec3d, 3>> triangles_;
  std::vector<Node> nodes_;
};

// What the fitted view is chosen from: the reference frame of a sequence.
struct ViewFitInput {
  Aabb solids;                         // bounds of the solids, placed as in the reference frame
  const Occluders* occluders = nullptr;  // their triangles (null: nothing hides anything)
  std::vector<Vec3d> water;            // the reference frame's particles
  double particle_radius = 0.01;
  std::optional<double> ground_height;  // the floor where no solid lies below; none: no ground
};

struct FittedView {
  Camera camera;
  double azimuth = kFitAzimuth, elevation = kFitElevation;  // degrees, as in view_direction
  Aabb framed;              // the box the camera holds in view
  // Fractions the camera sees, hidden by no solid: of the water's particles, of the
  // probes on the water's surface, and of those on the floor it can reach (-1: no
  // such probes, or no water).
  double water_seen = 0;
  double surface_seen = -1, floor_seen = -1;
};

// The view of the fitted camera (docs/rendering.md, "[camera]"):
//  - framed box: the water and the solids; when the scene's diagonal is more than 4
//    times the water's, the water and one water diagonal around it only;
//  - probes on a 24 x 24 grid over the framed box: in a cell with water, the top of
//    its highest particle (the water's surface); in a dry cell, the first solid
//    below (or the ground) where that lies no higher than the water's top: the
//    floor the water can flow onto in later frames;
//  - candidates: azimuths every 30 degrees starting at kFitAzimuth and going
//    alternately either side, at elevations 40, 55, 70 and 85 degrees in that
//    order, each at the distance that holds the framed box;
//  - score: the smaller of the fractions of surface probes and of floor probes that
//    the camera sees (in the image, hidden by no solid);
//  - the first candidate with a score of 0.8 or more, or failing that the best.
// Without water, the default direction frames the solids.
FittedView fit_view(const ViewFitInput& in, double fov_degrees, double aspect);

// Fraction of `points` (at most 1024 of them, evenly strided) that project
// into the image of a camera and that no solid hides from it. 0 for no points.
double fraction_seen(const Camera& camera, double aspect, const std::vector<Vec3d>& points,
                     const Occluders* occluders);

}  // namespace bw::render
