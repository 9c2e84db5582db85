// Vertex smoothing for the quality optimiser (George-Hecht-Saltel 1990 section 4.3 c,
// Klingner-Shewchuk 2007): a free vertex (on no constrained face) is moved to the best of
// two weighted barycentres of its ball (volume-weighted centroids of the ball's tets; mean
// of the ideal apexes over the ball's outer faces), then by a few steps of ascent on the
// worst quality of the ball: the least-norm point of the convex hull of the gradients of the
// nearly-worst tets (finite differences) gives a direction raising them all, followed by a
// line search that keeps the best acceptable position. A position is kept only if every tet
// of the ball stays positive (exact orient3d) and Context::accept holds for the ball.
#pragma once

#include "OptimizationContext.h"

namespace tetmesher
{
namespace optimization
{

// Worst values over `star`; valid = false when a tet of it is not positive (exact).
WorstOf worstOfStar(const Context& ctx, const std::vector<TetId>& star, bool& valid);

// Least improvement of the ball's worst score (in [0,1]) for which smoothVertex moves a
// vertex (1e-6 of Q or of the dihedral angle / 70.5 degrees, i.e. 7e-5 degrees). At 1e-8,
// 36k of the 39k moves of fandisk's dihedral stage (h = 0.02066) gained under 1e-6, each
// requeueing its ball: 0.92 s of optimisation, 0.18 s now, with the same minima.
constexpr double kMinSmoothingGain = 1e-6;

// Moves free vertex v when that improves its ball's worst score by kMinSmoothingGain at
// least (see above). `star` is scratch space. Returns true when the vertex moved.
bool smoothVertex(Context& ctx, VertexId v, std::vector<TetId>& star);

} // namespace optimization
} // namespace tetmesher
