#include "fastcorot/fem/rotation_method.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

TEST(RotationMethod, AcceptsSofaNamesAndAliases) {
  // Names and aliases of SOFA's FastTetrahedralCorotationalForceField `method` (SPEC.md).
  EXPECT_EQ(parse_rotation_method("qr"), RotationMethod::qr);
  EXPECT_EQ(parse_rotation_method("large"), RotationMethod::qr);
  EXPECT_EQ(parse_rotation_method("polar"), RotationMethod::polar);
  EXPECT_EQ(parse_rotation_method("polar2"), RotationMethod::polar2);
  EXPECT_EQ(parse_rotation_method("none"), RotationMethod::none);
  EXPECT_EQ(parse_rotation_method("linear"), RotationMethod::none);
  EXPECT_EQ(parse_rotation_method("small"), RotationMethod::none);
}

TEST(RotationMethod, CanonicalNamesRoundTrip) {
  for (auto method : {RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2, RotationMethod::none}) {
    EXPECT_EQ(parse_rotation_method(to_string(method)), method);
  }
}

TEST(RotationMethod, UnknownNameIsAnErrorNamingIt) {
  for (const char* bad : {"svd", "", "QR", "polar3"}) {
    try {
      parse_rotation_method(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(std::string("\"") + bad + "\""), std::string::npos);
      EXPECT_NE(std::string(error.what()).find("polar2"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace fastcorot
