#pragma once
// Flight paths made for any dataset: a named template placed over the dataset's lon/lat
// extent (centred on it, scaled down to fit small extents). `vegstream path --template`
// writes them out; flight/paths/ holds the Zion versions.
//
//  benchmark-30s  the core seed's §4 benchmark (001 §4, figs. 7–9): 30 s along the extent's
//                 longer axis through its centre; starts 1800 m above the terrain (single plants
//                 not drawn), reaches 15 m above the terrain at 10 s, stays there, climbs again
//                 after 20 s and ends at 1800 m at 30 s.
//  canyon-run     fast (150 m/s), low (60 m above the terrain), long (80 % of the longer axis)
//                 S-curve run, heading along the flight direction; exercises streaming.
//  orbit          a slow (120 s) circle around the extent's centre, looking at it; flown at one
//                 MSL height 400 m above the highest ground on the circle when ground is known.

#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/ground_height.h"
#include "geo/bounds.h"

namespace vegstream::flight {

// flight/paths/benchmark-30s.json as embedded at build time: the benchmark profile placed by
// hand over the Zion sample's Kolob meadow (flight/README.md), which `vegstream fly` flies over
// the Zion sample instead of the template (whose near-ground phase is bare slickrock there).
std::string_view zionBenchmarkPathJson();

// The known template names, in the order above.
const std::vector<std::string>& templateNames();

// A valid path (findProblem empty) inside datasetBounds, or InvalidInput for an unknown name
// (listing the known ones) or an empty extent. ground may return NaN (unknown) everywhere.
Result<FlightPath> makePathFromTemplate(const std::string& templateName, const geo::GeoBounds& datasetBounds,
                                        const GroundHeight& ground);

}  // namespace vegstream::flight
