#include "meta/xmp_packet_scan.h"

namespace surrogate::meta {

std::vector<std::string> scanXmpPackets(const std::string& bytes) {
  static const std::string kBegin = "<?xpacket begin=";
  static const std::string kEnd = "<?xpacket end=";
  std::vector<std::string> packets;
  std::size_t from = 0;
  while (true) {
    const std::size_t begin = bytes.find(kBegin, from);
    if (begin == std::string::npos) break;
    const std::size_t end = bytes.find(kEnd, begin + kBegin.size());
    if (end == std::string::npos) break;
    const std::size_t close = bytes.find("?>", end + kEnd.size());
    if (close == std::string::npos) break;
    packets.push_back(bytes.substr(begin, close + 2 - begin));
    from = close + 2;
  }
  return packets;
}

}  // namespace surrogate::meta
