// Reading flight-path JSON: a good file round-trips; every bad input is one InvalidInput error
// naming the file, line and column, and the field path.

#include <cmath>
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

// kGood with a wind section (issue 19): a mean wind, a fan that moves and a fixed rotor.
const std::string kWindy = R"({
  "name": "windy",
  "keyframes": [
    {"t": 0, "lat": 37.20, "lon": -112.98, "alt_m": 500, "heading": 10, "pitch": -20},
    {"t": 5, "lat": 37.21, "lon": -112.97, "alt_m": 1800, "alt_ref": "msl", "heading": 20, "pitch": -10}
  ],
  "wind": {"speed_mps": 6, "direction_deg": 250, "gustiness": 0.6,
    "sources": [
      {"name": "fan", "type": "fan", "radius_m": 12, "strength_mps": 9, "direction_deg": 90,
       "keyframes": [{"t": 0, "lat": 37.2001, "lon": -112.9879, "alt_m": 3},
                     {"t": 4, "lat": 37.2011, "lon": -112.9869, "alt_m": 1250, "alt_ref": "msl"}]},
      {"name": "rotor", "type": "rotor", "radius_m": 8, "strength_mps": 14,
       "keyframes": [{"t": 0, "lat": 37.2005, "lon": -112.9875, "alt_m": 20}]}
    ]}
})";

// kWindy with one substring replaced.
std::string windEdited(const std::string& from, const std::string& to) {
  std::string s = kWindy;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(FlightPathJson, ReadsTheWindSection) {
  const Result<FlightPath> r = parseFlightPath(kWindy, "paths/windy.json");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->wind.has_value());
  const WindSection& w = *r->wind;
  EXPECT_EQ(w.speedMps, 6.0);
  EXPECT_EQ(w.directionDeg, 250.0);
  EXPECT_EQ(w.gustiness, 0.6);
  ASSERT_EQ(w.sources.size(), 2u);
  const WindSourceSpec& fan = w.sources[0];
  EXPECT_EQ(fan.name, "fan");
  EXPECT_EQ(fan.type, WindSourceSpec::Type::Fan);
  EXPECT_DOUBLE_EQ(fan.radiusM, 12.0);
  EXPECT_DOUBLE_EQ(fan.strengthMps, 9.0);
  EXPECT_EQ(fan.directionDeg, 90.0);
  ASSERT_EQ(fan.keyframes.size(), 2u);
  EXPECT_EQ(fan.keyframes[0].altRef, AltRef::Terrain) << "alt_ref defaults to terrain, as for colliders";
  EXPECT_EQ(fan.keyframes[1].altRef, AltRef::Msl);
  EXPECT_DOUBLE_EQ(fan.keyframes[1].t, 4.0);
  EXPECT_DOUBLE_EQ(fan.keyframes[1].lon, -112.9869);
  const WindSourceSpec& rotor = w.sources[1];
  EXPECT_EQ(rotor.type, WindSourceSpec::Type::Rotor);
  EXPECT_FALSE(rotor.directionDeg.has_value());
  EXPECT_DOUBLE_EQ(rotor.strengthMps, 14.0);
  ASSERT_EQ(rotor.keyframes.size(), 1u);

  EXPECT_FALSE(parseFlightPath(kGood, "x.json")->wind.has_value()) << "no section: none";
  const Result<FlightPath> empty = parseFlightPath(windEdited(R"("wind": {"speed_mps": 6, "direction_deg": 250, "gustiness": 0.6,
    "sources": [)", R"("wind": {"sources": [)"), "x.json");
  ASSERT_TRUE(empty.ok()) << empty.error().message;
  EXPECT_FALSE(empty->wind->speedMps.has_value()) << "every value of the section is optional";
  EXPECT_FALSE(empty->wind->gustiness.has_value());
  const Result<FlightPath> whirl = parseFlightPath(windEdited(R"("type": "rotor")", R"("type": "whirlwind")"), "x.json");
  ASSERT_TRUE(whirl.ok()) << whirl.error().message;
  EXPECT_EQ(whirl->wind->sources[1].type, WindSourceSpec::Type::Whirlwind);
}

TEST(FlightPathJson, WritesTheWindSectionBack) {
  const FlightPath a = *parseFlightPath(kWindy, "x.json");
  const std::string text = flightPathToJson(a);
  const Result<FlightPath> b = parseFlightPath(text, "y.json");
  ASSERT_TRUE(b.ok()) << b.error().message << "\n" << text;
  ASSERT_TRUE(b->wind.has_value()) << text;
  EXPECT_EQ(b->wind->speedMps, a.wind->speedMps);
  EXPECT_EQ(b->wind->directionDeg, a.wind->directionDeg);
  EXPECT_EQ(b->wind->gustiness, a.wind->gustiness);
  ASSERT_EQ(b->wind->sources.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const WindSourceSpec &x = a.wind->sources[i], &y = b->wind->sources[i];
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.type, x.type);
    EXPECT_DOUBLE_EQ(y.radiusM, x.radiusM);
    EXPECT_DOUBLE_EQ(y.strengthMps, x.strengthMps);
    EXPECT_EQ(y.directionDeg, x.directionDeg);
    ASSERT_EQ(y.keyframes.size(), x.keyframes.size());
    for (std::size_t k = 0; k < x.keyframes.size(); ++k) {
      EXPECT_NEAR(y.keyframes[k].lat, x.keyframes[k].lat, 1e-7);
      EXPECT_NEAR(y.keyframes[k].altM, x.keyframes[k].altM, 1e-3);
      EXPECT_EQ(y.keyframes[k].altRef, x.keyframes[k].altRef);
    }
  }
  // Only what was given is written: an empty section stays empty, no section stays absent.
  FlightPath c = a;
  c.wind = WindSection{};
  const Result<FlightPath> d = parseFlightPath(flightPathToJson(c), "z.json");
  ASSERT_TRUE(d.ok()) << d.error().message << "\n" << flightPathToJson(c);
  ASSERT_TRUE(d->wind.has_value());
  EXPECT_FALSE(d->wind->speedMps.has_value());
  EXPECT_TRUE(d->wind->sources.empty());
  c.wind.reset();
  EXPECT_EQ(flightPathToJson(c).find("\"wind\""), std::string::npos);
}

TEST(FlightPathJson, WindUnknownKeyIsRefusedWithASuggestion) {
  EXPECT_HAS(errorFor(windEdited(R"("gustiness": 0.6)", R"("gustyness": 0.6)")),
             "paths/bad.json:7:63: wind.gustyness: unknown key \"gustyness\" (did you mean \"gustiness\"?); known "
             "keys: speed_mps, direction_deg, gustiness, sources");
  EXPECT_HAS(errorFor(windEdited(R"("radius_m": 8)", R"("radius": 8)")),
             "paths/bad.json:12:52: wind.sources[1].radius: unknown key \"radius\" (did you mean \"radius_m\"?)");
  EXPECT_HAS(errorFor(windEdited(R"("speed_mps": 6,)", R"("speed_mps": 6, "speed_mps": 7,)")),
             "paths/bad.json:7:25: wind.speed_mps: key given twice");
  EXPECT_HAS(errorFor(windEdited(R"("alt_m": 20})", R"("alt_m": 20, "alt": 1})")),
             "wind.sources[1].keyframes[0].alt: unknown key");
  EXPECT_HAS(errorFor(edited(R"("name": "demo")", R"("name": "demo", "wind": 3)")),
             "paths/bad.json:2:27: wind: must be an object, found a number");
}

TEST(FlightPathJson, WindValuesOutOfRange) {
  EXPECT_HAS(errorFor(windEdited(R"("speed_mps": 6)", R"("speed_mps": -2)")),
             "paths/bad.json:7:25: wind.speed_mps: must be ≥ 0 m/s, found -2");
  EXPECT_HAS(errorFor(windEdited(R"("speed_mps": 6)", R"("speed_mps": 101)")),
             "paths/bad.json:7:25: wind.speed_mps: must be ≤ 100 m/s, found 101");
  EXPECT_HAS(errorFor(windEdited(R"("gustiness": 0.6)", R"("gustiness": 1.5)")),
             "paths/bad.json:7:63: wind.gustiness: must be ≤ 1, found 1.5");
  EXPECT_HAS(errorFor(windEdited(R"("speed_mps": 6)", R"("speed_mps": "6")")),
             "paths/bad.json:7:25: wind.speed_mps: must be a number, found a string");
  EXPECT_HAS(errorFor(windEdited(R"("strength_mps": 14)", R"("strength_mps": 140)")),
             "paths/bad.json:12:73: wind.sources[1].strength_mps: must be ≤ 100 m/s, found 140");
  EXPECT_HAS(errorFor(windEdited(R"("radius_m": 8)", R"("radius_m": 0)")),
             "paths/bad.json:12:54: wind.sources[1].radius_m: must be a positive number of metres");
}

TEST(FlightPathJson, WindSourceWithoutKeyframesIsRefused) {
  const std::string missing = R"("strength_mps": 14,
       "keyframes": [{"t": 0, "lat": 37.2005, "lon": -112.9875, "alt_m": 20}]})";
  EXPECT_HAS(errorFor(windEdited(missing, R"("strength_mps": 14})")),
             "paths/bad.json:12:7: wind.sources[1].keyframes: missing required array");
  EXPECT_HAS(errorFor(windEdited(R"("keyframes": [{"t": 0, "lat": 37.2005, "lon": -112.9875, "alt_m": 20}])",
                                 R"("keyframes": [])")),
             "paths/bad.json:13:21: wind.sources[1].keyframes: a wind source needs at least 1 keyframe");
  EXPECT_HAS(errorFor(windEdited(R"("t": 4, )", R"("t": 0, )")),
             "paths/bad.json:11:28: wind.sources[0].keyframes[1].t: t = 0.000 s is not after "
             "wind.sources[0].keyframes[0].t = 0.000 s");
  EXPECT_HAS(errorFor(windEdited(R"("name": "rotor", )", "")), "paths/bad.json:12:7: wind.sources[1].name: missing");
  EXPECT_HAS(errorFor(windEdited(R"("type": "rotor")", R"("type": "tornado")")),
             "paths/bad.json:12:33: wind.sources[1].type: \"tornado\" is not one of \"fan\", \"whirlwind\", \"rotor\"");
}

TEST(FlightPathJson, OnlyAFanHasADirection) {
  EXPECT_HAS(errorFor(windEdited(R"("strength_mps": 9, "direction_deg": 90,)", R"("strength_mps": 9,)")),
             "paths/bad.json:9:7: wind.sources[0].direction_deg: a fan needs direction_deg (where it blows towards");
  EXPECT_HAS(errorFor(windEdited(R"("strength_mps": 14,)", R"("strength_mps": 14, "direction_deg": 90,)")),
             "paths/bad.json:12:94: wind.sources[1].direction_deg: only a fan has a direction (a rotor blows all "
             "around)");
}

// The same rules hold for a path built in code (validateFlightPath), not only for JSON.
TEST(FlightPathJson, WindRulesHoldForPathsBuiltInCode) {
  FlightPath p = *parseFlightPath(kWindy, "x.json");
  EXPECT_TRUE(validateFlightPath(p, "code").ok());
  FlightPath q = p;
  q.wind->speedMps = -1.0;
  EXPECT_EQ(validateFlightPath(q, "code").error().message, "code: wind.speed_mps: must be ≥ 0 m/s, found -1");
  q = p;
  q.wind->gustiness = std::nan("");
  EXPECT_EQ(findProblem(q)->field, "wind.gustiness");
  q = p;
  q.wind->sources[0].directionDeg.reset();
  EXPECT_EQ(findProblem(q)->field, "wind.sources[0].direction_deg");
  q = p;
  q.wind->sources[1].directionDeg = 10.0;
  EXPECT_EQ(findProblem(q)->field, "wind.sources[1].direction_deg");
  q = p;
  q.wind->sources[1].keyframes.clear();
  EXPECT_EQ(findProblem(q)->field, "wind.sources[1].keyframes");
  q = p;
  q.wind->sources[1].name.clear();
  EXPECT_EQ(findProblem(q)->field, "wind.sources[1].name");
  q = p;
  q.wind->sources[0].keyframes[1].lat = 91.0;
  EXPECT_EQ(findProblem(q)->field, "wind.sources[0].keyframes[1].lat");
}

TEST(FlightPathJson, LoadNamesTheFile) {
  const Result<FlightPath> r = loadFlightPath("/nonexistent/dir/p.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::NotFound);
  EXPECT_HAS(r.error().message, "/nonexistent/dir/p.json");
}

}  // namespace
}  // namespace vegstream::flight
