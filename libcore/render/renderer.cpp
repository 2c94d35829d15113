#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

#include "bw_render_shaders/embedded.h"

#include "common/error.h"
#include "render/camera.h"
#include "render/gl_api.h"
#include "render/particle_classes.h"

namespace bw::render {
namespace {

// Side of the sun's shadow maps (texels). Solids are few triangles, so their map can
// be fine; the water's map is drawn from every particle, so it is coarser.
constexpr int kSolidShadowSize = 2048;
constexpr int kFluidShadowSize = 512;
// The ground plane spans this many camera distances around the camera's target: far
// enough that its edge hides in the haze at the horizon.
constexpr double kGroundExtent = 60.0;
// Haze: the ground fades to the horizon colour over this many camera distances.
constexpr double kFogDistances = 6.0;
// Narrow-range filter, in particle radii: samples more than kRangeRatio nearer than
// the centre belong to another layer (a drop in front of the pool: a few radii apart);
// samples behind, or no fluid, are clamped to the centre's depth plus kClampRatio
// (Truong and Yuksel's clamp of one radius, which rounds silhouettes off).
constexpr double kRangeRatio = 5.0;
constexpr double kClampRatio = 1.0;
// The water's shadow is soft and its map coarse: beyond this many particles, only
// every k-th one is drawn into it (k up to kMaxShadowStride), its radius grown by
// cbrt(k) so that it carries the volume of the k - 1 left out.
constexpr std::size_t kShadowParticles = 20000;
constexpr std::size_t kMaxShadowStride = 8;
// Bilateral filter: width of the Gaussian on depth differences, in particle radii.
constexpr double kBilateralRangeRatio = 1.0;

// Every layer but the final image is this many pixels larger on each side: a point
// sprite is dropped when its centre leaves the view, so spheres up to this radius
// that straddle the border stay whole, and the filters see past the edge.
constexpr int kGuardPixels = 16;
// Eye distance where there is no fluid (shaders/common.glsl kNoFluid).
constexpr float kNoFluid = 1e30f;
// Entries of the colour map the shader interpolates between (wall_paint.h).
constexpr int kPaintColors = 256;

constexpr double kPi = 3.14159265358979323846;

// Mirrors `uniform Frame` of shaders/common.glsl (std140: mat4 and vec4 only).
struct FrameUniforms {
  float view[16], proj[16], inv_view[16], light_view[16], light_proj[16];
  float viewport[4], camera[4], light_dir[4], light_color[4], sky_color[4], horizon_color[4];
  float ground_color[4], ground[4], fluid_color[4], absorption[4], camera_position[4], filter[4], misc[4];
  float shadow[4], spray[4];
};
static_assert(sizeof(FrameUniforms) == (5 * 16 + 15 * 4) * sizeof(float), "std140 layout");

void put(float* out, const Mat4d& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[4 * c + r] = static_cast<float>(m(r, c));  // column-major
}
void put(float* out, const Vec3d& v, double w) {
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(v[k]);
  out[3] = static_cast<float>(w);
}
void put(float* out, double a, double b, double c, double d) {
  out[0] = static_cast<float>(a), out[1] = static_cast<float>(b), out[2] = static_cast<float>(c),
  out[3] = static_cast<float>(d);
}

// Resolves `#include "name"` lines against the embedded files, once per file.
void expand(const std::string& name, std::string& out, std::set<std::string>& seen) {
  const std::string_view text = shaders::embedded_file(name);
  if (text.empty()) fail_run("shader '{}' is not embedded in this executable", name);
  if (!seen.insert(name).second) return;
  std::istringstream in{std::string(text)};
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.rfind("#include \"", 0) == 0) {
      const std::size_t end = line.find('"', 10);
      expand(line.substr(10, end - 10), out, seen);
      out += "#line " + std::to_string(number + 1) + "\n";
    } else {
      out += line + "\n";
    }
  }
}

GLuint compile(GLenum stage, const std::string& name) {
  std::string source = "#version 450 core\n";
  std::set<std::string> seen;
  expand(name, source, seen);
  const GLuint shader = gl::CreateShader(stage);
  const char* text = source.c_str();
  gl::ShaderSource(shader, 1, &text, nullptr);
  gl::CompileShader(shader);
  GLint ok = 0;
  gl::GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl::GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl::DeleteShader(shader);
    std::string one_line = log;
    std::replace(one_line.begin(), one_line.end(), '\n', ' ');
    fail_run("shader {} does not compile: {}", name, one_line);
  }
  return shader;
}

class Program {
 public:
  Program() = default;
  Program(const std::string& vertex, const std::string& fragment) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
    id_ = gl::CreateProgram();
    gl::AttachShader(id_, vs);
    gl::AttachShader(id_, fs);
    gl::LinkProgram(id_);
    gl::DeleteShader(vs);
    gl::DeleteShader(fs);
    GLint ok = 0;
    gl::GetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      gl::GetProgramInfoLog(id_, sizeof log, nullptr, log);
      std::string one_line = log;
      std::replace(one_line.begin(), one_line.end(), '\n', ' ');
      fail_run("shaders {} + {} do not link: {}", vertex, fragment, one_line);
    }
  }
  Program(Program&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Program& operator=(Program&& o) noexcept {
    std::swap(id_, o.id_);
    return *this;
  }
  ~Program() {
    if (id_) gl::DeleteProgram(id_);
  }
  GLuint id() const { return id_; }
  void use() const { gl::UseProgram(id_); }
  void set(const char* name, int value) const { gl::ProgramUniform1i(id_, gl::GetUniformLocation(id_, name), value); }
  void set(const char* name, float value) const {
    gl::ProgramUniform1f(id_, gl::GetUniformLocation(id_, name), value);
  }

 private:
  GLuint id_ = 0;
};

struct Texture {
  GLuint id = 0;
  Texture() = default;
  Texture(GLenum format, int width, int height, bool linear) {
    gl::CreateTextures(GL_TEXTURE_2D, 1, &id);
    gl::TextureStorage2D(id, 1, format, width, height);
    gl::TextureParameteri(id, GL_TEXTURE_MIN_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    gl::TextureParameteri(id, GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    gl::TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl::TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  Texture(Texture&& o) noexcept : id(o.id) { o.id = 0; }
  Texture& operator=(Texture&& o) noexcept {
    std::swap(id, o.id);
    return *this;
  }
  ~Texture() {
    if (id) gl::DeleteTextures(1, &id);
  }
};

struct Framebuffer {
  GLuint id = 0;
  Framebuffer() = default;
  Framebuffer(std::initializer_list<GLuint> colors, GLuint depth, const char* what) {
    gl::CreateFramebuffers(1, &id);
    std::vector<GLenum> buffers;
    for (GLuint c : colors) {
      const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
      gl::NamedFramebufferTexture(id, attachment, c, 0);
      buffers.push_back(attachment);
    }
    if (depth) gl::NamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth, 0);
    if (buffers.empty()) {
      const GLenum none = GL_NONE;
      gl::NamedFramebufferDrawBuffers(id, 1, &none);
      gl::NamedFramebufferReadBuffer(id, GL_NONE);
    } else {
      gl::NamedFramebufferDrawBuffers(id, static_cast<GLsizei>(buffers.size()), buffers.data());
    }
    const GLenum status = gl::CheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) fail_run("the {} framebuffer is incomplete (0x{:x})", what, status);
  }
  Framebuffer(Framebuffer&& o) noexcept : id(o.id) { o.id = 0; }
  Framebuffer& operator=(Framebuffer&& o) noexcept {
    std::swap(id, o.id);
    return *this;
  }
  ~Framebuffer() {
    if (id) gl::DeleteFramebuffers(1, &id);
  }
};

struct Buffer {
  GLuint id = 0;
  std::size_t capacity = 0;
  Buffer() { gl::CreateBuffers(1, &id); }
  ~Buffer() { gl::DeleteBuffers(1, &id); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  void upload(const void* data, std::size_t bytes) {
    // Never empty: a zero-sized storage buffer is an error on some drivers.
    static const float kZero[4] = {};
    gl::NamedBufferData(id, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, sizeof kZero)),
                        bytes ? data : kZero, GL_STREAM_DRAW);
    capacity = bytes;
  }
};

void check_gl(const char* where) {
  const GLenum e = gl::GetError();
  if (e != GL_NO_ERROR) fail_run("OpenGL error 0x{:x} in {}", e, where);
}

}  // namespace

struct Renderer::Impl {
  RenderSettings settings;
  int width = 0, height = 0;            // the image
  int full_width = 0, full_height = 0;  // the layers, with the guard band
  float max_point_size = 64;

  Program sky, mesh, mesh_shadow, sprite_fluid, sprite_shadow, filter_narrow, filter_narrow_2d, filter_bilateral,
      blur_thickness, blur_shadow, normals, composite_scene, composite, sprite_spray;

  Texture scene_color, scene_depth, fluid_depth, fluid_mask, thickness, thickness_blur, filtered[2], normal_map,
      final_color;
  Texture shadow_depth, shadow_thickness, shadow_front, shadow_blur;
  Framebuffer scene_fb, fluid_fb, filter_fb[2], thickness_fb[2], normals_fb, final_fb, shadow_depth_fb,
      shadow_fluid_fb, shadow_blur_fb[2];
  GLuint smoothed = 0;  // the texture holding the smoothed depth after the last render

  Buffer uniforms, particles, foam, solid_vertices, solid_rows, ground_vertices;
  Buffer paint_points, paint_cells, paint_start, paint_colors;
  GLuint vao_empty = 0, vao_mesh = 0, vao_ground = 0;

  bool profiling = false;
  std::vector<std::pair<std::string, double>> times;
  std::chrono::steady_clock::time_point mark;
  // Ends the pass `name` when profiling.
  void lap(const char* name) {
    if (!profiling) return;
    gl::Finish();
    const auto now = std::chrono::steady_clock::now();
    times.emplace_back(name, std::chrono::duration<double, std::milli>(now - mark).count());
    mark = now;
  }

  void build();
  void set_mesh_layout(GLuint vao, GLuint buffer);
  void set_paint(const RenderInput& in);
  void draw_triangles(GLuint vao, std::size_t vertex_count);
};

void Renderer::Impl::set_mesh_layout(GLuint vao, GLuint buffer) {
  gl::VertexArrayVertexBuffer(vao, 0, buffer, 0, 9 * sizeof(float));
  for (GLuint a = 0; a < 3; ++a) {
    gl::EnableVertexArrayAttrib(vao, a);
    gl::VertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
    gl::VertexArrayAttribBinding(vao, a, 0);
  }
}

void Renderer::Impl::set_paint(const RenderInput& in) {
  const bool paint = settings.solids == SolidColoring::kWallPressure && in.paint;
  mesh.set("u_paint", paint ? 1 : 0);
  // Bound in every frame: a program's storage blocks have buffers whether it reads them or not.
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, paint_points.id);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, paint_cells.id);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, paint_start.id);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, paint_colors.id);
  if (!paint) return;
  const PaintTable& t = *in.paint;
  paint_points.upload(t.points.data(), t.points.size() * sizeof(float));
  paint_cells.upload(t.cells.data(), t.cells.size() * sizeof(std::int32_t));
  paint_start.upload(t.start.data(), t.start.size() * sizeof(std::uint32_t));
  mesh.set("u_paint_reach", t.reach);
  gl::ProgramUniform1ui(mesh.id(), gl::GetUniformLocation(mesh.id(), "u_paint_mask"), t.mask);
  gl::ProgramUniform2f(mesh.id(), gl::GetUniformLocation(mesh.id(), "u_paint_range"),
                       static_cast<float>(in.paint_scale.min), static_cast<float>(in.paint_scale.max));
  mesh.set("u_paint_colors", kPaintColors);
}

void Renderer::Impl::build() {
  sky = Program("fullscreen.vert", "sky.frag");
  mesh = Program("mesh.vert", "mesh.frag");
  mesh_shadow = Program("mesh_shadow.vert", "empty.frag");
  sprite_fluid = Program("sprite.vert", "sprite_fluid.frag");
  sprite_shadow = Program("sprite_shadow.vert", "sprite_shadow.frag");
  filter_narrow = Program("fullscreen.vert", "filter_narrow_range.frag");
  filter_narrow_2d = Program("fullscreen.vert", "filter_narrow_range_2d.frag");
  filter_bilateral = Program("fullscreen.vert", "filter_bilateral.frag");
  blur_thickness = Program("fullscreen.vert", "blur_thickness.frag");
  blur_shadow = Program("fullscreen.vert", "blur_shadow.frag");
  normals = Program("fullscreen.vert", "normals.frag");
  composite_scene = Program("fullscreen.vert", "composite_scene.frag");
  composite = Program("fullscreen.vert", "composite.frag");
  sprite_spray = Program("sprite_spray.vert", "sprite_spray.frag");
  sky.set("u_z", 1.0f);

  const int w = full_width, h = full_height;
  scene_color = Texture(GL_RGBA16F, w, h, true);
  scene_depth = Texture(GL_DEPTH_COMPONENT32F, w, h, false);
  fluid_depth = Texture(GL_R32F, w, h, false);
  fluid_mask = Texture(GL_DEPTH_COMPONENT32F, w, h, false);
  // Thickness of the water and (second channel) of its foam.
  thickness = Texture(GL_RG32F, w, h, false);
  thickness_blur = Texture(GL_RG32F, w, h, false);
  filtered[0] = Texture(GL_R32F, w, h, false);
  filtered[1] = Texture(GL_R32F, w, h, false);
  normal_map = Texture(GL_RGBA16F, w, h, false);
  final_color = Texture(GL_RGBA8, w, h, false);
  shadow_depth = Texture(GL_DEPTH_COMPONENT32F, kSolidShadowSize, kSolidShadowSize, true);
  gl::TextureParameteri(shadow_depth.id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  gl::TextureParameteri(shadow_depth.id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  shadow_thickness = Texture(GL_R32F, kFluidShadowSize, kFluidShadowSize, true);
  shadow_front = Texture(GL_R32F, kFluidShadowSize, kFluidShadowSize, false);
  shadow_blur = Texture(GL_R32F, kFluidShadowSize, kFluidShadowSize, false);

  scene_fb = Framebuffer({scene_color.id}, scene_depth.id, "scene");
  // Every pass after the particles' writes fluid pixels only: the fluid mask is the
  // depth buffer of their framebuffers.
  fluid_fb = Framebuffer({fluid_depth.id, thickness.id}, fluid_mask.id, "fluid");
  thickness_fb[0] = Framebuffer({thickness_blur.id}, fluid_mask.id, "thickness");
  thickness_fb[1] = Framebuffer({thickness.id}, fluid_mask.id, "thickness");
  filter_fb[0] = Framebuffer({filtered[0].id}, fluid_mask.id, "filter");
  filter_fb[1] = Framebuffer({filtered[1].id}, fluid_mask.id, "filter");
  normals_fb = Framebuffer({normal_map.id}, fluid_mask.id, "normals");
  final_fb = Framebuffer({final_color.id}, fluid_mask.id, "final");
  shadow_depth_fb = Framebuffer({}, shadow_depth.id, "shadow");
  shadow_fluid_fb = Framebuffer({shadow_thickness.id, shadow_front.id}, 0, "water shadow");
  shadow_blur_fb[0] = Framebuffer({shadow_blur.id}, 0, "water shadow blur");
  shadow_blur_fb[1] = Framebuffer({shadow_thickness.id}, 0, "water shadow blur");

  gl::CreateVertexArrays(1, &vao_empty);
  gl::CreateVertexArrays(1, &vao_mesh);
  gl::CreateVertexArrays(1, &vao_ground);
  set_mesh_layout(vao_mesh, solid_vertices.id);
  set_mesh_layout(vao_ground, ground_vertices.id);
  // The solids' rows (wall_paint.h), an integer per vertex from a second buffer.
  gl::VertexArrayVertexBuffer(vao_mesh, 1, solid_rows.id, 0, sizeof(std::int32_t));
  gl::EnableVertexArrayAttrib(vao_mesh, 3);
  gl::VertexArrayAttribIFormat(vao_mesh, 3, 1, GL_INT, 0);
  gl::VertexArrayAttribBinding(vao_mesh, 3, 1);
  const std::vector<float> colors = paint_colors_linear(kPaintColors);
  paint_colors.upload(colors.data(), colors.size() * sizeof(float));
  for (Buffer* b : {&paint_points, &paint_cells, &paint_start}) b->upload(nullptr, 0);
  float range[2] = {1, 64};
  gl::GetFloatv(GL_POINT_SIZE_RANGE, range);
  max_point_size = range[1];
  gl::Enable(GL_PROGRAM_POINT_SIZE);
  check_gl("set-up");
}

void Renderer::Impl::draw_triangles(GLuint vao, std::size_t vertex_count) {
  if (vertex_count == 0) return;
  gl::BindVertexArray(vao);
  gl::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertex_count));
}

Renderer::Renderer(GlContext& context, const RenderSettings& settings) : impl_(std::make_unique<Impl>()) {
  (void)context;  // proves a context is current
  settings.validate();
  impl_->settings = settings;
  impl_->width = settings.width;
  impl_->height = settings.height;
  impl_->full_width = settings.width + 2 * kGuardPixels;
  impl_->full_height = settings.height + 2 * kGuardPixels;
  impl_->build();
}

Renderer::~Renderer() {
  if (impl_) {
    gl::DeleteVertexArrays(1, &impl_->vao_empty);
    gl::DeleteVertexArrays(1, &impl_->vao_mesh);
    gl::DeleteVertexArrays(1, &impl_->vao_ground);
  }
}

Image Renderer::render(const RenderInput& in) {
  Impl& r = *impl_;
  const RenderSettings& s = r.settings;
  const int w = r.width, h = r.height;
  const int fw = r.full_width, fh = r.full_height;
  if (!(in.particle_radius > 0)) fail_run("render: particle radius {} is not positive", in.particle_radius);
  r.times.clear();
  r.mark = std::chrono::steady_clock::now();

  // ---- geometry of this frame: particles, solids, ground, bounds
  // Particles with a non-finite coordinate (a simulation that blew up) are left out.
  // With spray on, each is water, foam or spray by its neighbours in this frame;
  // the buffer holds the water and foam in their order, then the spray in theirs.
  const double spacing =
      in.particle_spacing > 0 ? in.particle_spacing : in.particle_radius / s.particle_radius_factor;
  std::vector<ParticleClass> classes;
  if (s.spray) {
    ClassifyParams params;
    params.spacing = spacing;
    params.spray_neighbours = s.spray_neighbours;
    params.foam_neighbours = s.foam_neighbours;
    classes = classify_particles(in.x, in.y, in.z, in.count, params);
  }
  std::vector<float> positions, spray_positions, foam_flags;
  positions.reserve(3 * in.count);
  foam_flags.reserve(in.count);
  Aabb content;
  for (std::size_t i = 0; i < in.count; ++i) {
    if (!std::isfinite(in.x[i]) || !std::isfinite(in.y[i]) || !std::isfinite(in.z[i])) continue;
    const ParticleClass c = classes.empty() ? ParticleClass::kWater : classes[i];
    if (c == ParticleClass::kSpray) {
      spray_positions.insert(spray_positions.end(), {in.x[i], in.y[i], in.z[i]});
    } else {
      positions.insert(positions.end(), {in.x[i], in.y[i], in.z[i]});
      foam_flags.push_back(c == ParticleClass::kFoam ? 1.0f : 0.0f);
    }
    content.add(Vec3d(in.x[i], in.y[i], in.z[i]));
  }
  const std::size_t count = positions.size() / 3;  // water and foam
  const std::size_t spray_count = spray_positions.size() / 3;
  positions.insert(positions.end(), spray_positions.begin(), spray_positions.end());
  if (!content.empty()) {
    content.min.array() -= in.particle_radius;
    content.max.array() += in.particle_radius;
  }
  r.particles.upload(positions.data(), positions.size() * sizeof(float));
  r.foam.upload(foam_flags.data(), foam_flags.size() * sizeof(float));
  std::size_t solid_vertex_count = 0;
  if (in.solids && !in.solids->vertices.empty()) {
    r.solid_vertices.upload(in.solids->vertices.data(), in.solids->vertices.size() * sizeof(float));
    solid_vertex_count = in.solids->vertices.size() / 9;
    if (in.solids->solid.size() == solid_vertex_count) {
      r.solid_rows.upload(in.solids->solid.data(), solid_vertex_count * sizeof(std::int32_t));
    } else {  // a soup made without rows: no solid's particles colour it
      const std::vector<std::int32_t> none(solid_vertex_count, -1);
      r.solid_rows.upload(none.data(), none.size() * sizeof(std::int32_t));
    }
    const Aabb b = in.solids->bounds();
    if (!b.empty()) content.add(b.min), content.add(b.max);
  }
  const Camera& cam = in.camera;
  const double cam_distance = (cam.target - cam.position).norm();

  // The ground depends on the camera only, so that what stands on it changes no
  // pixel of it but those it covers or shades.
  std::vector<float> ground;
  if (s.ground) {
    const Vec3d c = cam.target;
    const double half = kGroundExtent * cam_distance;
    const double gz = in.ground_height;
    const double corners[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
    for (const auto& k : corners) {
      const float v[9] = {static_cast<float>(c.x() + k[0] * half), static_cast<float>(c.y() + k[1] * half),
                          static_cast<float>(gz), 0, 0, 1, static_cast<float>(s.ground_color.x()),
                          static_cast<float>(s.ground_color.y()), static_cast<float>(s.ground_color.z())};
      ground.insert(ground.end(), v, v + 9);
    }
    r.ground_vertices.upload(ground.data(), ground.size() * sizeof(float));
  }

  // Clip planes: everything the camera may see, the ground up to the haze.
  Aabb visible = content;
  if (s.ground) {
    const double reach = kFogDistances * 4 * cam_distance;
    visible.add(Vec3d(cam.position.x() - reach, cam.position.y() - reach, in.ground_height));
    visible.add(Vec3d(cam.position.x() + reach, cam.position.y() + reach, in.ground_height));
  }
  if (visible.empty()) visible.add(cam.target);
  double near = 0, far = 0;
  clip_planes(cam, visible, near, far);
  // The water and the solids need depth precision; the ground's far reaches do not.
  // Near comes from what is close to the camera, not from the ground.
  if (!content.empty()) {
    double content_near = 0, content_far = 0;
    clip_planes(cam, content, content_near, content_far);
    near = std::max(std::min(near, content_near), far * 1e-5);
  }
  // The layers see a little more than the image: the same focal length over the
  // guard band.
  const double half_tan = std::tan(cam.fov_degrees * kPi / 360.0);
  const double full_fov = 360.0 / kPi * std::atan(half_tan * fh / h);
  const Mat4d view = look_at(cam.position, cam.target, cam.up);
  const Mat4d proj = perspective(full_fov, static_cast<double>(fw) / fh, near, far);
  const double focal_px = 0.5 * h / half_tan;

  // Sun: an orthographic view along the light that holds the content and the
  // shadows it throws onto the ground.
  const Vec3d light_dir = s.light.direction.normalized();
  Aabb shadow_box = content;
  if (!content.empty() && s.ground && light_dir.z() < -1e-3) {
    for (int i = 0; i < 8; ++i) {
      const Vec3d corner((i & 1) ? content.max.x() : content.min.x(), (i & 2) ? content.max.y() : content.min.y(),
                         (i & 4) ? content.max.z() : content.min.z());
      const double t = (in.ground_height - corner.z()) / light_dir.z();
      if (t > 0) shadow_box.add(corner + t * light_dir);
    }
  }
  if (shadow_box.empty()) shadow_box.add(cam.target);
  // The light's frame is a fixed rotation; its square is sized in steps of 2^(1/4) and
  // placed on whole texels of the water's (coarser) map, so that shadows do not
  // shimmer from frame to frame as the content moves.
  const Vec3d light_up = std::abs(light_dir.z()) < 0.99 ? Vec3d(0, 0, 1) : Vec3d(0, 1, 0);
  const Mat4d light_view = look_at(Vec3d::Zero(), light_dir, light_up);
  Aabb light_box;
  for (int i = 0; i < 8; ++i) {
    const Vec3d corner((i & 1) ? shadow_box.max.x() : shadow_box.min.x(),
                       (i & 2) ? shadow_box.max.y() : shadow_box.min.y(),
                       (i & 4) ? shadow_box.max.z() : shadow_box.min.z());
    light_box.add((light_view * Eigen::Vector4d(corner.x(), corner.y(), corner.z(), 1)).head<3>());
  }
  const Vec3d light_extent = light_box.extent();
  const double half_fit = std::max({0.5 * light_extent.x(), 0.5 * light_extent.y(), 1e-3}) * 1.02;
  const double half_side = std::exp2(std::ceil(4 * std::log2(half_fit)) / 4);
  const double snap = 2 * half_side / kFluidShadowSize;
  const double cx = snap * std::round(0.5 * (light_box.min.x() + light_box.max.x()) / snap);
  const double cy = snap * std::round(0.5 * (light_box.min.y() + light_box.max.y()) / snap);
  // View-space z of the box runs from min.z (far) to max.z (near); a margin around it.
  const double depth_margin = 0.05 * light_extent.z() + 1e-3;
  const double light_near = -light_box.max.z() - depth_margin, light_far = -light_box.min.z() + depth_margin;
  const Mat4d light_proj =
      orthographic(cx - half_side, cx + half_side, cy - half_side, cy + half_side, light_near, light_far);
  const double shadow_texel = 2 * half_side / kSolidShadowSize;

  // Thickness scale: a particle stands for spacing^3 of water, its sphere holds more.
  const double rad = in.particle_radius;
  const double sphere_volume = 4.0 / 3.0 * kPi * rad * rad * rad;
  const double thickness_scale =
      in.particle_spacing > 0 ? std::pow(in.particle_spacing, 3) / sphere_volume : 1.0;

  FrameUniforms u{};
  put(u.view, view);
  put(u.proj, proj);
  put(u.inv_view, Mat4d(view.inverse()));
  put(u.light_view, light_view);
  put(u.light_proj, light_proj);
  put(u.viewport, fw, fh, 1.0 / fw, 1.0 / fh);
  put(u.camera, near, far, focal_px, rad);
  put(u.light_dir, light_dir, s.light.intensity);
  put(u.light_color, s.light.color, s.light.ambient);
  put(u.sky_color, s.sky_color, s.light.shadows ? 1 : 0);
  put(u.horizon_color, s.horizon_color, kFogDistances * cam_distance);
  put(u.ground_color, s.ground_color, s.ground_tile);
  put(u.ground, in.ground_height, s.ground ? 1 : 0, shadow_texel, thickness_scale);
  put(u.fluid_color, s.fluid_color, s.refraction);
  put(u.absorption, s.absorption, s.specular);
  put(u.camera_position, cam.position, static_cast<double>(static_cast<int>(s.view)));
  const bool bilateral = s.filter == Filter::kBilateral;
  put(u.filter, s.filter_radius * rad, s.filter_max_pixels,
      (bilateral ? kBilateralRangeRatio : kRangeRatio) * rad, kClampRatio * rad);
  const std::size_t shadow_stride =
      std::clamp<std::size_t>((count + kShadowParticles - 1) / kShadowParticles, 1, kMaxShadowStride);
  const double shadow_radius = rad * std::cbrt(static_cast<double>(shadow_stride));
  put(u.misc, kGuardPixels, r.max_point_size,
      std::min<double>(shadow_radius * kFluidShadowSize / half_side, r.max_point_size), shadow_radius);
  // Two shadow-sphere diameters, in the light's depth units.
  put(u.shadow, 4 * shadow_radius / (light_far - light_near), 0, 0, 0);
  put(u.spray, s.foam, spacing, s.spray_size * spacing, s.spray_opacity);
  r.uniforms.upload(&u, sizeof u);
  gl::BindBufferBase(GL_UNIFORM_BUFFER, 0, r.uniforms.id);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, r.particles.id);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, r.foam.id);

  const GLsizei sprite_vertices = static_cast<GLsizei>(count);
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  const float far_front[4] = {1, 1, 1, 1};

  r.lap("upload");

  // ---- 0. shadow maps
  gl::DepthMask(GL_TRUE);  // depth clears obey the mask, and the last frame left it off
  gl::Disable(GL_BLEND);
  gl::Disable(GL_CULL_FACE);
  gl::ClearNamedFramebufferfv(r.shadow_depth_fb.id, GL_DEPTH, 0, &one);
  gl::ClearNamedFramebufferfv(r.shadow_fluid_fb.id, GL_COLOR, 0, zero);
  gl::ClearNamedFramebufferfv(r.shadow_fluid_fb.id, GL_COLOR, 1, far_front);
  if (s.light.shadows) {
    gl::BindFramebuffer(GL_FRAMEBUFFER, r.shadow_depth_fb.id);
    gl::Viewport(0, 0, kSolidShadowSize, kSolidShadowSize);
    gl::Enable(GL_DEPTH_TEST);
    gl::DepthFunc(GL_LESS);
    gl::DepthMask(GL_TRUE);
    r.mesh_shadow.use();
    r.draw_triangles(r.vao_mesh, solid_vertex_count);
    r.lap("solid shadow map");
    if (count > 0) {
      gl::BindFramebuffer(GL_FRAMEBUFFER, r.shadow_fluid_fb.id);
      gl::Viewport(0, 0, kFluidShadowSize, kFluidShadowSize);
      gl::Disable(GL_DEPTH_TEST);
      gl::Enable(GL_BLEND);
      gl::BlendEquationi(0, GL_FUNC_ADD);
      gl::BlendFunci(0, GL_ONE, GL_ONE);
      gl::BlendEquationi(1, GL_MIN);
      gl::BlendFunci(1, GL_ONE, GL_ONE);
      r.sprite_shadow.use();
      r.sprite_shadow.set("u_stride", static_cast<int>(shadow_stride));
      gl::BindVertexArray(r.vao_empty);
      gl::DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(count / shadow_stride));
      gl::Disable(GL_BLEND);
      // thickness -> blur -> thickness
      const GLint dir = gl::GetUniformLocation(r.blur_shadow.id(), "u_direction");
      r.blur_shadow.use();
      gl::BindFramebuffer(GL_FRAMEBUFFER, r.shadow_blur_fb[0].id);
      gl::ProgramUniform2i(r.blur_shadow.id(), dir, 1, 0);
      gl::BindTextureUnit(0, r.shadow_thickness.id);
      gl::DrawArrays(GL_TRIANGLES, 0, 3);
      gl::BindFramebuffer(GL_FRAMEBUFFER, r.shadow_blur_fb[1].id);
      gl::ProgramUniform2i(r.blur_shadow.id(), dir, 0, 1);
      gl::BindTextureUnit(0, r.shadow_blur.id);
      gl::DrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  r.lap("water shadow map");

  // ---- 1. scene: ground and solids, then the sky where nothing was drawn
  gl::Viewport(0, 0, fw, fh);
  gl::BindFramebuffer(GL_FRAMEBUFFER, r.scene_fb.id);
  gl::DepthMask(GL_TRUE);
  gl::ClearNamedFramebufferfv(r.scene_fb.id, GL_DEPTH, 0, &one);
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LESS);
  gl::BindTextureUnit(4, r.shadow_depth.id);
  gl::BindTextureUnit(5, r.shadow_thickness.id);
  gl::BindTextureUnit(6, r.shadow_front.id);
  r.mesh.use();
  r.set_paint(in);
  r.mesh.set("u_is_ground", 1);
  r.draw_triangles(r.vao_ground, ground.size() / 9);
  r.mesh.set("u_is_ground", 0);
  r.draw_triangles(r.vao_mesh, solid_vertex_count);
  gl::DepthFunc(GL_LEQUAL);
  gl::DepthMask(GL_FALSE);
  r.sky.use();
  gl::BindVertexArray(r.vao_empty);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  r.lap("scene");

  // ---- 2. fluid depth and thickness, one pass
  const float no_fluid[4] = {kNoFluid, kNoFluid, kNoFluid, kNoFluid};
  gl::BindFramebuffer(GL_FRAMEBUFFER, r.fluid_fb.id);
  gl::DepthMask(GL_TRUE);
  gl::DepthFunc(GL_ALWAYS);
  gl::ClearNamedFramebufferfv(r.fluid_fb.id, GL_COLOR, 0, no_fluid);
  gl::ClearNamedFramebufferfv(r.fluid_fb.id, GL_COLOR, 1, zero);
  gl::ClearNamedFramebufferfv(r.fluid_fb.id, GL_DEPTH, 0, &one);
  gl::BindTextureUnit(0, r.scene_depth.id);
  if (count > 0) {
    gl::Enable(GL_BLEND);
    gl::BlendEquationi(0, GL_MIN);
    gl::BlendFunci(0, GL_ONE, GL_ONE);
    gl::BlendEquationi(1, GL_FUNC_ADD);
    gl::BlendFunci(1, GL_ONE, GL_ONE);
    r.sprite_fluid.use();
    gl::BindVertexArray(r.vao_empty);
    gl::DrawArrays(GL_POINTS, 0, sprite_vertices);
    gl::Disable(GL_BLEND);
  }
  r.lap("fluid depth and thickness");
  // From here on, full-screen passes at depth 0.5 reach the fluid pixels only.
  gl::DepthMask(GL_FALSE);
  gl::DepthFunc(GL_GREATER);
  for (const Framebuffer* fb : {&r.filter_fb[0], &r.filter_fb[1]})
    gl::ClearNamedFramebufferfv(fb->id, GL_COLOR, 0, no_fluid);
  // The blur reads its neighbours outside the mask too: no values of an earlier frame.
  gl::ClearNamedFramebufferfv(r.thickness_fb[0].id, GL_COLOR, 0, zero);
  gl::ClearNamedFramebufferfv(r.normals_fb.id, GL_COLOR, 0, zero);

  // ---- 4. smoothing and normals
  r.smoothed = r.fluid_depth.id;
  if (s.filter != Filter::kNone && count > 0) {
    const Program& f = bilateral ? r.filter_bilateral : r.filter_narrow;
    const GLint dir = gl::GetUniformLocation(f.id(), "u_direction");
    f.use();
    gl::BindVertexArray(r.vao_empty);
    gl::BindFramebuffer(GL_FRAMEBUFFER, r.filter_fb[0].id);
    gl::ProgramUniform2i(f.id(), dir, 1, 0);
    gl::BindTextureUnit(0, r.fluid_depth.id);
    gl::DrawArrays(GL_TRIANGLES, 0, 3);
    gl::BindFramebuffer(GL_FRAMEBUFFER, r.filter_fb[1].id);
    gl::ProgramUniform2i(f.id(), dir, 0, 1);
    gl::BindTextureUnit(0, r.filtered[0].id);
    gl::DrawArrays(GL_TRIANGLES, 0, 3);
    r.smoothed = r.filtered[1].id;
    if (!bilateral) {  // the narrow-range filter's small 2-D pass
      r.filter_narrow_2d.use();
      gl::BindFramebuffer(GL_FRAMEBUFFER, r.filter_fb[0].id);
      gl::BindTextureUnit(0, r.filtered[1].id);
      gl::DrawArrays(GL_TRIANGLES, 0, 3);
      r.smoothed = r.filtered[0].id;
    }
  }
  if (count > 0) {
    // Thickness: thickness -> thickness_blur -> thickness.
    const GLint dir = gl::GetUniformLocation(r.blur_thickness.id(), "u_direction");
    r.blur_thickness.use();
    gl::BindVertexArray(r.vao_empty);
    gl::BindTextureUnit(1, r.fluid_depth.id);
    gl::BindFramebuffer(GL_FRAMEBUFFER, r.thickness_fb[0].id);
    gl::ProgramUniform2i(r.blur_thickness.id(), dir, 1, 0);
    gl::BindTextureUnit(0, r.thickness.id);
    gl::DrawArrays(GL_TRIANGLES, 0, 3);
    gl::BindFramebuffer(GL_FRAMEBUFFER, r.thickness_fb[1].id);
    gl::ProgramUniform2i(r.blur_thickness.id(), dir, 0, 1);
    gl::BindTextureUnit(0, r.thickness_blur.id);
    gl::DrawArrays(GL_TRIANGLES, 0, 3);
  }
  r.lap("smoothing");
  gl::BindFramebuffer(GL_FRAMEBUFFER, r.normals_fb.id);
  r.normals.use();
  gl::BindTextureUnit(0, r.smoothed);
  gl::BindVertexArray(r.vao_empty);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);

  r.lap("normals");

  // ---- 5. composite
  gl::BindFramebuffer(GL_FRAMEBUFFER, r.final_fb.id);
  gl::BindTextureUnit(0, r.scene_color.id);
  gl::Disable(GL_DEPTH_TEST);
  r.composite_scene.use();
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  gl::Enable(GL_DEPTH_TEST);
  r.composite.use();
  gl::BindTextureUnit(0, r.scene_color.id);
  gl::BindTextureUnit(1, r.scene_depth.id);
  gl::BindTextureUnit(2, r.smoothed);
  gl::BindTextureUnit(3, r.thickness.id);
  gl::BindTextureUnit(7, r.normal_map.id);
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
  r.lap("composite");

  // ---- 6. spray over the image, in the shaded view only
  if (spray_count > 0 && s.view == View::kShaded) {
    gl::Disable(GL_DEPTH_TEST);
    gl::Enable(GL_BLEND);
    gl::BlendEquation(GL_FUNC_ADD);
    gl::BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    r.sprite_spray.use();
    r.sprite_spray.set("u_first", static_cast<int>(count));
    gl::BindTextureUnit(1, r.scene_depth.id);
    gl::BindTextureUnit(2, r.smoothed);
    gl::BindVertexArray(r.vao_empty);
    gl::DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(spray_count));
    gl::Disable(GL_BLEND);
  }
  check_gl("render");
  r.lap("spray");

  // ---- read back, top row first
  std::vector<std::uint8_t> rgba(4 * static_cast<std::size_t>(w) * h);
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, r.final_fb.id);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(kGuardPixels, kGuardPixels, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  check_gl("glReadPixels");
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.resize(3 * static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* src = &rgba[4 * static_cast<std::size_t>(h - 1 - y) * w];
    std::uint8_t* dst = &image.rgb[3 * static_cast<std::size_t>(y) * w];
    for (int x = 0; x < w; ++x) dst[3 * x] = src[4 * x], dst[3 * x + 1] = src[4 * x + 1], dst[3 * x + 2] = src[4 * x + 2];
  }
  r.lap("read back");
  return image;
}

void Renderer::set_profiling(bool on) { impl_->profiling = on; }
std::vector<std::pair<std::string, double>> Renderer::pass_times() const { return impl_->times; }

FluidLayers Renderer::read_fluid_layers() const {
  const Impl& r = *impl_;
  FluidLayers layers;
  layers.width = r.width;
  layers.height = r.height;
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  auto read = [&](GLuint texture, int channels, GLenum format, std::vector<float>& out) {
    std::vector<float> raw(n * channels);
    gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl::GetTextureSubImage(texture, 0, kGuardPixels, kGuardPixels, 0, r.width, r.height, 1, format, GL_FLOAT,
                           static_cast<GLsizei>(raw.size() * sizeof(float)), raw.data());
    out.resize(n * (channels == 4 ? 3 : 1));
    const int keep = channels == 4 ? 3 : 1;
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x)
        for (int c = 0; c < keep; ++c)
          out[(static_cast<std::size_t>(y) * r.width + x) * keep + c] =
              raw[(static_cast<std::size_t>(r.height - 1 - y) * r.width + x) * channels + c];
  };
  read(r.fluid_depth.id, 1, GL_RED, layers.depth);
  read(r.smoothed ? r.smoothed : r.fluid_depth.id, 1, GL_RED, layers.smoothed_depth);
  for (std::vector<float>* v : {&layers.depth, &layers.smoothed_depth})
    for (float& d : *v)
      if (d >= 0.5f * kNoFluid) d = 0;
  read(r.thickness.id, 1, GL_RED, layers.thickness);
  read(r.normal_map.id, 4, GL_RGBA, layers.normals);
  check_gl("reading the fluid layers");
  return layers;
}

}  // namespace bw::render
