#include "meta/exiv2_setup.h"

#include <exiv2/exiv2.hpp>

#include <mutex>

namespace surrogate::meta {

namespace {

std::mutex xmpToolkitMutex;

void lockXmpToolkit(void* data, bool lock) {
  auto* m = static_cast<std::mutex*>(data);
  if (lock) m->lock();
  else m->unlock();
}

}  // namespace

std::mutex& exiv2Mutex() {
  static std::mutex m;
  return m;
}

void ensureExiv2Ready() {
  static std::once_flag once;
  std::call_once(once, [] {
    Exiv2::LogMsg::setHandler(nullptr);  // no handler: messages are dropped, never printed
    Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute);
#ifdef EXV_ENABLE_BMFF
    Exiv2::enableBMFF(true);
#endif
    Exiv2::XmpParser::initialize(lockXmpToolkit, &xmpToolkitMutex);
  });
}

}  // namespace surrogate::meta
