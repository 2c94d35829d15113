// Camera math of the renderer: OpenGL conventions (right-handed view space looking
// down -z, clip space z in [-1, 1]), column vectors, matrices as Eigen 4x4 doubles.
#pragma once

#include "common/geometry.h"
#include "render/render_settings.h"

namespace bw::render {

using Mat4d = Eigen::Matrix4d;

// World to view space.
Mat4d look_at(const Vec3d& position, const Vec3d& target, const Vec3d& up);
// Perspective projection; fov is vertical, in degrees; near, far > 0.
Mat4d perspective(double fov_degrees, double aspect, double near, double far);
// Orthographic projection of the box [l, r] x [b, t] x [-far, -near] of view space.
Mat4d orthographic(double l, double r, double b, double t, double near, double far);

// Azimuth and elevation of the default fitted view (degrees): from 30 degrees left of
// -y and 40 degrees above the horizon, a three-quarter view that shows the front and
// the top of walls standing across x, and over them. view_fit.h chooses among others
// when solids hide the water from this one.
constexpr double kFitAzimuth = -30.0;
constexpr double kFitElevation = 40.0;

// Unit vector from a target towards a camera seen at `azimuth` degrees (0: from -y,
// positive towards +x) and `elevation` degrees above the horizon.
Vec3d view_direction(double azimuth_degrees, double elevation_degrees);

// A camera that looks at the box's centre from the given azimuth and elevation, far
// enough that all eight corners of the box are in view, with a margin. An empty box
// gives the default camera.
Camera fit_camera(const Aabb& box, double fov_degrees, double aspect, double azimuth_degrees = kFitAzimuth,
                  double elevation_degrees = kFitElevation);

// Near and far planes that hold the box as seen from the camera, with a floor on near
// so that depth precision stays usable.
void clip_planes(const Camera& camera, const Aabb& box, double& near, double& far);

}  // namespace bw::render
