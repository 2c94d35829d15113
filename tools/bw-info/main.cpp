// bw-info: kind, counts, bounds and attributes of any breakwater file.
#include <cstdio>

#include "cli/tool.h"
#include "io/describe.h"

int main(int argc, char** argv) {
  CLI::App app{"Describe a breakwater file: its kind, counts, bounds, attributes and datasets.", "bw-info"};
  bw::cli::setup(app,
                 "  bw-info wall.h5\n"
                 "  bw-info out/run.h5 --json\n"
                 "  bw-sample mesh.obj --spacing 0.02 -o - | bw-info -\n");
  std::string path;
  bool json = false;
  bool brief = false;
  app.add_option("file", path, "A breakwater HDF5 file ('-' for standard input)")->required();
  app.add_flag("--json", json, "Print JSON on standard output");
  app.add_flag("--brief", brief, "Leave out the list of datasets");
  return bw::cli::run(app, argc, argv, [&] {
    const bw::Report report = bw::describe_file(path, {.list_datasets = !brief});
    const std::string text = json ? report.to_json() : report.to_text();
    std::fwrite(text.data(), 1, text.size(), stdout);
    return bw::kExitOk;
  });
}
