// Input files that are pipes or devices: `bw-info <(ssh host cat run.h5)`, a FIFO,
// /dev/stdin. HDF5, assimp and the seeds' reader seek, and a pipe can be read only
// once, so such a file is copied whole into a temporary file the first time a reader
// asks for it; later readers of the same path get the same copy.
#pragma once

#include <string>

namespace bw {

// A path to read `path` through: a pipe's or a device's temporary copy (removed when
// the process ends, also by SIGINT, SIGTERM or SIGHUP), or `path` itself for anything else (a regular file, a missing
// one, a folder), whose errors the reader reports. Throws InputError when the pipe
// cannot be read.
std::string seekable_path(const std::string& path);

}  // namespace bw
