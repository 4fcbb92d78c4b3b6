// Reading flight-path JSON: a good file round-trips; every bad input is one InvalidInput error
// naming the file, line and column, and the field path.

#include <string>

#include <gtest/gtest.h>

#include "flight/flight_path_json.h"

namespace vegstream::flight {
namespace {

const std::string kGood = R"({
  "name": "demo",
  "keyframes": [
    {"t": 0, "lat": 37.20, "lon": -112.98, "alt_m": 500, "heading": 10, "pitch": -20},
    {"t": 5, "lat": 37.21, "lon": -112.97, "alt_m": 1800, "alt_ref": "msl", "heading": 20, "pitch": -10},
    {"t": 9.5, "lat": 37.22, "lon": -112.96, "alt_m": 30, "alt_ref": "terrain", "heading": 350, "pitch": 0}
  ],
  "colliders": [
    {"name": "ball", "shape": "sphere", "radius_m": 2,
     "keyframes": [{"t": 0, "lat": 37.2, "lon": -112.98, "alt_m": 2}]}
  ]
})";

// The error message for text, which must fail to parse.
std::string errorFor(const std::string& text) {
  const Result<FlightPath> r = parseFlightPath(text, "paths/bad.json");
  EXPECT_FALSE(r.ok()) << text;
  if (r.ok()) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  return r.error().message;
}

// kGood with one substring replaced.
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kGood;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

#define EXPECT_HAS(haystack, needle) EXPECT_NE((haystack).find(needle), std::string::npos) << (haystack)

TEST(FlightPathJson, ReadsAGoodFileWithDefaults) {
  const Result<FlightPath> r = parseFlightPath(kGood, "paths/demo.json");
  ASSERT_TRUE(r.ok()) << r.error().message;
  const FlightPath& p = *r;
  EXPECT_EQ(p.name, "demo");
  ASSERT_EQ(p.keyframes.size(), 3u);
  EXPECT_EQ(p.keyframes[0].altRef, AltRef::Terrain) << "alt_ref defaults to terrain";
  EXPECT_EQ(p.keyframes[1].altRef, AltRef::Msl);
  EXPECT_DOUBLE_EQ(p.keyframes[2].t, 9.5);
  EXPECT_DOUBLE_EQ(p.duration(), 9.5);
  EXPECT_DOUBLE_EQ(p.bounds().northDeg, 37.22);
  EXPECT_DOUBLE_EQ(p.bounds().westDeg, -112.98);
  ASSERT_EQ(p.colliders.size(), 1u);
  EXPECT_EQ(p.colliders[0].shape, Collider::Shape::Sphere);
  EXPECT_DOUBLE_EQ(p.colliders[0].radiusM, 2.0);
}

TEST(FlightPathJson, WritesWhatItReads) {
  const FlightPath a = *parseFlightPath(kGood, "x.json");
  const Result<FlightPath> b = parseFlightPath(flightPathToJson(a), "y.json");
  ASSERT_TRUE(b.ok()) << b.error().message;
  ASSERT_EQ(b->keyframes.size(), a.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    EXPECT_NEAR(b->keyframes[i].lat, a.keyframes[i].lat, 1e-7);
    EXPECT_NEAR(b->keyframes[i].altM, a.keyframes[i].altM, 1e-3);
    EXPECT_EQ(b->keyframes[i].altRef, a.keyframes[i].altRef);
    EXPECT_NEAR(b->keyframes[i].headingDeg, a.keyframes[i].headingDeg, 1e-3);
  }
  EXPECT_EQ(b->name, "demo");
  ASSERT_EQ(b->colliders.size(), 1u);
  EXPECT_EQ(b->colliders[0].keyframes.size(), 1u);
}

TEST(FlightPathJson, MalformedJsonGivesLineAndColumn) {
  // A missing comma after the pitch of the second keyframe (line 5).
  const std::string m = errorFor(edited(R"("pitch": -10},)", R"("pitch": -10})"));
  EXPECT_HAS(m, "paths/bad.json:6:5: malformed JSON");
  EXPECT_EQ(errorFor("{\n  \"name\": \"x\",\n  \"keyframes\": [\n").find("paths/bad.json:4:1:"), 0u);
}

TEST(FlightPathJson, MissingFieldNamesThePathAndLine) {
  const std::string m = errorFor(edited(R"("lat": 37.21, )", ""));
  EXPECT_HAS(m, "paths/bad.json:5:5: keyframes[1].lat: missing required number");
  EXPECT_HAS(errorFor(R"({"name": "x"})"), "keyframes: missing required array");
  EXPECT_HAS(errorFor(edited(R"("heading": 350, )", "")), ":6:5: keyframes[2].heading: missing");
}

TEST(FlightPathJson, WrongTypeNamesTheField) {
  const std::string m = errorFor(edited(R"("alt_m": 1800)", R"("alt_m": "1800")"));
  EXPECT_HAS(m, ":5:");
  EXPECT_HAS(m, "keyframes[1].alt_m: must be a number, found a string");
  EXPECT_HAS(errorFor(edited(R"("alt_ref": "msl")", R"("alt_ref": "sea")")),
             "keyframes[1].alt_ref: \"sea\" is not one of");
  EXPECT_HAS(errorFor("[1, 2]"), "document: must be an object, found an array");
  EXPECT_HAS(errorFor(edited(R"("keyframes": [)", R"("keyframes": [ 7, )")), "keyframes[0]: must be an object");
  EXPECT_HAS(errorFor(edited("-112.97", "1e999")), "bad.json:5:35: malformed JSON: number overflow parsing '1e999'");
}

TEST(FlightPathJson, UnknownKeyIsRefusedWithASuggestion) {
  const std::string m = errorFor(edited(R"("pitch": 0)", R"("ptich": 0)"));
  EXPECT_HAS(m, "paths/bad.json:6:");
  EXPECT_HAS(m, "keyframes[2].ptich: unknown key \"ptich\" (did you mean \"pitch\"?)");
  EXPECT_HAS(errorFor(edited(R"("name": "demo")", R"("nmae": "demo")")), ":2:11: nmae: unknown key");
  EXPECT_HAS(errorFor(edited(R"("radius_m": 2)", R"("radius": 2)")), "colliders[0].radius: unknown key");
  EXPECT_HAS(errorFor(edited(R"("heading": 10,)", R"("heading": 10, "heading": 11,)")), "bad.json:4:");
  EXPECT_HAS(errorFor(edited(R"("heading": 10,)", R"("heading": 10, "heading": 11,)")),
             "keyframes[0].heading: key given twice");
}

TEST(FlightPathJson, KeyframesOutOfTimeOrder) {
  const std::string m = errorFor(edited(R"("t": 9.5)", R"("t": 4)"));
  EXPECT_HAS(m, "paths/bad.json:6:11: keyframes[2].t: t = 4.000 s is not after keyframes[1].t = 5.000 s");
  EXPECT_HAS(errorFor(edited(R"("t": 0)", R"("t": 1)")), "keyframes[0].t: the first keyframe must be at t = 0");
}

TEST(FlightPathJson, FewerThanTwoKeyframes) {
  const std::string one = R"({"keyframes": [{"t": 0, "lat": 1, "lon": 2, "alt_m": 3, "heading": 0, "pitch": 0}]})";
  EXPECT_HAS(errorFor(one), "paths/bad.json:1:15: keyframes: a path needs at least 2 keyframes, found 1");
  EXPECT_HAS(errorFor(R"({"keyframes": []})"), "found 0");
}

TEST(FlightPathJson, LatitudeOutOfRange) {
  const std::string m = errorFor(edited("37.21", "95"));
  EXPECT_HAS(m, "paths/bad.json:5:21: keyframes[1].lat: 95.000000 is out of range [-90, 90]");
  EXPECT_HAS(errorFor(edited("-112.96", "-190")), "keyframes[2].lon: -190.000000 is out of range [-180, 180]");
  EXPECT_HAS(errorFor(edited(R"("pitch": -20)", R"("pitch": -120)")), "keyframes[0].pitch");
  EXPECT_HAS(errorFor(edited(R"("alt_m": 30)", R"("alt_m": -3)")),
             "keyframes[2].alt_m: -3.0 m above the terrain is underground");
  EXPECT_HAS(errorFor(edited(R"("radius_m": 2)", R"("radius_m": 0)")), "colliders[0].radius_m: must be a positive");
  EXPECT_HAS(errorFor(edited(R"("shape": "sphere")", R"("shape": "capsule")")), "colliders[0].length_m: missing");
}

TEST(FlightPathJson, PathOutsideTheDataset) {
  const FlightPath p = *parseFlightPath(kGood, "x.json");
  const geo::GeoBounds zion{-113.2396, 37.1321, -112.8521, 37.5129};
  EXPECT_TRUE(checkInside(p, zion).ok());
  const geo::GeoBounds small{-112.99, 37.19, -112.965, 37.25};
  const Status s = checkInside(p, small);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().kind, ErrorKind::InvalidInput);
  EXPECT_HAS(s.error().message,
             "path leaves the dataset at keyframes[2] (37.220000, -112.960000) — dataset covers lat 37.190000");
}

TEST(FlightPathJson, LoadNamesTheFile) {
  const Result<FlightPath> r = loadFlightPath("/nonexistent/dir/p.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::NotFound);
  EXPECT_HAS(r.error().message, "/nonexistent/dir/p.json");
}

}  // namespace
}  // namespace vegstream::flight
