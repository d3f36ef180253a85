#include "bag_check.h"

#include <archive.h>
#include <archive_entry.h>
#include <openssl/evp.h>

#include <locale.h>

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace bagcheck {

namespace fs = std::filesystem;

namespace {
std::string hexDigest(const EVP_MD* md, const std::string& bytes) {
  unsigned char out[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  EVP_Digest(bytes.data(), bytes.size(), out, &len, md, nullptr);
  static const char* digits = "0123456789abcdef";
  std::string hex;
  for (unsigned i = 0; i < len; ++i) {
    hex.push_back(digits[out[i] >> 4]);
    hex.push_back(digits[out[i] & 15]);
  }
  return hex;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string decodePath(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      const std::string code = s.substr(i + 1, 2);
      if (code == "0A" || code == "0a") { out.push_back('\n'); i += 2; continue; }
      if (code == "0D" || code == "0d") { out.push_back('\r'); i += 2; continue; }
      if (code == "25") { out.push_back('%'); i += 2; continue; }
    }
    out.push_back(s[i]);
  }
  return out;
}
}  // namespace

std::string sha256(const std::string& bytes) { return hexDigest(EVP_sha256(), bytes); }
std::string sha512(const std::string& bytes) { return hexDigest(EVP_sha512(), bytes); }

BagFiles readBag(const fs::path& bag) {
  BagFiles out;
  if (fs::is_directory(bag)) {
    for (auto it = fs::recursive_directory_iterator(bag); it != fs::recursive_directory_iterator(); ++it)
      if (it->is_regular_file()) out.files[it->path().lexically_relative(bag).generic_string()] = slurp(it->path());
    return out;
  }
  archive* a = archive_read_new();
  archive_read_support_format_tar(a);
  archive_read_support_format_zip(a);
  if (archive_read_open_filename(a, bag.c_str(), 1 << 16) != ARCHIVE_OK)
    throw std::runtime_error("cannot open " + bag.string());
  archive_entry* e = nullptr;
  // Names are UTF-8: read them through a UTF-8 locale on this thread.
  locale_t utf8 = newlocale(LC_CTYPE_MASK, "C.UTF-8", static_cast<locale_t>(0));
  locale_t previous = utf8 ? uselocale(utf8) : static_cast<locale_t>(0);
  int rc;
  while ((rc = archive_read_next_header(a, &e)) == ARCHIVE_OK || rc == ARCHIVE_WARN) {
    std::string name = archive_entry_pathname_utf8(e) ? archive_entry_pathname_utf8(e) : archive_entry_pathname(e);
    const auto slash = name.find('/');
    const std::string top = name.substr(0, slash);
    if (out.top.empty()) out.top = top;
    if (top != out.top) throw std::runtime_error("more than one top-level folder: " + top);
    name = name.substr(slash + 1);
    std::string content;
    char buffer[65536];
    la_ssize_t n;
    while ((n = archive_read_data(a, buffer, sizeof buffer)) > 0) content.append(buffer, static_cast<std::size_t>(n));
    if (out.files.count(name)) throw std::runtime_error("duplicate entry " + name);
    out.files[name] = content;
    out.order.push_back(name);
  }
  if (rc != ARCHIVE_EOF) throw std::runtime_error("corrupt archive " + bag.string() + ": " + archive_error_string(a));
  archive_read_free(a);
  if (utf8) {
    uselocale(previous);
    freelocale(utf8);
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> parseManifest(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto space = line.find_first_of(" \t");
    const auto start = line.find_first_not_of(" \t", space);
    lines.emplace_back(line.substr(0, space), decodePath(line.substr(start)));
  }
  return lines;
}

std::multimap<std::string, std::string> parseBagInfo(const std::string& text) {
  std::multimap<std::string, std::string> info;
  std::istringstream in(text);
  std::string line, label, value;
  auto flush = [&] { if (!label.empty()) info.emplace(label, value); label.clear(); };
  while (std::getline(in, line)) {
    if (!line.empty() && (line[0] == ' ' || line[0] == '\t')) {
      value += "\n" + line.substr(line.find_first_not_of(" \t"));
      continue;
    }
    flush();
    const auto colon = line.find(": ");
    label = line.substr(0, colon);
    value = line.substr(colon + 2);
  }
  flush();
  return info;
}

std::vector<std::string> validate(const BagFiles& bag) {
  std::vector<std::string> problems;
  const auto& f = bag.files;
  auto get = [&](const std::string& n) -> const std::string* {
    auto it = f.find(n);
    return it == f.end() ? nullptr : &it->second;
  };
  const std::string* bagit = get("bagit.txt");
  if (!bagit || *bagit != "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n")
    problems.push_back("bagit.txt missing or not exactly the two 1.0 lines");

  std::set<std::string> payload;
  std::uint64_t bytes = 0;
  for (const auto& [name, content] : f)
    if (name.rfind("data/", 0) == 0) { payload.insert(name); bytes += content.size(); }

  bool anyManifest = false;
  for (const char* alg : {"sha256", "sha512"}) {
    const std::string* m = get(std::string("manifest-") + alg + ".txt");
    if (!m) { problems.push_back(std::string("no manifest-") + alg + ".txt"); continue; }
    anyManifest = true;
    std::set<std::string> listed;
    for (const auto& [hex, path] : parseManifest(*m)) {
      if (!listed.insert(path).second) problems.push_back("listed twice: " + path);
      if (path.rfind("data/", 0) != 0) problems.push_back("manifest path outside data/: " + path);
      const std::string* content = get(path);
      if (!content) { problems.push_back("listed but missing: " + path); continue; }
      const std::string actual = std::string(alg) == "sha256" ? sha256(*content) : sha512(*content);
      if (actual != hex) problems.push_back(std::string(alg) + " mismatch: " + path);
    }
    for (const std::string& p : payload)
      if (!listed.count(p)) problems.push_back(std::string("payload not in manifest-") + alg + ": " + p);
  }
  if (!anyManifest) problems.push_back("no payload manifest");

  const std::string* info = get("bag-info.txt");
  if (!info) {
    problems.push_back("no bag-info.txt");
  } else {
    const auto parsed = parseBagInfo(*info);
    if (parsed.count("Payload-Oxum") != 1) problems.push_back("Payload-Oxum not given exactly once");
    else if (parsed.find("Payload-Oxum")->second != std::to_string(bytes) + "." + std::to_string(payload.size()))
      problems.push_back("Payload-Oxum wrong: " + parsed.find("Payload-Oxum")->second);
  }

  for (const char* alg : {"sha256", "sha512"}) {
    const std::string name = std::string("tagmanifest-") + alg + ".txt";
    const std::string* m = get(name);
    if (!m) { problems.push_back("no " + name); continue; }
    std::set<std::string> listed;
    for (const auto& [hex, path] : parseManifest(*m)) {
      listed.insert(path);
      if (path.rfind("data/", 0) == 0 || path.rfind("tagmanifest-", 0) == 0)
        problems.push_back(name + " lists " + path);
      const std::string* content = get(path);
      if (!content) { problems.push_back("tag file listed but missing: " + path); continue; }
      const std::string actual = std::string(alg) == "sha256" ? sha256(*content) : sha512(*content);
      if (actual != hex) problems.push_back(name + " mismatch: " + path);
    }
    for (const auto& [path, content] : f)
      if (path.rfind("data/", 0) != 0 && path.rfind("tagmanifest-", 0) != 0 && !listed.count(path))
        problems.push_back("tag file not in " + name + ": " + path);
  }
  return problems;
}

}  // namespace bagcheck
