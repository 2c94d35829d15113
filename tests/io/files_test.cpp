// Round trips of every file kind of docs/formats.md.
#include <gtest/gtest.h>

#include "common/error.h"
#include "io/fragments_file.h"
#include "io/frame_file.h"
#include "io/h5.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "io/run_index.h"
#include "test_support.h"

namespace {

using bw::Vec3d;
using bw::test::TempDir;

TEST(ParticlesFile, RoundTrip) {
  TempDir dir;
  bw::SampledSolid s;
  s.grid.origin = Vec3d(-1, 2, 0.5);
  s.grid.spacing = 0.25;
  s.grid.dims = {4, 5, 6};
  s.surface = {{0, 0, 0}, {3, 4, 5}, {1, 2, 3}};
  s.voxels = {{1, 1, 1}, {2, 2, 2}};
  s.has_voxels = true;
  s.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  s.source = "tet.obj";
  s.scale = 2;
  s.mesh_volume = 1.0 / 6;
  bw::write_particles(s, dir.file("p.h5"), "test");
  const bw::SampledSolid r = bw::read_particles(dir.file("p.h5"));
  EXPECT_EQ(r.grid.origin, s.grid.origin);
  EXPECT_EQ(r.grid.spacing, s.grid.spacing);
  EXPECT_EQ(r.grid.dims, s.grid.dims);
  EXPECT_EQ(r.surface, s.surface);
  EXPECT_EQ(r.voxels, s.voxels);
  EXPECT_TRUE(r.has_voxels);
  EXPECT_EQ(r.mesh.vertices, s.mesh.vertices);
  EXPECT_EQ(r.mesh.triangles, s.mesh.triangles);
  EXPECT_EQ(r.source, s.source);
  EXPECT_EQ(r.scale, 2);
  EXPECT_EQ(r.mesh_volume, s.mesh_volume);
  EXPECT_EQ(r.surface_positions()[1], Vec3d(-1 + 3.5 * 0.25, 2 + 4.5 * 0.25, 0.5 + 5.5 * 0.25));

  // Without voxels the group is absent and reads back as such.
  s.has_voxels = false;
  s.voxels.clear();
  bw::write_particles(s, dir.file("q.h5"), "test");
  EXPECT_FALSE(bw::read_particles(dir.file("q.h5")).has_voxels);
}

TEST(ParticlesFile, CellOutsideTheGridIsRefused) {
  TempDir dir;
  bw::SampledSolid s;
  s.grid.spacing = 1;
  s.grid.dims = {2, 2, 2};
  s.surface = {{0, 0, 2}};
  bw::write_particles(s, dir.file("bad.h5"), "test");
  try {
    bw::read_particles(dir.file("bad.h5"));
    FAIL();
  } catch (const bw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/surface/cell"), std::string::npos) << e.what();
  }
}

TEST(FrameFile, RoundTripWithBodies) {
  TempDir dir;
  bw::FrameData f;
  f.frame = 42;
  f.time = 1.75;
  f.x = {0, 1, 2};
  f.y = {3, 4, 5};
  f.z = {6, 7, 8};
  f.vx = f.vy = f.vz = {0.5f, -0.5f, 1};
  f.rho = {998, 1000, 1002};
  f.id = {10, 11, 12};
  f.bx = f.by = f.bz = {9, 9};
  f.bodies.id = {0, 3};
  f.bodies.position = {{1, 2, 3}, {4, 5, 6}};
  f.bodies.orientation = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5)};
  f.bodies.linear_velocity = {{0, 0, -1}, {1, 0, 0}};
  f.bodies.angular_velocity = {{0, 0, 0}, {0, 1, 0}};
  const std::string path = bw::frame_file_name(dir.path(), 42);
  EXPECT_EQ(path, dir.path() + "/000042.h5");
  bw::write_frame(f, path);
  const bw::FrameData r = bw::read_frame(path);
  EXPECT_EQ(r.frame, 42);
  EXPECT_EQ(r.time, 1.75);
  EXPECT_EQ(r.x, f.x);
  EXPECT_EQ(r.z, f.z);
  EXPECT_EQ(r.vy, f.vy);
  EXPECT_EQ(r.rho, f.rho);
  EXPECT_TRUE(r.p.empty());
  EXPECT_EQ(r.id, f.id);
  EXPECT_EQ(r.bz, f.bz);
  ASSERT_EQ(r.bodies.size(), 2u);
  EXPECT_EQ(r.bodies.id, f.bodies.id);
  EXPECT_EQ(r.bodies.position[1], Vec3d(4, 5, 6));
  EXPECT_EQ(r.bodies.orientation[1].coeffs(), f.bodies.orientation[1].coeffs());
  EXPECT_EQ(r.bodies.angular_velocity[1], Vec3d(0, 1, 0));
  EXPECT_TRUE(r.fields().velocity && r.fields().density && !r.fields().pressure && r.fields().id);
}

// H5Part readers number steps from 0: frame 42's one step is Step#0, with the frame
// number and the time (TimeValue, the name ParaView reads) as attributes.
TEST(FrameFile, OneStepNamedStep0WhateverTheFrame) {
  TempDir dir;
  bw::FrameData f;
  f.frame = 42;
  f.time = 1.75;
  f.x = f.y = f.z = {1, 2};
  f.bodies.id = {0};
  f.bodies.position = {{1, 2, 3}};
  f.bodies.orientation = {Eigen::Quaterniond::Identity()};
  f.bodies.linear_velocity = f.bodies.angular_velocity = {{0, 0, 0}};
  const std::string path = bw::frame_file_name(dir.path(), 42);
  bw::write_frame(f, path);
  const bw::h5::File file = bw::h5::File::open(path, "frame");
  EXPECT_EQ(file.root().children(), std::vector<std::string>{"Step#0"});
  const bw::h5::Group step = file.root().open_group("Step#0");
  EXPECT_EQ(step.attr<double>("TimeValue"), 1.75);
  EXPECT_EQ(step.attr<double>("time"), 1.75);
  EXPECT_EQ(step.attr<std::int32_t>("frame"), 42);
  const bw::FrameHeader h = bw::read_frame_header(path, true);
  EXPECT_EQ(h.frame, 42);
  EXPECT_EQ(h.step, "/Step#0");
  EXPECT_EQ(h.fluid, 2u);
  EXPECT_EQ(h.body_count, 1u);
  ASSERT_EQ(h.bodies.size(), 1u);
  EXPECT_EQ(h.bodies.position[0], Vec3d(1, 2, 3));
  EXPECT_FALSE(h.fields.velocity || h.fields.boundary);
}

// Frame files of earlier versions named their step Step#F: they still read.
TEST(FrameFile, OlderLayoutWithStepNamedAfterTheFrameReads) {
  TempDir dir;
  const std::string path = dir.file("000007.h5");
  {
    bw::h5::File file = bw::h5::File::create(path, "frame");
    file.root().set_attr("frame", std::int32_t{7});
    file.root().set_attr("time", 0.35);
    bw::h5::Group step = file.root().create_group("Step#7");
    step.set_attr("time", 0.35);
    for (const char* c : {"x", "y", "z", "rho"}) step.write<float>(c, std::vector<float>{1, 2, 3});
    file.commit();
  }
  const bw::FrameData r = bw::read_frame(path);
  EXPECT_EQ(r.frame, 7);
  EXPECT_EQ(r.time, 0.35);
  EXPECT_EQ(r.x, (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(r.rho, (std::vector<float>{1, 2, 3}));
  const bw::FrameHeader h = bw::read_frame_header(path);
  EXPECT_EQ(h.step, "/Step#7");
  EXPECT_EQ(h.fluid, 3u);
  EXPECT_TRUE(h.fields.density);
  // The index points at the step the file has.
  bw::RunIndex index;
  index.frames.push_back(bw::index_frame(h, "frames/000007.h5"));
  EXPECT_NE(bw::xdmf_text(index).find("frames/000007.h5:/Step#7/rho"), std::string::npos);
}

// A frame file without its step group is refused, naming the file and the group.
TEST(FrameFile, MissingStepIsRefusedNamingTheFile) {
  TempDir dir;
  const std::string path = dir.file("000003.h5");
  {
    bw::h5::File file = bw::h5::File::create(path, "frame");
    file.root().set_attr("frame", std::int32_t{3});
    file.root().set_attr("time", 0.1);
    file.commit();
  }
  try {
    bw::read_frame(path);
    FAIL() << "read";
  } catch (const bw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Step#0"), std::string::npos) << e.what();
  }
}

TEST(RunFile, RoundTrip) {
  TempDir dir;
  bw::RunRecord run;
  run.scene_text = "[time]\nend = 1\n";
  run.scene_path = "/x/scene.toml";
  run.device = "PoCL cpu";
  run.tool = "bw-sim test";
  run.status = "complete";
  bw::SolidRecord solid;
  solid.name = "wall";
  solid.particles = "/x/wall.h5";
  solid.kind = "breakable";
  solid.translation = Vec3d(1, 2, 3);
  solid.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3d::UnitZ()));
  solid.scale = 1.5;
  solid.body = 0;
  run.solids = {solid};
  bw::BodyRecord body;
  body.name = "wall";
  body.solid = 0;
  body.mass = 100;
  body.inertia = bw::Mat3d::Identity() * 3;
  body.reference_center = Vec3d(0.1, 0.2, 0.3);
  body.voxels = 1000;
  bw::BodyRecord child = body;
  child.name = "wall.1";
  child.parent = 0;
  child.created_time = 0.5;
  run.bodies = {body, child};
  bw::FrameStats stats;
  stats.frame = 0;
  stats.steps = 12;
  stats.kinetic_energy = 1.25;
  stats.emitted_energy = 0.75;
  stats.outflow_energy = 0.5;
  run.frames = {stats, stats};
  run.frames[1].frame = 1;
  bw::FractureEvent event;
  event.time = 0.5;
  event.parent = 0;
  event.seeds = {{0, 0, 0}, {1, 1, 1}};
  event.child_body = {1, 2};
  event.child_seed = {0, 1};
  event.child_component = {0, 0};
  run.fractures = {event};
  bw::write_run(run, dir.file("run.h5"));
  const bw::RunRecord r = bw::read_run(dir.file("run.h5"));
  EXPECT_EQ(r.scene_text, run.scene_text);
  EXPECT_EQ(r.status, "complete");
  ASSERT_EQ(r.solids.size(), 1u);
  EXPECT_EQ(r.solids[0].kind, "breakable");
  EXPECT_TRUE(r.solids[0].rotation.isApprox(solid.rotation));
  ASSERT_EQ(r.bodies.size(), 2u);
  EXPECT_EQ(r.bodies[1].name, "wall.1");
  EXPECT_EQ(r.bodies[1].parent, 0);
  EXPECT_EQ(r.bodies[0].inertia, body.inertia);
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[1].frame, 1);
  EXPECT_EQ(r.frames[0].steps, 12);
  EXPECT_EQ(r.frames[0].kinetic_energy, 1.25);
  EXPECT_EQ(r.frames[0].emitted_energy, 0.75);
  EXPECT_EQ(r.frames[0].outflow_energy, 0.5);
  ASSERT_EQ(r.fractures.size(), 1u);
  EXPECT_EQ(r.fractures[0].seeds[1], Vec3d(1, 1, 1));
  EXPECT_EQ(r.fractures[0].child_body, (std::vector<std::int32_t>{1, 2}));
}

TEST(FragmentsFile, RoundTrip) {
  TempDir dir;
  bw::FragmentSet set;
  set.source = "cube.obj";
  set.seeds = {{0.25, 0.5, 0.5}, {0.75, 0.5, 0.5}};
  for (int k = 0; k < 2; ++k) {
    bw::Fragment f;
    f.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1.0 + k}};
    f.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    f.seed = k;
    f.volume = (1.0 + k) / 6;
    f.body = 5 + k;
    set.fragments.push_back(f);
  }
  bw::write_fragments(set, dir.file("f.h5"));
  const bw::FragmentSet r = bw::read_fragments(dir.file("f.h5"));
  ASSERT_EQ(r.fragments.size(), 2u);
  EXPECT_EQ(r.seeds, set.seeds);
  EXPECT_EQ(r.fragments[1].mesh.vertices, set.fragments[1].mesh.vertices);
  EXPECT_EQ(r.fragments[1].mesh.triangles, set.fragments[1].mesh.triangles);
  EXPECT_EQ(r.fragments[1].body, 6);
  EXPECT_EQ(r.fragments[0].volume, 1.0 / 6);
}

// The index writes OUTDIR/meshes.h5 and OUTDIR/run.xdmf2: a fragments file under
// either name, by any spelling, would be replaced by them.
TEST(RunIndex, FragmentsMayNotTakeTheNamesTheIndexWrites) {
  TempDir dir;
  const std::string run = dir.file("run.h5");
  EXPECT_THROW(bw::check_fragments_beside_run(run, dir.file("meshes.h5")), bw::InputError);
  EXPECT_THROW(bw::check_fragments_beside_run(run, dir.path() + "/./run.xdmf2"), bw::InputError);
  EXPECT_NO_THROW(bw::check_fragments_beside_run(run, dir.file("fragments.h5")));
  EXPECT_NO_THROW(bw::check_fragments_beside_run(run, ""));
  try {
    bw::check_fragments_beside_run(run, dir.file("meshes.h5"));
  } catch (const bw::InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("meshes.h5") +
                                         ": is where the index writes meshes.h5; give the fragments file another name");
  }
}

}  // namespace
