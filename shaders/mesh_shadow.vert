#include "common.glsl"
// Solids seen from the sun, for the shadow map.
layout(location = 0) in vec3 a_position;
void main() { gl_Position = u_light_proj * u_light_view * vec4(a_position, 1.0); }
