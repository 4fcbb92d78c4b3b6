// The terrain pass's draws (render/terrain_pass.h): one indirect draw per piece, whose first
// instance is the piece's index into this frame slot's pieces (set 3, binding 0), so the vertex
// stage finds its piece at gl_InstanceIndex and hands the index on to the fragment stage.
#include "terrain_piece.glsl"
layout(std430, set = 3, binding = 0) readonly buffer DrawPieces { Piece drawPieces[]; };
