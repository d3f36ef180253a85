// The decode floor: a plain libjpeg-turbo full decode of JPEG files to 8-bit RGB, nothing else.
//
// Every speed target of issue 19 is a ratio to this figure. The files are read into memory,
// then decoded on N threads (default: all cores), each thread taking the next file; the pixels
// are decoded into one buffer per thread and dropped. Prints wall time, CPU time (user and
// system) and peak resident memory, as text or (--json) as one JSON object.
//
// Two variants show what Surrogate's ImageDecode must do besides decoding, so that its time
// can be read against both (neither is the floor of the issue):
//   --hold    every image is kept, each in its own slot of one block of fresh memory, the way
//             the decoded stack holds them (mapped, advised as transparent huge pages, each
//             slot backed by madvise(MADV_POPULATE_WRITE) just before it is decoded into). On a
//             virtual machine fresh memory can cost more than the decoding (see
//             bench/fresh_memory_bench).
//   --digest  the SHA-256 of each image's decoded pixels, which the carrier records for every
//             image (OpenSSL, as Surrogate).
//
//   decode_floor [--threads N] [--json] [--hold] [--digest] FILE.jpg ...
//   decode_floor [--threads N] [--json] [--hold] [--digest] DIR   (every *.jpg / *.jpeg in DIR)
#include <sys/mman.h>
#include <sys/resource.h>

#include <cstdio>  // before jpeglib.h, which uses FILE
#include <jpeglib.h>
#include <openssl/evp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct ErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
};

[[noreturn]] void onJpegError(j_common_ptr info) {
  std::longjmp(reinterpret_cast<ErrorManager*>(info->err)->jump, 1);
}

std::vector<unsigned char> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Where a decoded image goes: into `into` when given (a slot of the held block, of `capacity`
// bytes), or else into `buffer` (reused across files). No destination: the header only.
struct Destination {
  std::vector<unsigned char>* buffer = nullptr;
  unsigned char* into = nullptr;
  std::size_t capacity = 0;
};

// Reads the header of one JPEG, then decodes it to RGB into `to` (not when `to` has neither
// buffer nor slot), with the SHA-256 of the pixels when `digest`. Returns the pixel count the
// header declares, or 0 when libjpeg reports an error or the image is larger than the slot.
std::size_t decodeRgb(const std::vector<unsigned char>& bytes, Destination to, bool digest) {
  jpeg_decompress_struct info{};
  ErrorManager errors{};
  info.err = jpeg_std_error(&errors.base);
  errors.base.error_exit = onJpegError;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    return 0;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  const std::size_t count = std::size_t(info.image_width) * info.image_height;
  if ((!to.buffer && !to.into) || (to.into && count * 3 > to.capacity)) {
    jpeg_destroy_decompress(&info);
    return to.into ? 0 : count;  // a file larger than the first would overrun its slot: failed
  }
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  const std::size_t stride = std::size_t(info.output_width) * info.output_components;
  unsigned char* pixels = to.into;
  if (!pixels) {
    to.buffer->resize(stride * info.output_height);
    pixels = to.buffer->data();
  }
  while (info.output_scanline < info.output_height) {
    JSAMPROW rows[16];
    const unsigned n = std::min(16u, info.output_height - info.output_scanline);
    for (unsigned r = 0; r < n; ++r) rows[r] = pixels + (info.output_scanline + r) * stride;
    jpeg_read_scanlines(&info, rows, n);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  if (digest) {
    unsigned char sha[EVP_MAX_MD_SIZE];
    unsigned length = 0;
    EVP_Digest(pixels, stride * info.output_height, sha, &length, EVP_sha256(), nullptr);
  }
  return count;
}

std::vector<fs::path> listInputs(const std::vector<std::string>& args) {
  std::vector<fs::path> files;
  for (const std::string& a : args) {
    if (!fs::is_directory(a)) {
      files.emplace_back(a);
      continue;
    }
    for (const auto& e : fs::directory_iterator(a)) {
      std::string ext = e.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (ext == ".jpg" || ext == ".jpeg") files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

#define SURROGATE_STRINGIFY2(x) #x
#define SURROGATE_STRINGIFY(x) SURROGATE_STRINGIFY2(x)
const char* libjpegVersion() {
#ifdef LIBJPEG_TURBO_VERSION
  return "turbo " SURROGATE_STRINGIFY(LIBJPEG_TURBO_VERSION);
#else
  return "API " SURROGATE_STRINGIFY(JPEG_LIB_VERSION);
#endif
}

double seconds(const timeval& t) { return t.tv_sec + t.tv_usec / 1e6; }

constexpr std::size_t kHugePage = std::size_t(2) << 20;

// One block of fresh memory for `bytes`, on a huge page boundary, advised as huge pages (the
// stack's MappedBlock). Never unmapped: the program ends after the decode. Written out here
// rather than taken from core/resident.h, so that the floor does not move with the code it is
// the floor of (bench/fresh_memory_bench measures that code).
unsigned char* freshBlock(std::size_t bytes) {
  const std::size_t mapped = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = mmap(nullptr, mapped + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return nullptr;
  auto* at = reinterpret_cast<unsigned char*>((reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) / kHugePage * kHugePage);
  madvise(at, mapped, MADV_HUGEPAGE);
  return at;
}

// Backs the pages of [p, p + bytes) before they are written, as makeResident does for a slot.
void populate(unsigned char* p, std::size_t bytes) {
  const std::uintptr_t page = 4096, at = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t begin = at / page * page, end = (at + bytes + page - 1) / page * page;
  madvise(reinterpret_cast<void*>(begin), end - begin, 23 /* MADV_POPULATE_WRITE, Linux 5.14 */);
}

}  // namespace

int main(int argc, char** argv) {
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  bool json = false, hold = false, digest = false;
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) threads = std::max(1, std::atoi(argv[++i]));
    else if (a == "--json") json = true;
    else if (a == "--hold") hold = true;
    else if (a == "--digest") digest = true;
    else args.push_back(a);
  }
  const std::vector<fs::path> files = listInputs(args);
  if (files.empty()) {
    std::fprintf(stderr, "usage: decode_floor [--threads N] [--json] [--hold] [--digest] FILE.jpg ... | DIR\n");
    return 2;
  }
  // Reading the files is not decoding: they are in memory before the clock starts.
  std::vector<std::vector<unsigned char>> data;
  for (const fs::path& f : files) data.push_back(readBytes(f));
  // The held block is mapped (not backed) before the clock starts, as the stack is made once
  // the first image's size is known; its slots are backed inside the clock.
  std::size_t slot = 0;
  unsigned char* block = nullptr;
  if (hold) {
    const std::size_t declared = decodeRgb(data.front(), Destination{}, false);  // the header only
    if (declared == 0) {
      std::fprintf(stderr, "decode_floor: %s is not a JPEG libjpeg can read\n", files.front().c_str());
      return 1;
    }
    slot = declared * 3;
    block = freshBlock(slot * data.size());
    if (!block) {
      std::fprintf(stderr, "decode_floor: no memory for %zu images of %zu pixels\n", data.size(), declared);
      return 1;
    }
  }

  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  std::atomic<std::size_t> next{0}, pixels{0}, failed{0};
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) {
    pool.emplace_back([&] {
      std::vector<unsigned char> buffer;
      for (std::size_t i; (i = next++) < data.size();) {
        unsigned char* into = nullptr;
        if (block) {
          into = block + i * slot;
          populate(into, slot);
        }
        const std::size_t n = decodeRgb(data[i], {&buffer, into, slot}, digest);
        pixels += n;
        if (n == 0) ++failed;
      }
    });
  }
  for (std::thread& t : pool) t.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  const double user = seconds(after.ru_utime) - seconds(before.ru_utime);
  const double sys = seconds(after.ru_stime) - seconds(before.ru_stime);
  const double peakMiB = after.ru_maxrss / 1024.0;

  if (json) {
    std::printf("{\"files\":%zu,\"failed\":%zu,\"threads\":%u,\"hold\":%s,\"digest\":%s,\"megapixels\":%.3f,"
                "\"wall_s\":%.4f,\"user_s\":%.4f,\"sys_s\":%.4f,\"peak_mib\":%.1f,\"libjpeg\":\"%s\"}\n",
                files.size(), failed.load(), threads, hold ? "true" : "false", digest ? "true" : "false",
                pixels / 1e6, wall, user, sys, peakMiB, libjpegVersion());
  } else {
    std::printf("decoded %zu JPEG files (%.1f Mpx) to RGB on %u threads (libjpeg %s)%s%s\n", files.size(),
                pixels / 1e6, threads, libjpegVersion(), hold ? ", each held in fresh memory" : "",
                digest ? ", SHA-256 of each image's pixels" : "");
    std::printf("  wall %.3f s, CPU %.3f s (user %.3f, system %.3f), peak %.0f MiB\n", wall, user + sys, user,
                sys, peakMiB);
    if (failed) std::printf("  %zu files failed to decode\n", failed.load());
  }
  return failed ? 1 : 0;
}
