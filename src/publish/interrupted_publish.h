// Private to src/publish: the hidden name a publish writes its folder under before renaming it
// into place, and the removal of such folders that a killed publish left behind.
//
// The name carries the writer's process id, ".NAME.partial-PID-XXXXXX", so that a later publish
// can tell a leftover (its process no longer runs) from a publish still at work beside it, as
// archive's removeStaleParts does for a pack's ".NAME.part-PID-N".
//
//   std::string pattern = stagingPattern(out);            // for mkdtemp
//   for (const std::string& s : removeInterruptedPublishes(out)) note(s);
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace surrogate::publish {

// The mkdtemp pattern of the folder a publish to `out` writes: beside `out`, in its parent.
std::string stagingPattern(const std::filesystem::path& out);

// Removes, in the folder that holds `out`, every staging folder of a publish (to any name)
// whose process no longer runs; a folder of a running process, of another user, a symbolic
// link or a name of another form is left alone. Returns one sentence per folder removed
// ("removed PATH, the partial folder of a publish that did not finish (process N no longer
// runs)").
std::vector<std::string> removeInterruptedPublishes(const std::filesystem::path& out);

}  // namespace surrogate::publish
