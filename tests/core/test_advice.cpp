// The words of a warning (src/core/advice.h), against sentences written out here by hand.
#include <catch2/catch.hpp>

#include "core/advice.h"

using surrogate::Advice;
using surrogate::Usable;
using surrogate::adviceText;

TEST_CASE("advice reads what happened then usable or not then what to do then the figure", "[advice]") {
  CHECK(adviceText({"IMG_0003: the highlight is faint", Usable::WithCare, "its light may be off",
                    "look at it on the overview", "confidence 0.42"}) ==
        "IMG_0003: the highlight is faint. Usable with care: its light may be off. What to do: look at it on the "
        "overview. (confidence 0.42)");
  CHECK(adviceText({"A chart was found.", Usable::Yes, "", "nothing.", ""}) ==
        "A chart was found. Usable. What to do: nothing.");
  CHECK(adviceText({"x", Usable::No, "the map is empty. ", "run again", "0 of 5"}) ==
        "x. Not usable: the map is empty. What to do: run again. (0 of 5)");
}

// How a sphere is named on the command line (src/core/sphere_reference.h).
#include "core/sphere_reference.h"

TEST_CASE("spheres are named sphere1 from 1 and a bare number keeps its index from 0", "[sphere-reference]") {
  using surrogate::sphereIndexOfReference;
  CHECK(sphereIndexOfReference("sphere1") == 0);
  CHECK(sphereIndexOfReference("sphere2") == 1);
  CHECK(sphereIndexOfReference("0") == 0);
  CHECK(sphereIndexOfReference("1") == 1);
  CHECK_FALSE(sphereIndexOfReference("sphere0"));
  CHECK_FALSE(sphereIndexOfReference("sphere"));
  CHECK_FALSE(sphereIndexOfReference("Sphere1"));
  CHECK_FALSE(sphereIndexOfReference("-1"));
  CHECK_FALSE(sphereIndexOfReference("1x"));
  CHECK(surrogate::sphereReference(0) == "sphere1");
  CHECK(surrogate::personsSphereTarget("IMG_0003:1") == "IMG_0003:sphere2");
  CHECK(surrogate::personsSphereTarget("0") == "sphere1");
  CHECK(surrogate::personsSphereTarget("IMG_0003") == "IMG_0003");
}
