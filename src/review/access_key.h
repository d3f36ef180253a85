// The review server's key: a secret made when `surrogate review` starts and printed only in the
// address it gives (http://127.0.0.1:PORT/?key=KEY), so that only the person who started it (and
// the browser they open that address in) can use the page. Any other account of the computer
// reaches 127.0.0.1 too, and the loopback, Host and Origin checks of review.h do not tell it from
// the operator; the key does.
//
// The browser is given the key once, in the address; the server answers that first load with a
// cookie holding it (HttpOnly: the page's script never sees it; SameSite=Strict: no other site's
// page makes the browser send it), and the page takes the key out of the address bar
// (kForgetKeyJs), so that it does not stay on the screen or in the history. Every request after
// carries the cookie.
//
//   const AccessKey key = AccessKey::generate();
//   std::cout << "http://127.0.0.1:" << port << "/?key=" << key.text() << "\n";
//   if (!key.matchesOneOf(cookieValues(request.get_header_value("Cookie"), key.cookieName(port)))) refuse();
#pragma once

#include <string>
#include <vector>

namespace surrogate::review {

class AccessKey {
 public:
  // 32 bytes from OpenSSL's RAND_bytes (the operating system's random source), as 64 lowercase
  // hexadecimal digits: 256 bits, beyond guessing. Throws Error(Internal) when no random bytes
  // can be had.
  static AccessKey generate();

  const std::string& text() const { return text_; }
  // Whether `given` is this key, compared in constant time (CRYPTO_memcmp): how long a refusal
  // takes says nothing of how many characters were right.
  bool matches(const std::string& given) const;
  bool matchesOneOf(const std::vector<std::string>& given) const;
  // The cookie's name: one per port, since cookies are not kept apart by port and two reviews
  // served at once (two captures) must not overwrite each other's key in the browser.
  static std::string cookieName(int port);

 private:
  std::string text_;
};

// Served first in the page's script: replaces the address with the same one without its query
// (the key), as the page's history entry.
extern const char* const kForgetKeyJs;

// The values of cookie `name` in a Cookie header ("a=1; b=2"). There may be more than one: a
// page served by another program on 127.0.0.1 (cookies are not kept apart by port) can set one
// of the same name with another path, which the browser then sends first.
std::vector<std::string> cookieValues(const std::string& cookieHeader, const std::string& name);

}  // namespace surrogate::review
