#include "common.glsl"
// A particle as a point sprite large enough to cover its sphere's silhouette, from
// the positions in a storage buffer (one vertex per particle, gl_VertexID).
layout(std430, binding = 1) readonly buffer Particles { float p_position[]; };
// 1 for a foam particle (render/particle_classes.h), 0 for water.
layout(std430, binding = 2) readonly buffer Foam { float p_foam[]; };

flat out vec3 v_center;   // sphere centre, view space
flat out float v_foam;

void main() {
  int i = gl_VertexID;
  vec3 world = vec3(p_position[3 * i], p_position[3 * i + 1], p_position[3 * i + 2]);
  vec3 c = (u_view * vec4(world, 1.0)).xyz;
  float r = u_camera.w;
  float dist = length(c);
  v_center = c;
  v_foam = p_foam[i];
  gl_Position = u_proj * vec4(c, 1.0);
  // The fluid mask takes the sprite's constant depth (window depth 0.0005, in front
  // of the full-screen passes' 0.5); the sphere's own depth goes to the colour target.
  gl_Position.z = -0.999 * gl_Position.w;
  // The camera inside a sphere, or a sphere behind the near plane: nothing to draw.
  if (dist <= r * 1.001 || -c.z < u_camera.x) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    gl_PointSize = 1.0;
    return;
  }
  // The silhouette is the tangent cone of half-angle alpha around the direction to
  // the centre, theta off the view axis: on screen it reaches tan(theta + alpha) -
  // tan(theta) away from the projected centre radially, tan(alpha) / cos(theta)
  // across (in units of the focal length).
  float alpha = asin(r / dist);
  float theta = acos(clamp(-c.z / dist, -1.0, 1.0));
  float radial = tan(min(theta + alpha, 1.5)) - tan(theta);
  float across = tan(alpha) / cos(theta);
  // One pixel of margin: pixel centres, not areas, decide coverage.
  gl_PointSize = min(2.0 * u_camera.z * max(radial, across) + 1.0, u_misc.y);
}
