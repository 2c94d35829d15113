// Overrides of scene keys from the command line (bw-sim --set KEY=VALUE): a
// parameter study runs one scene file at many settings without copies of it.
//
// KEY is the key's path as error messages print it: names separated by dots, an
// index in brackets for arrays of tables and for one element of an array:
//   spacing=0.005   time.cfl=0.2   fluid.c0=40   domain.max[2]=0.8
//   solid[0].particles="tank-0.005.h5"   fluid.block[0].velocity=[0, 0, -3]
// VALUE is a TOML value (number, string in quotes, boolean, array, inline table);
// text that does not start like one ("tank.h5") is taken as a string. Tables that
// are missing on the way are created ([fluid] in a scene without one); an index
// names an existing element, or the one past the last to append (a new block).
//
// Overrides replace the values in the parsed file before any key is read, so a
// value they set is checked exactly like one written in the file, with the same
// one-line message ("scene.toml: fluid.c0: -1 must be positive"); a key that is
// not a scene key is reported as unknown in the same way.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>  // private to libcore/scene: only its .cpp files include this header

namespace bw::scene {

// Applies "KEY=VALUE" overrides in order to `root`, the parsed scene file `file`.
// Throws InputError "<file>: --set <text>: <problem>" when an override cannot be
// applied (no '=', an empty or malformed key, an index past the end, a path through
// a value that is not a table, or a value that starts like TOML and is not).
void apply_overrides(toml::table& root, const std::vector<std::string>& overrides, const std::string& file);

}  // namespace bw::scene
