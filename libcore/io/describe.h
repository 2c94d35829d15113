// What bw-info prints: kind, counts, bounds and attributes of any breakwater file.
#pragma once

#include <string>

#include "common/report.h"

namespace bw {

struct DescribeOptions {
  bool list_datasets = true;   // every dataset with its shape and type
};

// Opens the file ("-": standard input) and describes it: the root attributes, a
// summary of its kind (particles: counts, grid, bounds, volumes; frame: each step's
// time, particle count and bounds; run: the per-frame statistics table; fragments:
// fragment count and volumes) and the datasets. Throws InputError for a file that is
// not a breakwater file.
Report describe_file(const std::string& path, const DescribeOptions& options = {});

}  // namespace bw
