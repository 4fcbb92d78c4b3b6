#pragma once
// Taking the acquisition shading out of imagery: albedo = observed / shading, with the shading
// a Lambertian direct sun plus a uniform diffuse sky, normalised so that flat ground keeps its
// colour:
//
//   shading(n)  = k · max(0, n · s) + (1 − k)        n: the DEM's unit normal, s: the sun (ENU)
//   gain(n)     = shading(up) / shading(n),  clamped to kMinDeshadingGain … kMaxDeshadingGain
//   albedo      = observed · gain(n)                  (linear light)
//
// k is the direct fraction of the irradiance on flat ground (kDirectFraction: 0.8, a clear
// mid-latitude day; the diffuse sky is taken as isotropic and unoccluded). Slopes turned away
// from the sun (n · s ≤ 0) get only the sky, so their gain would be up to 1/(1 − k) = 5: the
// clamp bounds it at 2.5, since such pixels hold mostly noise and cast shadows the DEM does not
// model. Cast shadows (terrain between the pixel and the sun) are not modelled.
//
// The model: Lambert's cosine law with a direct/diffuse split as in the topographic
// corrections of remote sensing (e.g. the "C correction", Teillet, Guindon & Goodenough 1982,
// whose c = (1 − k)/k here is fixed rather than regressed per band).

#include <vector>

#include <glm/vec3.hpp>

namespace vegstream::datasets {

inline constexpr double kDirectFraction = 0.8;
inline constexpr float kMinDeshadingGain = 0.5f;
inline constexpr float kMaxDeshadingGain = 2.5f;

struct SunAngles {
  double azimuthDeg = 0.0;    // clockwise from north
  double elevationDeg = 0.0;  // above the horizon
};

// Unit vector towards the sun in a local east-north-up frame.
glm::dvec3 sunVectorEnu(const SunAngles& sun);

// k · max(0, n · s) + (1 − k) for unit n and s.
double shading(const glm::dvec3& normal, const glm::dvec3& sun, double directFraction);

// shading(up) / shading(n), clamped as above.
float deshadingGain(const glm::dvec3& normal, const glm::dvec3& sun, double directFraction);

// Unit normals (east, north, up) of a square height tile: `heights` row-major from the north,
// size × size, NaN = nodata; pixelM the ground size of a pixel (Web Mercator pixels are square
// on the ground). Central differences, one-sided at the tile's edges and next to nodata; a pixel
// with no valid neighbour on an axis has no slope along it; a nodata pixel points up.
std::vector<glm::vec3> tileNormals(const std::vector<float>& heights, int size, double pixelM);

}  // namespace vegstream::datasets
