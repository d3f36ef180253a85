// Private to src/carrier: a document parsed once, validated, and read as a libxml2 tree.
#pragma once

#include <libxml/tree.h>

#include <filesystem>
#include <memory>
#include <string>

namespace surrogate::xml {

struct DocDeleter {
  void operator()(xmlDoc* d) const { xmlFreeDoc(d); }
};
using DocPtr = std::unique_ptr<xmlDoc, DocDeleter>;

// `text` parsed as checkWellFormed parses it and validated against `xsd` (errors as
// validateAgainstSchema's), in one parse. The tree is for reading only: the white space
// between elements is left out and short texts are kept inside their nodes, which makes the
// tree of a carrier listing 100 000 files about 70 MB smaller.
DocPtr parseValidated(const std::string& text, const std::string& source,
                      const std::filesystem::path& xsd);

}  // namespace surrogate::xml
