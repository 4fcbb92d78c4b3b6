#pragma once
// Seeded, deterministic mutations of a valid JSON text, for feeding the readers of user JSON
// (species catalog, dataset.json, flight paths) what users and broken files give them: bytes
// flipped, the text cut short, JSON tokens inserted anywhere (huge exponents "1e9999",
// "-1e9990", null, deeply nested arrays, wrong types), values replaced by a token of another
// type, members deleted or duplicated. The same seed and index always give the same text, so a
// failure names a case that can be replayed.

#include <cstdint>
#include <string>

namespace vegstream::testing {

struct JsonMutation {
  std::string text;
  std::string what;  // "replace value at 120 by 1e9999" — for failure messages
};

// Mutation number `index` of `valid` under `seed`: one to three edits chosen by (seed, index).
// `valid` must be valid JSON (its values and members are found by scanning it).
JsonMutation mutateJson(const std::string& valid, uint64_t seed, uint64_t index);

// Mutation `index` restricted to edits that keep a number-overflow token in the text
// ("1e9999", "-1e9990", ...): a value replaced by one, or one inserted. For the executable runs.
JsonMutation mutateJsonWithHugeNumber(const std::string& valid, uint64_t seed, uint64_t index);

}  // namespace vegstream::testing
