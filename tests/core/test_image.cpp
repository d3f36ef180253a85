#include <catch2/catch.hpp>

#include "core/image.h"

using namespace surrogate;

TEST_CASE("luminance of white is white and of pure green is its Rec.709 weight") {
  Image rgb(2, 1, 3);
  rgb.at(0, 0, 0) = rgb.at(0, 0, 1) = rgb.at(0, 0, 2) = 65535;
  rgb.at(1, 0, 1) = 65535;
  const Image y = luminance(rgb);
  REQUIRE(y.channels == 1);
  CHECK(y.at(0, 0) == 65535);
  CHECK(y.at(1, 0) == Approx(0.7152 * 65535).margin(1));
}

#include "core/json.h"

TEST_CASE("JsonWriter separates members and escapes control characters") {
  JsonWriter j;
  j.beginObject().key("a").value(1).key("b").beginArray().value("x\"\n").value(true).endArray()
      .key("c").value(0.5).endObject();
  CHECK(j.str() == "{\"a\":1,\"b\":[\"x\\\"\\n\",true],\"c\":0.5}");
}
