#pragma once
// The measurement AOVs of an AOV frame (FrameRequest::aov, shaders/common/aov.glsl), decoded on
// the CPU from what the renderer reads back: the resolved float colour target, in which the
// vegetation wrote (species + 1, 1, 0, 1) on the samples it covers and the ground and sky 0,
// and the depth target's first sample (reverse-Z, 0 for the sky).
//
// Contract: coverage = the resolved g (the share of covered samples), clamped to 0 … 1;
// species = round(r / g) where g > 0 (exact where one species covers the pixel; where several
// share it, the coverage-weighted mean rounded), else 0; distanceM = the Euclidean distance from
// the camera to the point the first sample sees, through the frame's inverse projection
// (camera-relative view space), 0 where the depth is 0 (the sky).

#include <cstdint>

#include <glm/mat4x4.hpp>

#include "render/frame_types.h"

namespace vegstream::render {

// packed: width × height texels of the colour target's format (render_targets.h
// kColorFormat, B10G11R11 unsigned floats: r in bits 0–10, g 11–21, b 22–31); depth: width ×
// height floats; both row-major from the top. inverseProjection: the inverse of
// projection(camera, width / height).
AovImage decodeAov(uint32_t width, uint32_t height, const uint32_t* packed, const float* depth,
                   const glm::dmat4& inverseProjection);

}  // namespace vegstream::render
