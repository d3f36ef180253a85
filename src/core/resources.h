// Where the project's data files (xsd/, xslt/, mappings/) are found at run time.
//
// Looked up in order: $SURROGATE_RESOURCES, <executable dir>/../share/surrogate, the source
// tree the program was built from. A missing resource is an installation problem, reported as
// Error(Internal) naming the file that was looked for.
#pragma once

#include <filesystem>
#include <string>

namespace surrogate {

std::filesystem::path resourcePath(const std::string& relative);

}  // namespace surrogate
