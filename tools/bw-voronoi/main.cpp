// bw-voronoi: cut a solid into the Voronoi cells of fracture seeds with exact
// geometry, check the fragments (the prefracture check), write their meshes.
#include <cstdio>

#include "cli/tool.h"
#include "common/atomic_file.h"
#include "common/terminal.h"
#include "io/run_index.h"
#include "voronoi/check.h"
#include "voronoi/replay.h"

namespace {

struct CheckArgs {
  std::string input;
  std::string seeds;
  std::size_t random = 0;
  std::uint64_t random_seed = 1;
  std::string output;
  std::string export_dir;
  std::string export_format = "obj";
  bool json = false;
  int threads = 0;
  bool verbose = false;
};

struct ReplayArgs {
  std::string run;
  std::string output;
  std::string export_dir;
  std::string export_format = "obj";
  bool json = false;
  int threads = 0;
  bool index = false;
};

struct IndexArgs {
  std::string run;
  std::string fragments;
};

std::string index_text(const bw::MeshesReport& r) {
  std::string text = fmt::format("index: {} ({} frames, {} static triangles, up to {} body triangles a frame)\n",
                                 r.path, r.frames, r.static_triangles, r.body_triangles);
  if (r.bodies_without_mesh > 0)
    text += fmt::format("index: up to {} bodies a frame have no mesh (give the fragments file of replay)\n",
                        r.bodies_without_mesh);
  return text;
}

void print(const std::string& text, bool to_stderr) { std::fputs(text.c_str(), to_stderr ? stderr : stdout); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cut a solid into the Voronoi cells of fracture seeds, with exact geometry, and check the\n"
               "fragments: closed, filling the solid exactly, inside it and inside their cells.",
               "bw-voronoi"};
  bw::cli::setup(app,
                 "  bw-voronoi check house.obj --random 100 --seed 7\n"
                 "  bw-voronoi check wall.h5 --seeds seeds.txt -o wall_fragments.h5 --export wall_fragments/\n"
                 "  bw-voronoi check plate.obj --seeds old_fragments.h5 --json > report.json\n"
                 "  bw-sample dam.obj --spacing 0.02 -o - | bw-voronoi check - --random 50\n"
                 "  bw-voronoi replay out/dam/run.h5 -o out/dam/fragments.h5 --index\n"
                 "  bw-voronoi index out/box/run.h5\n"
                 "Exit status: 0 every check passed, 3 a check failed, 2 bad usage or input, 1 failure.\n");
  app.require_subcommand(1);

  CheckArgs c;
  CLI::App* check = app.add_subcommand(
      "check", "Prefracture check: cut INPUT by the seeds' Voronoi cells and check every fragment");
  check->add_option("input", c.input,
                    "A mesh (any format assimp reads) or a bw-sample particles file, which carries its mesh "
                    "('-': particles file on standard input)")
      ->required();
  CLI::Option* seeds = check->add_option(
      "--seeds", c.seeds, "Seeds file: text with 'x y z' per line, or a breakwater HDF5 file with /seeds");
  CLI::Option* random =
      check->add_option("--random", c.random, "Draw N seeds uniformly inside the mesh")
          ->check(bw::cli::in_range(1, static_cast<double>(bw::voronoi::kMaxSeeds)));
  check->add_option("--seed", c.random_seed, "Random seed for --random (the same seed gives the same seeds)")
      ->needs(random);
  seeds->excludes(random);
  check->add_option("-o,--output", c.output, "Fragments file to write (HDF5; '-' for standard output)");
  check->add_option("--export", c.export_dir, "Also write each fragment as a mesh file into this folder");
  check->add_option("--export-format", c.export_format, "Mesh format of --export")
      ->check(CLI::IsMember({"obj", "ply"}));
  check->add_flag("--json", c.json, "Print the report as JSON");
  check->add_option("--threads", c.threads, "Worker threads (default: one per hardware thread)")
      ->check(bw::cli::kNonNegative);
  check->add_flag("-v,--verbose", c.verbose, "Print the options used");

  ReplayArgs p;
  CLI::App* replay = app.add_subcommand(
      "replay", "Rebuild the exact mesh of every body that fracture created in a run, from its recorded events");
  replay->add_option("run", p.run, "Run file written by bw-sim (OUTDIR/run.h5)")->required();
  replay->add_option("-o,--output", p.output, "Fragments file to write, one fragment per body (HDF5; '-' for stdout)")
      ->required();
  replay->add_option("--export", p.export_dir, "Also write each fragment as a mesh file into this folder");
  replay->add_option("--export-format", p.export_format, "Mesh format of --export")
      ->check(CLI::IsMember({"obj", "ply"}));
  replay->add_flag("--json", p.json, "Print the report as JSON");
  replay->add_flag("--index", p.index,
                   "Then place every body's mesh in every frame (OUTDIR/meshes.h5) and add them to the run's "
                   "ParaView index OUTDIR/run.xdmf2 (as bw-voronoi index does)");
  replay->add_option("--threads", p.threads, "Worker threads (default: one per hardware thread)")
      ->check(bw::cli::kNonNegative);

  IndexArgs x;
  CLI::App* index = app.add_subcommand(
      "index", "Place the solids' and bodies' meshes in every frame of a run (OUTDIR/meshes.h5) and rewrite its "
               "ParaView index OUTDIR/run.xdmf2 with them");
  index->add_option("run", x.run, "Run file written by bw-sim (OUTDIR/run.h5), beside its frames folder")->required();
  index->add_option("--fragments", x.fragments,
                    "Fragments file of bw-voronoi replay: the meshes of the bodies that fracture created");

  return bw::cli::run(app, argc, argv, [&] {
    if (*index) {
      print(index_text(bw::write_run_meshes(x.run, x.fragments)), false);
      return bw::kExitOk;
    }
    if (*replay) {
      if (p.index && (p.output == "-" || p.run == "-"))
        throw bw::InputError("replay --index: the run and fragments files must be files, not -");
      bw::check_output_file(p.output, {p.run});  // before the work, not after it
      if (p.index) bw::check_fragments_beside_run(p.run, p.output);
      bw::voronoi::ReplayOptions options;
      options.source = p.run;
      options.threads = p.threads;
      options.warn = [&](const std::string& message) { bw::cli::note(app, "warning: " + message); };
      const bw::RunRecord run = bw::read_run(p.run);
      const bw::voronoi::ReplayResult result = bw::voronoi::replay_run(run, options);
      bw::FragmentSet set = result.fragments;
      set.tool = "bw-voronoi " BW_VERSION;
      set.options = "replay";
      bw::write_fragments(set, p.output);
      if (!p.export_dir.empty()) bw::voronoi::export_fragments(set.fragments, p.export_dir, p.export_format);
      print(p.json ? result.report().to_json() + "\n" : result.text(), p.output == "-");
      if (p.index) print(index_text(bw::write_run_meshes(p.run, p.output)), false);
      return result.passed() ? bw::kExitOk : bw::kExitCheckFailed;
    }
    if (!*seeds && !*random) throw bw::InputError("check: give the seeds with --seeds FILE or --random N");
    if (!c.output.empty()) bw::check_output_file(c.output, {c.input, c.seeds});
    // The report goes to standard output, unless the fragments file does.
    const bool report_to_stderr = c.output == "-";
    if (c.verbose) {
      bw::cli::note(app, fmt::format("check {} with {}, output {}, export {} ({}), threads {}", c.input,
                                     *random ? fmt::format("--random {} --seed {}", c.random, c.random_seed)
                                             : "--seeds " + c.seeds,
                                     c.output.empty() ? "none" : c.output,
                                     c.export_dir.empty() ? "none" : c.export_dir, c.export_format, c.threads));
    }
    bw::voronoi::CheckOptions options;
    options.source = c.input;
    options.threads = c.threads;
    options.warn = [&](const std::string& message) { bw::cli::note(app, "warning: " + message); };
    bw::ProgressLine progress;
    if (progress.active()) {
      options.progress = [&](std::size_t done, std::size_t total) {
        progress.update(fmt::format("cutting cells: {} / {}", done, total), done == total);
      };
    }
    bw::voronoi::SeedChoice choice;
    if (*random) {
      choice.random = c.random;
      choice.random_seed = c.random_seed;
    } else {
      choice.points = bw::voronoi::read_seeds(c.seeds);
    }
    bw::TriMesh mesh = bw::voronoi::load_solid_mesh(c.input, &options.input_kind);

    const bw::voronoi::CheckResult result = bw::voronoi::prefracture_check(std::move(mesh), choice, options);
    progress.clear();

    // Written also when a check fails, so that the fragments can be looked at.
    if (!c.output.empty()) {
      bw::FragmentSet set = result.fragment_set();
      set.tool = "bw-voronoi " BW_VERSION;
      set.options = *random ? fmt::format("check --random {} --seed {}", c.random, c.random_seed)
                            : "check --seeds " + c.seeds;
      bw::write_fragments(set, c.output);
    }
    if (!c.export_dir.empty()) bw::voronoi::export_fragments(result.fragments, c.export_dir, c.export_format);
    print(c.json ? result.report().to_json() + "\n" : result.text(), report_to_stderr);
    return result.passed() ? bw::kExitOk : bw::kExitCheckFailed;
  });
}
