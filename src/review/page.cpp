#include "review/page.h"

#include <string>

#include "core/version.h"
#include "report/html.h"
#include "report/page_assets.h"
#include "review/access_key.h"
#include "review/web_files.h"

namespace surrogate::review {

std::string pageHtml() {
  // The version is the page's only datum, in its generator tag: put in place of the marker.
  static const std::string kMarker = "{{version}}";
  std::string html = kReviewHtml;
  const auto at = html.find(kMarker);
  if (at != std::string::npos) html.replace(at, kMarker.size(), escapeHtml(surrogateVersion()));
  return html;
}

std::string pageScript() {
  // One script, in this order: the report's error recorder first (it catches what the rest
  // throws), the key taken out of the address, then the page's files, each using those before.
  std::string js = std::string(report::kPageErrorsJs) + kForgetKeyJs;
  for (const char* file : {kReviewDecisionsJs, kReviewGeometryJs, kReviewWordsJs, kReviewDomJs, kReviewPanelsJs, kReviewPageJs})
    js += file;
  return js;
}

std::string pageCss() { return std::string(report::kReportCss) + kReviewCss; }

}  // namespace surrogate::review
