#include "publish/web_layout.h"

#include <array>
#include <cstdlib>
#include <map>
#include <system_error>

#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/json.h"
#include "core/temp_dir.h"
#include "publish/rgb_jpeg.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kStep = "publish";

// The web viewers order the PTM terms (1, u, v, u^2, uv, v^2); a .ptm stores a0..a5 as
// (u^2, v^2, uv, u, v, 1) (formats/ptm.h). kWebPtmTerm[j] is the .ptm index of web term j.
constexpr std::array<int, 6> kWebPtmTerm = {5, 3, 4, 0, 2, 1};

// The HSH orders the viewers evaluate: OpenLIME's shader has the first nine terms only.
constexpr int kMaxWebHshTerms = 9;

void checkQuality(const PublishOptions& options) {
  if (options.quality < 1 || options.quality > 100)
    throw Error(ErrorKind::Usage, "--quality " + std::to_string(options.quality), kStep,
                "needs a JPEG quality from 1 to 100");
}

// One JPEG's worth of planes: three bytes per texel, rows top-first.
using PlaneImage = std::vector<std::uint8_t>;

struct Layout {
  std::vector<double> scale, bias;  // nplanes values each
  std::vector<PlaneImage> images;   // nplanes / 3
};

std::string infoJson(const PublishedModel& m, const Layout& layout, int quality) {
  JsonWriter j;
  j.beginObject()
      .key("width").value(m.width).key("height").value(m.height)
      .key("format").value("jpg")
      .key("type").value(m.type).key("colorspace").value(m.colorspace)
      .key("nplanes").value(m.nplanes)
      .key("quality").value(quality)
      .key("materials").beginArray().beginObject().key("scale").beginArray();
  for (double s : layout.scale) j.value(s);
  j.endArray().key("bias").beginArray();
  for (double b : layout.bias) j.value(b);
  j.endArray().endObject().endArray().endObject();
  return j.str() + "\n";
}

// The largest side a baseline JPEG can describe (libjpeg's JPEG_MAX_DIMENSION).
constexpr int kMaxJpegSide = 65500;

WebLayoutFiles assemble(PublishedModel model, const Layout& layout, int quality) {
  if (model.width > kMaxJpegSide || model.height > kMaxJpegSide)
    throw Error(ErrorKind::Input, "the model", kStep,
                "is " + std::to_string(model.width) + "x" + std::to_string(model.height) +
                    " texels; a JPEG plane holds at most 65500 on a side: reduce it (run --resize) to publish it");
  WebLayoutFiles out;
  model.nplanes = static_cast<int>(layout.scale.size());
  out.files.emplace_back("info.json", infoJson(model, layout, quality));
  for (std::size_t p = 0; p < layout.images.size(); ++p)
    out.files.emplace_back("plane_" + std::to_string(p) + ".jpg",
                           encodeRgbJpeg(layout.images[p], model.width, model.height, quality));
  for (const auto& f : out.files) model.files.push_back(f.first);
  out.model = std::move(model);
  return out;
}

// A .ptm decodes a = (byte - bias) * scale in 0..255 units; the viewers compute
// (byte/255 - bias') * scale' and expect 0..1 units, so scale' = scale and bias' = bias/255
// (LRGB: the colour, 0..1, multiplies a luminance that 255 would make 1).
void addPtmTerm(const formats::PtmFile& ptm, int term, Layout* layout) {
  const int k = kWebPtmTerm[static_cast<std::size_t>(term)];
  layout->scale.push_back(ptm.scale[static_cast<std::size_t>(k)]);
  layout->bias.push_back(ptm.bias[static_cast<std::size_t>(k)] / 255.0);
}

Layout ptmLrgbLayout(const formats::PtmFile& ptm) {
  Layout layout;
  const std::size_t n = ptm.texels();
  layout.images.assign(3, PlaneImage(n * 3));
  layout.images[0] = ptm.rgb;  // the colour, stored as it is: scale 1, bias 0
  layout.scale = {1, 1, 1};
  layout.bias = {0, 0, 0};
  for (int term = 0; term < 6; ++term) {
    addPtmTerm(ptm, term, &layout);
    PlaneImage& image = layout.images[1 + term / 3];
    const int k = kWebPtmTerm[static_cast<std::size_t>(term)];
    for (std::size_t t = 0; t < n; ++t) image[t * 3 + term % 3] = ptm.coefficients[t * 6 + k];
  }
  return layout;
}

Layout ptmRgbLayout(const formats::PtmFile& ptm) {
  Layout layout;
  const std::size_t n = ptm.texels();
  layout.images.assign(6, PlaneImage(n * 3));
  for (int term = 0; term < 6; ++term) {
    const int k = kWebPtmTerm[static_cast<std::size_t>(term)];
    for (int c = 0; c < 3; ++c) {
      addPtmTerm(ptm, term, &layout);  // the .ptm shares one scale and bias across R, G, B
      const std::uint8_t* block = ptm.coefficients.data() + static_cast<std::size_t>(c) * n * 6;
      PlaneImage& image = layout.images[static_cast<std::size_t>(term)];
      for (std::size_t t = 0; t < n; ++t) image[t * 3 + c] = block[t * 6 + k];
    }
  }
  return layout;
}

// An .rti decodes coef = byte/255 * scale + bias; the viewers' (byte/255 - bias') * scale'
// gives the same with scale' = scale and bias' = -bias/scale. A term with scale 0 is the
// constant `bias`: its plane is written as zeros with scale' 1 and bias' -bias.
Layout hshLayout(const formats::HshFile& hsh) {
  Layout layout;
  const std::size_t n = hsh.texels();
  const auto terms = static_cast<std::size_t>(hsh.terms);
  layout.images.assign(terms, PlaneImage(n * 3));
  for (std::size_t k = 0; k < terms; ++k) {
    const double s = hsh.scale[k], b = hsh.bias[k];
    const bool constant = s == 0;
    for (int c = 0; c < 3; ++c) {
      layout.scale.push_back(constant ? 1.0 : s);
      layout.bias.push_back(constant ? -b : -b / s);
    }
    PlaneImage& image = layout.images[k];
    if (constant) continue;
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t c = 0; c < 3; ++c) image[t * 3 + c] = hsh.coefficients[(t * 3 + c) * terms + k];
  }
  return layout;
}

// The folder being written: beside the final one (same file system, so the rename is
// atomic), hidden and named as partial, removed unless committed.
class StagingFolder {
 public:
  explicit StagingFolder(const fs::path& out) : out_(out) {
    const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    std::string pattern = (parent / ("." + out.filename().string() + ".partial-XXXXXX")).string();
    if (!mkdtemp(pattern.data()))
      throw Error(ErrorKind::Input, parent.string(), kStep,
                  "cannot create a folder here; check that it exists and is writable");
    path_ = pattern;
  }
  ~StagingFolder() {
    if (!committed_) removeTreeForcibly(path_.c_str());
  }
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const fs::path& path() const { return path_; }
  void commit() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                               fs::perms::others_read | fs::perms::others_exec, ec);
    fs::rename(path_, out_, ec);  // replaces an empty folder, never a full one
    if (ec)
      throw Error(ErrorKind::Input, out_.string(), kStep,
                  "could not be put in place (" + ec.message() + "); remove it or choose another folder");
    committed_ = true;
  }

 private:
  fs::path out_, path_;
  bool committed_ = false;
};

void checkOutputFolder(const fs::path& out) {
  std::error_code ec;
  const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(parent, ec))
    throw Error(ErrorKind::Usage, out.string(), kStep,
                "is in a folder that does not exist (" + parent.string() + "); create it first");
  if (!fs::exists(out, ec)) return;
  if (!fs::is_directory(out, ec) || !fs::is_empty(out, ec))
    throw Error(ErrorKind::Usage, out.string(), kStep,
                "already exists and is not an empty folder; publish writes a new folder: remove it "
                "or name another one");
}

void writeLayout(const WebLayoutFiles& layout, const fs::path& folder) {
  fs::create_directories(folder);
  for (const auto& [name, bytes] : layout.files) writeFileAtomically(folder / name, bytes);
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

// The model file as Surrogate reads it: a .ptm (any variant) or an HSH .rti, by its first bytes.
WebLayoutFiles layoutOfFile(const fs::path& file, const PublishOptions& options) {
  const std::string bytes = readFile(file, kStep);
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  if (startsWith(bytes, "PTM_")) return webLayoutOf(formats::parsePtm(data, bytes.size(), file.string()), options);
  if (!bytes.empty() && bytes[0] == '#')
    return webLayoutOf(formats::parseRti(data, bytes.size(), file.string()), options);
  throw Error(ErrorKind::Input, file.string(), kStep,
              "is neither a PTM (.ptm) nor an HSH RTI (.rti) file, nor a capture folder; give one of these");
}

struct CaptureModel {
  std::string path;  // relative to the capture
  std::string folder;
};

bool isModelResult(const carrier::FileRecord& f) {
  const std::string ext = fs::path(f.path).extension().string();
  return f.role == "result" && startsWith(f.path, "finished-files/") && (ext == ".ptm" || ext == ".rti");
}

// The capture's recorded results, each checked against its recorded digest (what is published
// is what the carrier describes), with a subfolder named after the file's stem, or after the
// whole name when two results share a stem.
std::vector<CaptureModel> recordedModels(const fs::path& capture) {
  std::error_code ec;
  if (!fs::is_regular_file(capture / "assembly-files" / "carrier.xml", ec))
    throw Error(ErrorKind::Input, capture.string(), kStep,
                "is a folder without a carrier (assembly-files/carrier.xml): run `surrogate run` on the "
                "capture first, or give a .ptm or .rti file");
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files" / "carrier.xml");
  std::vector<CaptureModel> models;
  std::map<std::string, int> stems;
  for (const carrier::FileRecord& f : c.files) {
    if (!isModelResult(f)) continue;
    if (digestFile(capture / f.path).sha256 != f.sha256)
      throw Error(ErrorKind::Fixity, (capture / f.path).string(), kStep,
                  "is not the file the carrier records (its SHA-256 differs); run the capture again "
                  "or restore the file");
    models.push_back({f.path, fs::path(f.path).stem().string()});
    ++stems[models.back().folder];
  }
  for (CaptureModel& m : models) {
    if (stems[m.folder] < 2) continue;
    std::string name = fs::path(m.path).filename().string();
    for (char& ch : name) ch = ch == '.' ? '-' : ch;
    m.folder = name;
  }
  if (models.empty())
    throw Error(ErrorKind::Input, capture.string(), kStep,
                "its carrier records no PTM or HSH result in finished-files/; run `surrogate run` on it first");
  return models;
}
}  // namespace

WebLayoutFiles webLayoutOf(const formats::PtmFile& ptm, const PublishOptions& options) {
  checkQuality(options);
  formats::validatePtm(ptm, "the PTM");
  PublishedModel m;
  m.type = "ptm";
  m.width = ptm.width;
  m.height = ptm.height;
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  m.colorspace = lrgb ? "lrgb" : "rgb";
  return assemble(std::move(m), lrgb ? ptmLrgbLayout(ptm) : ptmRgbLayout(ptm), options.quality);
}

WebLayoutFiles webLayoutOf(const formats::HshFile& hsh, const PublishOptions& options) {
  checkQuality(options);
  formats::validateHsh(hsh, "the RTI");
  if (hsh.terms > kMaxWebHshTerms)
    throw Error(ErrorKind::Input, "the RTI", kStep,
                "has " + std::to_string(hsh.terms) + " HSH terms (order 4); the web viewers evaluate HSH "
                "up to order 3 (9 terms): fit with --basis hsh3 to publish it");
  PublishedModel m;
  m.type = "hsh";
  m.colorspace = "rgb";
  m.width = hsh.width;
  m.height = hsh.height;
  return assemble(std::move(m), hshLayout(hsh), options.quality);
}

std::vector<PublishedModel> publish(const fs::path& source, const fs::path& out, const PublishOptions& options) {
  checkQuality(options);
  checkOutputFolder(out);
  std::error_code ec;
  if (!fs::exists(source, ec))
    throw Error(ErrorKind::Input, source.string(), kStep, "does not exist; give a .ptm, an .rti or a capture folder");
  std::vector<WebLayoutFiles> layouts;
  if (fs::is_directory(source, ec)) {
    for (const CaptureModel& m : recordedModels(source)) {
      WebLayoutFiles layout = layoutOfFile(source / m.path, options);
      layout.model.source = m.path;
      layout.model.folder = m.folder;
      layouts.push_back(std::move(layout));
    }
  } else {
    layouts.push_back(layoutOfFile(source, options));
    layouts.back().model.source = source.string();
  }
  StagingFolder staging(out);
  std::vector<PublishedModel> published;
  for (const WebLayoutFiles& layout : layouts) {
    writeLayout(layout, staging.path() / layout.model.folder);
    published.push_back(layout.model);
  }
  staging.commit();
  return published;
}

}  // namespace surrogate::publish
