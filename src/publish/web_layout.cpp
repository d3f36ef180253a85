#include "publish/web_layout.h"

#include <algorithm>
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
#include "fit/normals.h"
#include "publish/deep_zoom.h"
#include "publish/interrupted_publish.h"
#include "publish/rgb_jpeg.h"
#include "publish/viewer.h"
#include "publish/web_terms.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kStep = "publish";

// The HSH orders the viewers evaluate: OpenLIME's shader has the first nine terms only.
constexpr int kMaxWebHshTerms = 9;

// Tile sides the viewers handle well: below 16 a screen needs thousands of requests, above
// 4096 a tile is as large as the planes `auto` leaves whole.
constexpr int kMinTileSize = 16, kMaxTileSize = 4096;

void checkOptions(const PublishOptions& options) {
  if (options.quality < 1 || options.quality > 100)
    throw Error(ErrorKind::Usage, "--quality " + std::to_string(options.quality), kStep,
                "needs a JPEG quality from 1 to 100");
  if (options.tileSize < kMinTileSize || options.tileSize > kMaxTileSize)
    throw Error(ErrorKind::Usage, "--tile-size " + std::to_string(options.tileSize), kStep,
                "needs a tile side from 16 to 4096 texels");
}

// The normals and the albedo the viewer shows, from the project's own code (the pictures the
// DerivedMaps stage writes), as 8-bit RGB at the size of the viewer's planes.
struct DerivedPictures {
  PlaneRaster normals, albedo;
};

PlaneRaster eightBit(const Image& image) {
  PlaneRaster r;
  r.width = image.width;
  r.height = image.height;
  r.rgb.resize(image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    r.rgb[i] = static_cast<std::uint8_t>((image.pixels[i] * 2 + 257) / 514);  // round(v / 257)
  return r;
}

// A model halved as the planes are for the viewer: every coefficient the 2x2 mean of its bytes
// (the byte-to-coefficient rule is affine, so this is the mean of the coefficients).
formats::PtmFile halved(formats::PtmFile p) {
  const std::size_t block = p.texels() * 6;
  std::vector<std::uint8_t> coefficients;
  for (std::size_t at = 0; at < p.coefficients.size(); at += block) {
    const auto part = halveTexels(p.coefficients.data() + at, p.width, p.height, 6);
    coefficients.insert(coefficients.end(), part.begin(), part.end());
  }
  if (!p.rgb.empty()) p.rgb = halveTexels(p.rgb.data(), p.width, p.height, 3);
  p.coefficients = std::move(coefficients);
  p.width = (p.width + 1) / 2;
  p.height = (p.height + 1) / 2;
  return p;
}

formats::HshFile halved(formats::HshFile h) {
  h.coefficients = halveTexels(h.coefficients.data(), h.width, h.height, 3 * h.terms);
  h.width = (h.width + 1) / 2;
  h.height = (h.height + 1) / 2;
  return h;
}

// Computed at the viewer's size: for a model larger than that, from the model halved (the
// Lambertian fits cost seconds per million texels, and the viewer shows no more).
template <typename Model>
DerivedPictures derivedPictures(const Model& model, int threads) {
  const int halvings = halvingsToFit(model.width, model.height, kViewerMaxSide);
  if (halvings == 0) return {eightBit(fit::normalMap(model, nullptr, threads)), eightBit(fit::albedoMap(model, threads))};
  Model small = halved(model);
  for (int k = 1; k < halvings; ++k) small = halved(std::move(small));
  return {eightBit(fit::normalMap(small, nullptr, threads)), eightBit(fit::albedoMap(small, threads))};
}

// One JPEG's worth of planes: three bytes per texel, rows top-first.
using PlaneImage = std::vector<std::uint8_t>;

bool tiled(const PublishedModel& m, const PublishOptions& o) {
  if (o.tiles == TileLayout::Auto) return m.width > kAutoTileSide || m.height > kAutoTileSide;
  return o.tiles == TileLayout::DeepZoom;
}

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

std::string planeName(std::size_t p) { return "plane_" + std::to_string(p); }

// `picture` halved `halvings` times, as JPEG.
std::string encodedAt(const PlaneRaster& picture, int halvings, int quality) {
  if (halvings == 0) return encodeRgbJpeg(picture.rgb, picture.width, picture.height, quality);
  PlaneRaster r = halfSize(picture);
  for (int k = 1; k < halvings; ++k) r = halfSize(r);
  return encodeRgbJpeg(r.rgb, r.width, r.height, quality);
}

// The viewer's copy: every picture halved until it fits in kViewerMaxSide (the Deep Zoom
// level of that size when tiled); at full size the planes are plane_N.jpg's own bytes.
std::string viewerData(const std::string& info, const std::vector<PlaneRaster>& planes,
                       const std::vector<std::string>& wholeJpegs, const DerivedPictures& maps, int levels, int quality) {
  ViewerData d;
  d.infoJson = info;
  d.halvings = halvingsToFit(planes.front().width, planes.front().height, kViewerMaxSide);
  d.width = maps.normals.width;
  d.height = maps.normals.height;
  d.level = wholeJpegs.empty() ? std::max(-1, levels - 1 - d.halvings) : -1;
  for (std::size_t p = 0; p < planes.size(); ++p)
    d.planes.push_back(d.halvings == 0 && !wholeJpegs.empty() ? wholeJpegs[p] : encodedAt(planes[p], d.halvings, quality));
  d.normals = encodedAt(maps.normals, 0, quality);
  d.albedo = encodedAt(maps.albedo, 0, quality);
  return viewerDataJs(d);
}

WebLayoutFiles assemble(PublishedModel model, Layout layout, const DerivedPictures& maps, const PublishOptions& options) {
  if (model.width > kMaxJpegSide || model.height > kMaxJpegSide)
    throw Error(ErrorKind::Input, "the model", kStep,
                "is " + std::to_string(model.width) + "x" + std::to_string(model.height) +
                    " texels; a JPEG plane holds at most 65500 on a side: reduce it (run --resize) to publish it");
  WebLayoutFiles out;
  model.nplanes = static_cast<int>(layout.scale.size());
  const std::string info = infoJson(model, layout, options.quality);
  out.files.emplace_back("info.json", info);
  std::vector<PlaneRaster> planes;
  for (PlaneImage& image : layout.images) planes.push_back({model.width, model.height, std::move(image)});
  std::vector<std::string> wholeJpegs;
  if (tiled(model, options)) {
    model.tiles = "deepzoom";
    model.levels = deepZoomLevelCount(model.width, model.height, options.tileSize);
    for (std::size_t p = 0; p < planes.size(); ++p)
      for (auto& file : deepZoomFiles(planes[p], planeName(p), options.tileSize, options.quality, options.threads))
        out.files.push_back(std::move(file));
  } else {
    for (std::size_t p = 0; p < planes.size(); ++p) {
      wholeJpegs.push_back(encodeRgbJpeg(planes[p].rgb, model.width, model.height, options.quality));
      out.files.emplace_back(planeName(p) + ".jpg", wholeJpegs.back());
    }
  }
  out.files.emplace_back("index.html", viewerHtml(options.description, basisOf(model)));
  out.files.emplace_back("viewer-data.js",
                         viewerData(info, planes, wholeJpegs, maps, model.levels, options.quality));
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
    std::string pattern = stagingPattern(out);  // ".NAME.partial-PID-XXXXXX"
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
  for (const auto& [name, bytes] : layout.files) {
    const fs::path file = folder / name;
    fs::create_directories(file.parent_path());  // the tiles' level folders
    writeFileAtomically(file, bytes);
  }
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

WebLayoutFiles webLayoutOfFile(const fs::path& file, const PublishOptions& options) {
  const std::string bytes = readFile(file, kStep);
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  const formats::ModelBudget budget{options.memoryBudget, kPublishBytesPerTexel, 1};
  if (startsWith(bytes, "PTM_"))
    return webLayoutOf(formats::parsePtm(data, bytes.size(), file.string(), nullptr, budget), options);
  if (!bytes.empty() && bytes[0] == '#')
    return webLayoutOf(formats::parseRti(data, bytes.size(), file.string(), nullptr, budget), options);
  throw Error(ErrorKind::Input, file.string(), kStep,
              "is neither a PTM (.ptm) nor an HSH RTI (.rti) file, nor a capture folder; give one of these");
}

namespace {

struct CaptureModel {
  std::string path;  // relative to the capture
  std::string folder;
};

bool isModelResult(const carrier::FileRecord& f) {
  const std::string ext = fs::path(f.path).extension().string();
  return f.role == "result" && startsWith(f.path, "finished-files/") && (ext == ".ptm" || ext == ".rti");
}

// A path a carrier gives is read only inside the capture: relative, with no "." or ".." part
// and no empty one, and no symbolic link on the way (a link's target can lie anywhere, and a
// carrier edited by hand could name any file whose digest it copied). Error(Input) naming the
// carrier and the path.
void checkRecordedPath(const fs::path& capture, const std::string& path) {
  const fs::path carrierFile = capture / "assembly-files" / "carrier.xml";
  auto refuse = [&](const std::string& why) {
    throw Error(ErrorKind::Input, carrierFile.string(), kStep,
                "records the result \"" + path + "\", " + why +
                    "; publish reads only files inside the capture: run `surrogate run` on the capture "
                    "again, or give the .ptm or .rti file itself");
  };
  if (path.empty() || path.front() == '/' || path.back() == '/' || path.find('\\') != std::string::npos ||
      path.find('\0') != std::string::npos)
    refuse("which is not a relative path with '/' between its parts");
  fs::path at = capture;
  for (std::size_t start = 0; start <= path.size();) {
    const std::size_t slash = std::min(path.find('/', start), path.size());
    const std::string part = path.substr(start, slash - start);
    if (part.empty() || part == "." || part == "..") refuse("which has an empty, \".\" or \"..\" part");
    at /= fs::u8path(part);
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(at, ec);
    if (fs::is_symlink(st)) refuse("and " + at.lexically_relative(capture).generic_string() + " is a symbolic link");
    // A missing file is left to the digest, which names it.
    if (slash == path.size() && fs::exists(st) && !fs::is_regular_file(st)) refuse("which is not a regular file");
    start = slash + 1;
  }
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
    checkRecordedPath(capture, f.path);
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
  return models;
}

// The learned layouts the capture's carrier records (LearnedFit, stages/learned_fit_stage.h:
// finished-files/<basis>/info.json and its planes), each file checked against its recorded
// digest and copied as it is: the layout is already what a viewer reads, and writing it again
// would compress its planes twice.
std::vector<WebLayoutFiles> recordedLearnedLayouts(const fs::path& capture, const carrier::Carrier& c) {
  std::vector<WebLayoutFiles> out;
  for (const carrier::FileRecord& info : c.files) {
    const fs::path path(info.path);
    const std::string basis = path.parent_path().filename().string();
    if (info.role != "result" || path.filename() != "info.json" ||
        path.parent_path().parent_path() != "finished-files" || (basis != "rbf" && basis != "bln"))
      continue;
    const std::string folder = path.parent_path().generic_string() + "/";
    WebLayoutFiles layout;
    for (const carrier::FileRecord& f : c.files) {
      if (f.role != "result" || !startsWith(f.path, folder) || f.path.find('/', folder.size()) != std::string::npos) continue;
      checkRecordedPath(capture, f.path);
      const std::string bytes = readFile(capture / f.path, kStep);
      if (sha256Hex(bytes) != f.sha256)
        throw Error(ErrorKind::Fixity, (capture / f.path).string(), kStep,
                    "is not the file the carrier records (its SHA-256 differs); run the capture again "
                    "or restore the file");
      const std::string name = f.path.substr(folder.size());
      layout.files.emplace(name == "info.json" ? layout.files.begin() : layout.files.end(), name, bytes);
      layout.model.files.push_back(name);
    }
    const WebLayoutSummary summary = describeWebLayout(capture / info.path);
    layout.model.source = info.path;
    layout.model.folder = basis;
    layout.model.type = summary.type;
    layout.model.colorspace = summary.colorspace;
    layout.model.width = summary.width;
    layout.model.height = summary.height;
    layout.model.nplanes = summary.nplanes;
    out.push_back(std::move(layout));
  }
  return out;
}
}  // namespace

std::string basisOf(const PublishedModel& model) {
  if (model.type == "ptm") return "ptm-" + model.colorspace;
  if (model.type == "rbf") return "rbf";
  if (model.type == "bilinear") return "bln";
  int order = 1;
  while (3 * (order + 1) * (order + 1) <= model.nplanes) ++order;
  return "hsh" + std::to_string(order);
}

WebDescription webDescriptionOf(const carrier::Header& header) {
  WebDescription d;
  d.title = header.title;
  for (const carrier::Creator& c : header.creators) d.creators.emplace_back(c.name, c.role);
  d.rights = header.rights;
  d.license = header.license;
  return d;
}

const char* tileLayoutName(TileLayout tiles) {
  switch (tiles) {
    case TileLayout::Auto: return "auto";
    case TileLayout::None: return "none";
    case TileLayout::DeepZoom: return "deepzoom";
  }
  return "auto";
}

TileLayout parseTileLayout(const std::string& name) {
  for (TileLayout t : {TileLayout::Auto, TileLayout::None, TileLayout::DeepZoom})
    if (name == tileLayoutName(t)) return t;
  throw Error(ErrorKind::Usage, "--tiles " + name, kStep,
              "is not a tile layout; give auto (tiles for a side over 4096), none or deepzoom");
}

WebLayoutFiles webLayoutOf(const formats::PtmFile& ptm, const PublishOptions& options) {
  checkOptions(options);
  formats::validatePtm(ptm, "the PTM");
  PublishedModel m;
  m.type = "ptm";
  m.width = ptm.width;
  m.height = ptm.height;
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  m.colorspace = lrgb ? "lrgb" : "rgb";
  return assemble(std::move(m), lrgb ? ptmLrgbLayout(ptm) : ptmRgbLayout(ptm), derivedPictures(ptm, options.threads), options);
}

WebLayoutFiles webLayoutOf(const formats::HshFile& hsh, const PublishOptions& options) {
  checkOptions(options);
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
  return assemble(std::move(m), hshLayout(hsh), derivedPictures(hsh, options.threads), options);
}

void writeWebLayoutFolder(const WebLayoutFiles& layout, const fs::path& out) {
  checkOutputFolder(out);
  removeInterruptedPublishes(out);
  StagingFolder staging(out);
  try {
    writeLayout(layout, staging.path());
  } catch (const Error& e) {  // named as the user will look for it, as publish() does
    const fs::path inside = fs::path(e.file()).lexically_relative(staging.path());
    if (e.file().empty() || inside.empty() || *inside.begin() == "..") throw;
    throw Error(e.kind(), (out / inside).string(), e.step(), e.message());
  }
  staging.commit();
}

std::vector<PublishedModel> publish(const fs::path& source, const fs::path& out, const PublishOptions& options,
                                    std::vector<std::string>* removedLeftovers) {
  checkOptions(options);
  checkOutputFolder(out);
  const std::vector<std::string> removed = removeInterruptedPublishes(out);
  if (removedLeftovers) *removedLeftovers = removed;
  std::error_code ec;
  if (!fs::exists(source, ec))
    throw Error(ErrorKind::Input, source.string(), kStep, "does not exist; give a .ptm, an .rti or a capture folder");
  std::vector<WebLayoutFiles> layouts;
  const bool capture = fs::is_directory(source, ec);
  PublishOptions described = options;
  if (capture) {
    const std::vector<CaptureModel> models = recordedModels(source);  // checks the carrier is there
    described.description =
        webDescriptionOf(carrier::loadCarrier(source / "assembly-files" / "carrier.xml"));
    for (const CaptureModel& m : models) {
      WebLayoutFiles layout = webLayoutOfFile(source / m.path, described);
      layout.model.source = m.path;
      layout.model.folder = m.folder;
      layouts.push_back(std::move(layout));
    }
    for (WebLayoutFiles& layout :
         recordedLearnedLayouts(source, carrier::loadCarrier(source / "assembly-files" / "carrier.xml")))
      layouts.push_back(std::move(layout));
    if (layouts.empty())
      throw Error(ErrorKind::Input, source.string(), kStep,
                  "its carrier records no PTM, HSH or learned result in finished-files/; run `surrogate run` on it first");
  } else {
    layouts.push_back(webLayoutOfFile(source, options));
    layouts.back().model.source = source.string();
  }
  StagingFolder staging(out);
  std::vector<PublishedModel> published;
  for (const WebLayoutFiles& layout : layouts) {
    try {
      writeLayout(layout, staging.path() / layout.model.folder);
    } catch (const Error& e) {
      // Named as the user will look for it: OUT/..., not the hidden folder removed on the way out.
      const fs::path inside = fs::path(e.file()).lexically_relative(staging.path());
      if (e.file().empty() || inside.empty() || *inside.begin() == "..") throw;
      throw Error(e.kind(), (out / inside).string(), e.step(), e.message());
    }
    published.push_back(layout.model);
  }
  if (capture) {
    std::vector<IndexedModel> index;
    for (const PublishedModel& m : published) index.push_back({m.folder, basisOf(m)});
    writeFileAtomically(staging.path() / "index.html", webIndexHtml(described.description, index));
  }
  // Fault injection for the test of the cleanup (tests/publish/test_render_web_e2e.cpp): with
  // SURROGATE_FAULT_INJECTION=publish the process dies here, its folder written but not yet
  // renamed, as a kill -9 or a power cut could leave it.
  if (const char* fault = std::getenv("SURROGATE_FAULT_INJECTION"); fault && std::string(fault) == "publish")
    std::_Exit(137);
  staging.commit();
  return published;
}

}  // namespace surrogate::publish
