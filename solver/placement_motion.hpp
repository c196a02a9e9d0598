#pragma once

/// @file
/// Stage 1 of the synthesis (motion_generation.hpp) for a library over placements
/// (SynthesisModel::placements(): demonstrations at several object positions), the query a
/// placement (x, y, theta):
/// - interp: the query's cell in the Delaunay triangulation of the demonstrated placements
///   (placement_cell.hpp) and the blend of its vertices' motions with the barycentric weights
///   (BlendMotionsWeighted: weighted slerp of the wrist orientation, weighted aslerp of the
///   wrist relative to each object centre, weighted fingers), moved and turned with the object
///   from the blended placement to the query (a rounding-size move; none at a vertex, which is
///   that demonstration exactly). A cell cannot be blended, as a bracket cannot
///   (bracket.hpp), when its grasps lie on different sides of the handle, their orientations
///   relative to the object differ by more than BracketOptions::max_orientation_change, or a
///   vertex with weight is weak while another is not; nor when its blend failed its nominal
///   trial in physics (MotionGenerationOptions::reject_blend). It then falls back, in this
///   order, to the blend of the vertices that can be blended (the heaviest robust vertex and,
///   heaviest first, each other vertex that passes those tests with the ones kept, the weights
///   scaled to sum to one; at least two vertices, not after a failed blend, and reachable), to
///   the heaviest robust vertex moved and turned with the object when that is reachable, else
///   to the plain blend, left to the refinement. Outside the hull: kOutOfRange, naming the hull.
/// - nearest: the nearest demonstrated placement in the placement space (theta scaled by
///   kDefaultThetaLength), moved and turned with the object.
/// - line: the line principle (fitted over the position nearest the scene's object centre,
///   SynthesisModel::LineEntries) on the nearest entry's side, placed at the query's object.

#include "solver/motion_generation.hpp"

namespace graspsynth {

/// The grasping motion for `task` over the placements of model.library() (see the file
/// comment); model.placements() must hold. Options assumed valid; failures are results.
MotionGenerationResult GeneratePlacementMotion(const SynthesisModel& model,
                                               const SynthesisTask& task,
                                               const MotionGenerationOptions& options);

}  // namespace graspsynth
