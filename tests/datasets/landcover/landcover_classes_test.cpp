// The landcover class tables (landcover_classes.h): every code of both schemes with its name and
// kind, the scheme names, detection from a histogram of codes (decided, and each way of being
// ambiguous), and the report of codes a scheme does not know.

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "datasets/landcover_classes.h"

namespace vegstream::datasets {
namespace {

using K = LandcoverKind;

std::map<int, K> kinds(LandcoverScheme s) {
  std::map<int, K> m;
  for (const LandcoverClass& c : landcoverClasses(s)) m[c.code] = c.kind;
  return m;
}

TEST(LandcoverClasses, WorldCoverTable) {
  const std::map<int, K> expected = {{10, K::Tree},    {20, K::Shrub}, {30, K::Grass}, {40, K::Crop},
                                     {50, K::Built},   {60, K::Bare},  {70, K::Snow},  {80, K::Water},
                                     {90, K::Wetland}, {95, K::Tree},  {100, K::Grass}};
  EXPECT_EQ(kinds(LandcoverScheme::WorldCover), expected);
  EXPECT_STREQ(findLandcoverClass(LandcoverScheme::WorldCover, 10)->name, "Tree cover");
  EXPECT_STREQ(findLandcoverClass(LandcoverScheme::WorldCover, 60)->name, "Bare / sparse vegetation");
  EXPECT_STREQ(findLandcoverClass(LandcoverScheme::WorldCover, 100)->name, "Moss and lichen");
  EXPECT_EQ(findLandcoverClass(LandcoverScheme::WorldCover, 0), nullptr);
  EXPECT_EQ(findLandcoverClass(LandcoverScheme::WorldCover, 11), nullptr);
  EXPECT_EQ(findLandcoverClass(LandcoverScheme::WorldCover, 255), nullptr);
}

TEST(LandcoverClasses, NlcdTable) {
  const std::map<int, K> expected = {{11, K::Water}, {12, K::Snow},  {21, K::Built}, {22, K::Built}, {23, K::Built},
                                     {24, K::Built}, {31, K::Bare},  {41, K::Tree},  {42, K::Tree},  {43, K::Tree},
                                     {51, K::Shrub}, {52, K::Shrub}, {71, K::Grass}, {72, K::Grass}, {73, K::Grass},
                                     {74, K::Grass}, {81, K::Grass}, {82, K::Crop},  {90, K::Tree},  {95, K::Wetland}};
  EXPECT_EQ(kinds(LandcoverScheme::Nlcd), expected);
  EXPECT_STREQ(findLandcoverClass(LandcoverScheme::Nlcd, 42)->name, "Evergreen Forest");
  EXPECT_STREQ(findLandcoverClass(LandcoverScheme::Nlcd, 95)->name, "Emergent Herbaceous Wetlands");
  EXPECT_EQ(findLandcoverClass(LandcoverScheme::Nlcd, 10), nullptr);
  EXPECT_EQ(findLandcoverClass(LandcoverScheme::Nlcd, 0), nullptr);
}

TEST(LandcoverClasses, TablesAreSortedAndNamed) {
  for (LandcoverScheme s : {LandcoverScheme::WorldCover, LandcoverScheme::Nlcd}) {
    int last = 0;
    for (const LandcoverClass& c : landcoverClasses(s)) {
      EXPECT_GT(c.code, last) << toString(s);  // ascending and no 0: the lookup is a binary search
      last = c.code;
      EXPECT_GT(std::string(c.name).size(), 2u);
    }
  }
  EXPECT_STREQ(toString(K::Wetland), "wetland");
  EXPECT_STREQ(toString(K::Built), "built");
}

TEST(LandcoverScheme, Parse) {
  EXPECT_EQ(*parseLandcoverScheme("worldcover"), std::optional(LandcoverScheme::WorldCover));
  EXPECT_EQ(*parseLandcoverScheme("nlcd"), std::optional(LandcoverScheme::Nlcd));
  EXPECT_EQ(*parseLandcoverScheme("auto"), std::nullopt);
  auto bad = parseLandcoverScheme("corine");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(bad.error().message.find("'corine'"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("worldcover, nlcd or auto"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(parseLandcoverScheme("WorldCover"));  // names are lower case, as in dataset.json
}

ClassHistogram histogram(std::initializer_list<std::pair<int, uint64_t>> counts) {
  ClassHistogram h{};
  for (const auto& [code, n] : counts) h[static_cast<size_t>(code)] = n;
  return h;
}

TEST(LandcoverScheme, DetectedFromTheCodesOnlyOneSchemeHas) {
  auto wc = detectLandcoverScheme(histogram({{0, 5000}, {10, 100}, {30, 50}, {80, 7}, {95, 3}}), "wc.tif");
  ASSERT_TRUE(wc) << wc.error().message;
  EXPECT_EQ(*wc, LandcoverScheme::WorldCover);
  auto nlcd = detectLandcoverScheme(histogram({{11, 10}, {42, 300}, {90, 20}, {95, 20}, {250, 4}}), "nlcd.tif");
  ASSERT_TRUE(nlcd) << nlcd.error().message;
  EXPECT_EQ(*nlcd, LandcoverScheme::Nlcd);
  // One code of one scheme among codes both have (90, 95) decides.
  auto one = detectLandcoverScheme(histogram({{90, 1000}, {95, 1000}, {100, 1}}), "m.tif");
  ASSERT_TRUE(one) << one.error().message;
  EXPECT_EQ(*one, LandcoverScheme::WorldCover);
}

void expectAmbiguous(const ClassHistogram& h, std::initializer_list<const char*> pieces) {
  auto r = detectLandcoverScheme(h, "lc.tif");
  ASSERT_FALSE(r) << "detected " << toString(*r);
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  const std::string& m = r.error().message;
  EXPECT_NE(m.find("'lc.tif'"), std::string::npos) << m;
  EXPECT_NE(m.find("--landcover-scheme"), std::string::npos) << m;
  for (const char* p : pieces) EXPECT_NE(m.find(p), std::string::npos) << p << " in " << m;
}

TEST(LandcoverScheme, AmbiguousCodesAreAnErrorSuggestingTheOption) {
  // Codes of both schemes (e.g. a CORINE-like numbering).
  expectAmbiguous(histogram({{10, 40}, {11, 30}, {20, 5}}),
                  {"only WorldCover has, 10 (40 px), 20 (5 px)", "only NLCD has, 11 (30 px)"});
  // Only codes both have.
  expectAmbiguous(histogram({{90, 40}, {95, 2}}), {"none of its codes"});
  // Nothing but no data.
  expectAmbiguous(histogram({{0, 400}}), {"no class codes at all"});
}

TEST(LandcoverScheme, UnknownCodesDoNotDecide) {
  // NLCD with an undeclared fill value (250) over most of the raster: still NLCD, and the fill
  // is reported as unknown.
  const ClassHistogram h = histogram({{250, 90000}, {42, 300}, {11, 20}});
  auto s = detectLandcoverScheme(h, "nlcd.tif");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(*s, LandcoverScheme::Nlcd);
  EXPECT_EQ(unknownClasses(h, *s), (std::vector<UnknownClass>{{250, 90000}}));
  // Unknown codes alone decide nothing.
  expectAmbiguous(histogram({{1, 50}, {2, 50}, {250, 9}}), {"none of its codes"});
}

TEST(LandcoverScheme, UnknownCodesAreListedWithTheirPixels) {
  const ClassHistogram h = histogram({{0, 99}, {7, 1234}, {10, 500}, {11, 3}, {255, 8}});
  const std::vector<UnknownClass> wc = unknownClasses(h, LandcoverScheme::WorldCover);
  const std::vector<UnknownClass> expected = {{7, 1234}, {11, 3}, {255, 8}};
  EXPECT_EQ(wc, expected);  // 0 (no data) is never unknown
  const std::vector<UnknownClass> nlcd = unknownClasses(h, LandcoverScheme::Nlcd);
  const std::vector<UnknownClass> expectedNlcd = {{7, 1234}, {10, 500}, {255, 8}};
  EXPECT_EQ(nlcd, expectedNlcd);
  EXPECT_TRUE(unknownClasses(histogram({{10, 5}, {20, 1}}), LandcoverScheme::WorldCover).empty());

  EXPECT_EQ(unknownClassesWarning({{7, 1234}}, LandcoverScheme::WorldCover),
            "class 7: 1234 pixels, unknown to worldcover; it grows nothing");
  EXPECT_EQ(unknownClassesWarning(wc, LandcoverScheme::WorldCover),
            "classes 7: 1234 pixels, 11: 3 pixels, 255: 8 pixels, unknown to worldcover; they grow nothing");
  EXPECT_EQ(unknownClassesWarning({}, LandcoverScheme::Nlcd), "");
}

}  // namespace
}  // namespace vegstream::datasets
