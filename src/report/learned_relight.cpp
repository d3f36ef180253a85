#include "report/learned_relight.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base64.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "publish/web_reader.h"
#include "report/embed.h"

namespace surrogate::report {

namespace fs = std::filesystem;

namespace {

void writeNumbers(std::ostringstream& j, const char* name, const std::vector<float>& v) {
  j << ",\"" << name << "\":[";
  for (std::size_t k = 0; k < v.size(); ++k) j << (k ? "," : "") << static_cast<double>(v[k]);
  j << "]";
}

// The P coefficient bytes of each step x step block of texels, averaged (rounded half up).
std::vector<std::uint8_t> averaged(const fit::LearnedModel& m, int step) {
  if (step == 1) return m.coefficients;
  const int w = (m.width + step - 1) / step, h = (m.height + step - 1) / step, P = m.planes;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h * P);
  for (int by = 0; by < h; ++by)
    for (int bx = 0; bx < w; ++bx)
      for (int p = 0; p < P; ++p) {
        std::uint64_t sum = 0, n = 0;
        for (int y = by * step; y < std::min(m.height, (by + 1) * step); ++y)
          for (int x = bx * step; x < std::min(m.width, (bx + 1) * step); ++x, ++n)
            sum += m.coefficients[(static_cast<std::size_t>(y) * m.width + x) * P + p];
        out[(static_cast<std::size_t>(by) * w + bx) * P + p] = static_cast<std::uint8_t>((2 * sum + n) / (2 * n));
      }
  return out;
}

}  // namespace

std::string relightJson(const fit::LearnedModel& m, int maxSide, std::size_t maxBytes) {
  const int step = relightBlockSide(m.width, m.height, static_cast<std::size_t>(m.planes), maxSide, maxBytes);
  const int w = (m.width + step - 1) / step, h = (m.height + step - 1) / step;
  std::ostringstream j;
  j.precision(9);  // floats read back exactly
  j << "{\"model\":\"learned\",\"basis\":\"" << fit::learnedKindName(m.kind) << "\",\"width\":" << w
    << ",\"height\":" << h << ",\"originalWidth\":" << m.width << ",\"originalHeight\":" << m.height
    << ",\"planes\":" << m.planes << ",\"resolution\":" << m.resolution << ",\"nodes\":[";
  j.precision(17);
  for (std::size_t i = 0; i < m.lights.size() && m.kind == fit::LearnedKind::Rbf; ++i)
    j << (i ? "," : "") << m.lights[i][0] << "," << m.lights[i][1] << "," << m.lights[i][2];
  j << "]";
  j.precision(9);
  writeNumbers(j, "range", m.range);
  writeNumbers(j, "scale", m.scale);
  writeNumbers(j, "bias", m.bias);
  std::string out = j.str() + ",\"basisBytes\":\"";
  appendBase64(out, m.basis.data(), m.basis.size());
  out += "\",\"coefficients\":\"";
  const std::vector<std::uint8_t> coefficients = averaged(m, step);
  appendBase64(out, coefficients.data(), coefficients.size());
  return out + "\"}";
}

std::optional<std::string> learnedRelightJson(const carrier::Carrier& c, const ReportSource& source,
                                              const carrier::FileRecord& info, int maxSide, std::size_t maxBytes) {
  // The layout reader reads a folder: the recorded files of this one, copied into a temporary
  // folder (a package's files are not on disk).
  const std::string folder = fs::path(info.path).parent_path().generic_string() + "/";
  TempDir temp("report");
  for (const carrier::FileRecord& f : c.files) {
    if (f.path.compare(0, folder.size(), folder) != 0 || f.path.find('/', folder.size()) != std::string::npos) continue;
    const std::optional<std::string> bytes = source.read(f.path);
    if (!bytes) return std::nullopt;
    std::ofstream(temp.path() / f.path.substr(folder.size()), std::ios::binary) << *bytes;
  }
  const publish::WebLayoutModel web = publish::readWebLayout(temp.path() / "info.json");
  if (!web.isLearned) throw Error(ErrorKind::Input, info.path, "report", "is not a learned model's info.json");
  return relightJson(web.learned, maxSide, maxBytes);
}

}  // namespace surrogate::report
