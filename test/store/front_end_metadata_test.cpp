// The metadata rows that record a map's front end, read back as the front end they were written of.

#include "store/front_end_metadata.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace mrs_vpr {
namespace {

std::map<std::string, std::string> asTable(const DescriptorParams& params) {
  std::map<std::string, std::string> table;
  for (const auto& [key, value] : frontEndMetadata(params)) table[key] = value;
  return table;
}

TEST(FrontEndMetadata, EachFrontEndReadsBackAsWritten) {
  DescriptorParams hog;
  hog.type = kHogFrontEnd;
  hog.hog_cell_size = 8;
  hog.hog_blur = 0.1;  // A fraction that a short decimal would round.
  DescriptorParams thumbnail;
  thumbnail.type = kThumbnailFrontEnd;
  thumbnail.image_width = 32;
  for (const DescriptorParams& written : {hog, thumbnail}) {
    const auto read = frontEndOfMetadata(asTable(written));
    ASSERT_TRUE(read.has_value()) << written.describe();
    EXPECT_TRUE(read->sameFrontEnd(written)) << read->describe() << " against " << written.describe();
    EXPECT_EQ(read->hog_blur, written.hog_blur);
  }
  EXPECT_EQ(asTable(hog).count("patch_size"), 0U) << "only the chosen front end's parameters are recorded";
  EXPECT_EQ(asTable(thumbnail).count("hog_bins"), 0U);
}

TEST(FrontEndMetadata, AMapWithoutATypeHoldsThumbnails) {
  // Maps written before the front end could be chosen record the thumbnail's parameters and no type.
  DescriptorParams thumbnail;
  thumbnail.type = kThumbnailFrontEnd;
  std::map<std::string, std::string> table = asTable(thumbnail);
  table.erase("descriptor_type");
  const auto read = frontEndOfMetadata(table);
  ASSERT_TRUE(read.has_value());
  EXPECT_TRUE(read->sameFrontEnd(thumbnail)) << read->describe();
}

TEST(FrontEndMetadata, AMissingOrMalformedValueReadsAsNoFrontEnd) {
  DescriptorParams hog;
  hog.type = kHogFrontEnd;
  std::map<std::string, std::string> missing = asTable(hog);
  missing.erase("hog_bins");
  EXPECT_FALSE(frontEndOfMetadata(missing).has_value());
  // A fraction or a number no int holds (a corrupt map) is no value either, not a rounded or overflowed one.
  for (const char* bad : {"", "9 bins", "nine", "8.5", "1e20", "-1e20", "nan"}) {
    std::map<std::string, std::string> malformed = asTable(hog);
    malformed["hog_bins"] = bad;
    EXPECT_FALSE(frontEndOfMetadata(malformed).has_value()) << "'" << bad << "'";
  }
  std::map<std::string, std::string> unknown = asTable(hog);
  unknown["descriptor_type"] = "sift";
  EXPECT_FALSE(frontEndOfMetadata(unknown).has_value());
}

}  // namespace
}  // namespace mrs_vpr
