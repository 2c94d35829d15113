// Temporary files that must not outlive a tool stopped by a signal: the files
// AtomicFile writes before they take their final names, and the copies of pipes read
// as inputs. A tool stopped by SIGINT, SIGTERM or SIGHUP (Ctrl-C, a scheduler's
// preemption, a closed terminal) removes them, then dies of the signal as it would
// have. A tool that handles a signal itself (bw-sim stops at a frame) keeps its
// handler; SIGKILL leaves them.
#pragma once

#include <string>

namespace bw {

// Marks `path` for removal on those signals; returns a ticket for forget_temp_file,
// or -1 when too many are marked at once (the file then is not removed on a signal).
int remember_temp_file(const std::string& path);

// The file is gone or in its place: no longer removed on a signal.
void forget_temp_file(int ticket);

}  // namespace bw
