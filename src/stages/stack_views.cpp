#include "stages/stack_views.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace surrogate::stages {

namespace {

double srgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double linearToSrgb(double l) {
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}

// Input rows read at once by the resize (bounded so a strong reduction of a wide image does
// not hold many full-resolution rows), but always enough for one output row.
constexpr std::size_t kResizeBufferBytes = std::size_t(16) << 20;

}  // namespace

// ---- CropStack ------------------------------------------------------------------------------

CropStack::CropStack(std::shared_ptr<const ImageStack> inner, PixelRect rect)
    : inner_(std::move(inner)), rect_(rect) {
  if (rect.x < 0 || rect.y < 0 || rect.width <= 0 || rect.height <= 0 ||
      rect.x + rect.width > inner_->width() || rect.y + rect.height > inner_->height())
    throw Error(ErrorKind::Internal, "", "crop", "crop rectangle outside the images");
}

void CropStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  const int ch = channels();
  if (rect_.x == 0 && rect_.width == inner_->width()) {
    inner_->readRows(index, rect_.y + y0, rect_.y + y1, out);
    return;
  }
  const std::size_t inRow = static_cast<std::size_t>(inner_->width()) * ch;
  const std::size_t outRow = static_cast<std::size_t>(rect_.width) * ch;
  std::vector<std::uint16_t> rows(inRow * static_cast<std::size_t>(y1 - y0));
  inner_->readRows(index, rect_.y + y0, rect_.y + y1, rows.data());
  for (int y = 0; y < y1 - y0; ++y)
    std::copy_n(rows.data() + y * inRow + static_cast<std::size_t>(rect_.x) * ch, outRow,
                out + y * outRow);
}

// ---- LuminanceStack -------------------------------------------------------------------------

LuminanceStack::LuminanceStack(std::shared_ptr<const pipeline::DecodedStack> decoded)
    : decoded_(std::move(decoded)) {}

void LuminanceStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  if (decoded_->channels() == 1) {
    decoded_->readRows(index, y0, y1, out);
    return;
  }
  const std::size_t pixels = static_cast<std::size_t>(y1 - y0) * width();
  // A stack in memory is read where it is: sphere detection reads every pixel of every image
  // through here, and a copy of the rows cost a fifth of `surrogate lights`.
  if (const std::uint8_t* held = decoded_->heldSamples(index, y0, y1)) {
    if (decoded_->format().bytesPerSample == 1) luminanceOfPixels(held, pixels, out);
    else luminanceOfPixels(reinterpret_cast<const std::uint16_t*>(held), pixels, out);
    return;
  }
  if (decoded_->format().bytesPerSample == 1) {
    std::vector<std::uint8_t> rgb(pixels * 3);
    decoded_->readSamples(index, y0, y1, rgb.data());
    luminanceOfPixels(rgb.data(), pixels, out);
  } else {
    std::vector<std::uint16_t> rgb(pixels * 3);
    decoded_->readRows(index, y0, y1, rgb.data());
    luminanceOfPixels(rgb.data(), pixels, out);
  }
}

void LuminanceStack::readWindow(int index, int x0, int y0, int x1, int y1, std::uint16_t* out) const {
  const std::uint8_t* held = decoded_->channels() == 3 && y1 > y0 ? decoded_->heldSamples(index, y0, y1) : nullptr;
  if (!held || x0 < 0 || x1 > width() || x0 > x1) {
    ImageStack::readWindow(index, x0, y0, x1, y1, out);  // grey, in a file, or refused there
    return;
  }
  // Each row's window only: the luminance of a pixel is its own samples' (luminanceOfPixels).
  const std::size_t bytes = static_cast<std::size_t>(decoded_->format().bytesPerSample);
  const std::size_t rowBytes = static_cast<std::size_t>(width()) * 3 * bytes, span = std::size_t(x1 - x0);
  for (int y = y0; y < y1; ++y) {
    const std::uint8_t* from = held + std::size_t(y - y0) * rowBytes + std::size_t(x0) * 3 * bytes;
    std::uint16_t* to = out + std::size_t(y - y0) * span;
    if (bytes == 1) luminanceOfPixels(from, span, to);
    else luminanceOfPixels(reinterpret_cast<const std::uint16_t*>(from), span, to);
  }
}

// ---- GreyAsRgbStack -------------------------------------------------------------------------

GreyAsRgbStack::GreyAsRgbStack(std::shared_ptr<const ImageStack> grey) : grey_(std::move(grey)) {
  if (grey_->channels() != 1) throw Error(ErrorKind::Internal, "", "image stack", "not a grey stack");
}

void GreyAsRgbStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  const std::size_t pixels = static_cast<std::size_t>(y1 - y0) * width();
  std::vector<std::uint16_t> grey(pixels);
  grey_->readRows(index, y0, y1, grey.data());
  for (std::size_t p = 0; p < pixels; ++p) out[3 * p] = out[3 * p + 1] = out[3 * p + 2] = grey[p];
}

// ---- TableStack -----------------------------------------------------------------------------

TableStack::TableStack(std::shared_ptr<const ImageStack> inner, std::array<Table, 3> tables,
                       Transfer transfer)
    : inner_(std::move(inner)), tables_(std::move(tables)), transfer_(transfer) {}

void TableStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  inner_->readRows(index, y0, y1, out);
  const std::size_t n = static_cast<std::size_t>(y1 - y0) * width();
  if (channels() == 3) {
    for (std::size_t p = 0; p < n; ++p)
      for (int c = 0; c < 3; ++c) out[3 * p + c] = tables_[c][out[3 * p + c]];
  } else {
    for (std::size_t p = 0; p < n; ++p) out[p] = tables_[1][out[p]];
  }
}

double toLinear(std::uint16_t value, Transfer transfer) {
  const double v = value / 65535.0;
  return transfer == Transfer::Srgb ? srgbToLinear(v) : v;
}

double linearOf(double value, Transfer transfer) {
  return toLinear(static_cast<std::uint16_t>(std::lround(std::clamp(value, 0.0, 1.0) * 65535)), transfer);
}

std::array<TableStack::Table, 3> gainTables(const std::array<double, 3>& gains, Transfer input,
                                            Transfer output) {
  std::array<TableStack::Table, 3> tables;
  for (int c = 0; c < 3; ++c) {
    tables[c].resize(65536);
    for (int v = 0; v < 65536; ++v) {
      const double l = std::min(1.0, toLinear(static_cast<std::uint16_t>(v), input) * gains[c]);
      const double e = output == Transfer::Srgb ? linearToSrgb(l) : l;
      tables[c][v] = static_cast<std::uint16_t>(std::lround(std::clamp(e, 0.0, 1.0) * 65535.0));
    }
  }
  return tables;
}

// ---- AreaResizeStack ------------------------------------------------------------------------

std::vector<AreaResizeStack::Span> AreaResizeStack::spans(int in, int out) {
  // In units of 1/out input pixel: output pixel X covers [X*in, (X+1)*in), input pixel i
  // covers [i*out, (i+1)*out); the weights of one output pixel sum to `in`.
  std::vector<Span> result(out);
  for (int X = 0; X < out; ++X) {
    const std::int64_t a = std::int64_t(X) * in, b = std::int64_t(X + 1) * in;
    const int first = static_cast<int>(a / out);
    const int last = static_cast<int>((b - 1) / out);
    result[X].first = first;
    for (int i = first; i <= last; ++i) {
      const std::int64_t lo = std::max<std::int64_t>(a, std::int64_t(i) * out);
      const std::int64_t hi = std::min<std::int64_t>(b, std::int64_t(i + 1) * out);
      result[X].weights.push_back(hi - lo);
    }
  }
  return result;
}

AreaResizeStack::AreaResizeStack(std::shared_ptr<const ImageStack> inner, int width, int height)
    : inner_(std::move(inner)), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > inner_->width() || height > inner_->height())
    throw Error(ErrorKind::Internal, "", "resize", "resize target outside 1..input size");
  xSpans_ = spans(inner_->width(), width);
  ySpans_ = spans(inner_->height(), height);
  toLinear_.resize(65536);
  for (int v = 0; v < 65536; ++v)
    toLinear_[v] = inner_->transfer() == Transfer::Srgb
                       ? std::llround(toLinear(static_cast<std::uint16_t>(v), Transfer::Srgb) * 16777216.0)
                       : std::int64_t(v) << 8;
  bucketStart_.resize(static_cast<std::size_t>(toLinear_.back() >> 8) + 2);
  std::size_t v = 0;
  for (std::size_t b = 0; b < bucketStart_.size(); ++b) {
    while (v < 65535 && toLinear_[v] < static_cast<std::int64_t>(b) << 8) ++v;
    bucketStart_[b] = static_cast<std::uint16_t>(v);
  }
}

void AreaResizeStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  const int ch = channels(), inW = inner_->width();
  const std::size_t inRow = static_cast<std::size_t>(inW) * ch;
  const std::int64_t divisor = std::int64_t(inW) * inner_->height();
  std::vector<std::uint16_t> rows;
  std::vector<std::int64_t> horizontal(static_cast<std::size_t>(width_) * ch);
  std::vector<std::int64_t> acc(horizontal.size());

  int Y = y0;
  while (Y < y1) {
    // As many output rows as fit the buffer (at least one).
    const int firstIn = ySpans_[Y].first;
    int Yend = Y + 1;
    while (Yend < y1) {
      const int lastIn = ySpans_[Yend].first + static_cast<int>(ySpans_[Yend].weights.size());
      if (static_cast<std::size_t>(lastIn - firstIn) * inRow * 2 > kResizeBufferBytes) break;
      ++Yend;
    }
    const int endIn = ySpans_[Yend - 1].first + static_cast<int>(ySpans_[Yend - 1].weights.size());
    rows.resize(static_cast<std::size_t>(endIn - firstIn) * inRow);
    inner_->readRows(index, firstIn, endIn, rows.data());

    for (int oy = Y; oy < Yend; ++oy) {
      std::fill(acc.begin(), acc.end(), 0);
      const Span& sy = ySpans_[oy];
      for (std::size_t k = 0; k < sy.weights.size(); ++k) {
        const std::uint16_t* row = rows.data() + static_cast<std::size_t>(sy.first + k - firstIn) * inRow;
        for (int X = 0; X < width_; ++X) {
          const Span& sx = xSpans_[X];
          for (int c = 0; c < ch; ++c) {
            std::int64_t sum = 0;
            for (std::size_t j = 0; j < sx.weights.size(); ++j)
              sum += toLinear_[row[static_cast<std::size_t>(sx.first + j) * ch + c]] * sx.weights[j];
            horizontal[static_cast<std::size_t>(X) * ch + c] = sum;
          }
        }
        for (std::size_t s = 0; s < acc.size(); ++s) acc[s] += horizontal[s] * sy.weights[k];
      }
      std::uint16_t* dst = out + static_cast<std::size_t>(oy - y0) * width_ * ch;
      for (std::size_t s = 0; s < acc.size(); ++s) {
        const std::int64_t mean = (acc[s] + divisor / 2) / divisor;
        // The sample whose linear value is nearest the mean (ties to the lower sample): v is
        // the first sample at or above the mean, or the last one.
        std::size_t v = bucketStart_[std::min<std::size_t>(static_cast<std::size_t>(mean >> 8),
                                                           bucketStart_.size() - 1)];
        while (v < 65535 && toLinear_[v] < mean) ++v;
        if (v > 0 && toLinear_[v] >= mean && mean - toLinear_[v - 1] <= toLinear_[v] - mean) --v;
        dst[s] = static_cast<std::uint16_t>(v);
      }
    }
    Y = Yend;
  }
}

}  // namespace surrogate::stages
