// One triangle that covers the viewport at normalized depth u_z: 0 by default
// (window depth 0.5, which the passes over fluid pixels test against the fluid
// mask), 1 for the sky (the far plane). Passes of whole images draw it.
uniform float u_z;
out vec2 v_uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, u_z, 1.0);
}
