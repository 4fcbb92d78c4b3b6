// An AOV frame (render/aov_image.h, FrameRequest::aov): instead of colours, every pass writes
// what the measurement AOVs need, and the resolved float target is read back as they are.
// The terrain and the sky write 0; a plant's or a tree's fragment writes (species + 1, 1, 0, 1)
// on the samples it covers, so that after the MSAA resolve (an average) g is the fraction of the
// pixel's samples covered by vegetation and r / g the species (exact where one species covers
// the pixel). A plant's planar shadow (core seed 001 §3.6) is not vegetation: it writes nothing.
// Needs frame_uniforms.glsl.

bool aovFrame() { return frame.outputs.x > 0.5; }

// What a vegetation fragment of catalog species `species` writes in an AOV frame.
vec4 aovVegetation(uint species) { return vec4(float(species + 1u), 1.0, 0.0, 1.0); }

// What the ground or the sky writes: its colour, or 0 in an AOV frame.
vec4 aovGround(vec4 colour) { return aovFrame() ? vec4(0.0) : colour; }
