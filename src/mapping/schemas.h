// Private to src/mapping: libxml2 set-up shared by the stylesheet runner and the validators.
#pragma once

namespace surrogate::mapping {

// Makes libxml2 safe (network refused, see carrier/xml.h) and maps the remote schema URLs the
// vendored schemas use (METS -> xlink) to the local copies in xsd/. Idempotent.
void initialiseXml();

}  // namespace surrogate::mapping
