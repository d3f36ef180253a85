// Relighting: an image of the object under a new light, from a .ptm or .rti HSH model.
//
//   PTM LRGB: out_c = C_c * L(lu, lv) / 255        RGB: out_c = L_c(lu, lv)
//   HSH:      out_c = 255 * sum_k coef_{c,k} H_k(theta, phi)
// with (lu, lv) = extrapolation * (lx, ly) of the normalised light, theta clamped to
// pi/2 - 0.01 as the viewers do (docs/formats.md, "Light directions" and each format's rendering).
// Enhancements (docs/hrti-math.md, "Normals, albedo and enhancement"):
//   diffuse gain g (PTM only): each polynomial is transformed around the texel's normal
//     direction (the maximum, or the Lambertian fallback; fit/ptm_math.h), which keeps the
//     maximum's position and value and multiplies the curvature by g;
//   specular (Blinn-Phong with the recovered normal N, fit/normals.h):
//     out_c = kd * diffuse_c + ks * 255 * max(0, N . H)^exponent,  H = normalize(l + (0,0,1))
// Output: 8-bit sRGB-encoded RGB (bitsPerSample 8, values widened *257), rows top-first.
//
//   auto model = openRelightable("finished-files/object.ptm");
//   RenderOptions options;
//   options.diffuseGain = 2.0;
//   Image raking = model->render({0.95, 0.0, 0.31}, options);
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/image.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::fit {

struct RenderOptions {
  double diffuseGain = 1.0;     // g > 0; 1 = unchanged. PTM only (HSH: must stay 1)
  double extrapolation = 1.0;   // PTM: multiplies (lu, lv); > 1 lights beyond grazing
  bool specular = false;        // add a Blinn-Phong highlight from the recovered normals
  double kd = 0.7;              // diffuse weight when specular is on
  double ks = 0.3;              // specular weight (of 255)
  double specularExponent = 40; // larger = tighter highlight
  int threads = 0;              // 0 = all cores; the image is identical at any count
};

// Throws Error(Usage) naming "--light" for a zero or non-finite light, or the option at
// fault (e.g. "--gain" for g <= 0, or g != 1 on an HSH model).
Image render(const formats::PtmFile& ptm, const std::array<double, 3>& light,
             const RenderOptions& options = {});
Image render(const formats::HshFile& hsh, const std::array<double, 3>& light,
             const RenderOptions& options = {});

// A fitted model of either kind, behind one interface (OpenImageIO-style plugins).
// Owns its data; copy deleted.
class Relightable {
 public:
  virtual ~Relightable() = default;
  Relightable() = default;
  Relightable(const Relightable&) = delete;
  Relightable& operator=(const Relightable&) = delete;

  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual std::string basis() const = 0;  // "ptm-lrgb", "ptm-rgb", "hsh2", "hsh3", "hsh4"
  virtual Image render(const std::array<double, 3>& light, const RenderOptions& options) const = 0;
  virtual Image normalMap(int* fallbackCount = nullptr, int threads = 0) const = 0;
  virtual Image albedoMap(int threads = 0) const = 0;
  // Both maps, as normalMap and albedoMap make them; a PTM makes them in one pass (both pictures
  // held at once), finding each texel's normal once.
  virtual void normalAndAlbedoMaps(Image* normals, Image* albedo, int* fallbackCount = nullptr,
                                   int threads = 0) const {
    *normals = normalMap(fallbackCount, threads);
    *albedo = albedoMap(threads);
  }
};

// What `surrogate render` holds per texel beside the model: the rendered picture (16-bit RGB),
// the 8-bit rows and the stream of the file written (9 bytes a texel measured with
// /usr/bin/time on a 12000x12000 PTM, with or without --specular, which frees its normals
// before the file is written).
inline constexpr std::uint64_t kRenderBytesPerTexel = 12;

std::unique_ptr<Relightable> makeRelightable(formats::PtmFile ptm);
std::unique_ptr<Relightable> makeRelightable(formats::HshFile hsh);
// Reads a .ptm or .rti, chosen by the file's first bytes ("PTM_" or '#'); Error(Input) else,
// and when reading it would not fit `budget` (formats/model_budget.h).
std::unique_ptr<Relightable> openRelightable(const std::filesystem::path& path,
                                             const formats::ModelBudget& budget = {});

}  // namespace surrogate::fit
