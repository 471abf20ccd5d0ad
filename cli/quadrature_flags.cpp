#include "cli/quadrature_flags.h"

#include "core/errors.h"

namespace lh::cli {

void QuadratureFlags::applyTo(MarchOptions& march) const {
    const bool stepGiven = step && step->count() > 0, nodesGiven = nodes && nodes->count() > 0;
    if (stepGiven && nodesGiven && gaussNodes > 0)
        throw InputError("--step sets fixed steps, which --gauss-nodes " +
                         std::to_string(gaussNodes) +
                         " replaces; give one of them (or --gauss-nodes 0 with --step)");
    march.stepVoxels = stepVoxels;
    march.cellNodes = stepGiven && !nodesGiven ? 0 : gaussNodes;
    // One flag, the refinement bound of whichever quadrature runs.
    if (bound && bound->count() > 0)
        (march.cellNodes > 0 ? march.cellRefineBound : march.maxStepOpticalDepth) = refineBound;
}

void addQuadratureFlags(CLI::App* cmd, QuadratureFlags& flags) {
    flags.nodes =
        cmd->add_option("--gauss-nodes", flags.gaussNodes,
                        "Gauss nodes per lattice cell (1-3: cell quadrature; 0: fixed steps)")
            ->capture_default_str();
    const MarchOptions defaults;
    flags.bound = cmd->add_option(
        "--max-optical-depth", flags.refineBound,
        "Refinement bound; smaller is more accurate and slower. Cells (default " +
            std::to_string(defaults.cellRefineBound).substr(0, 3) +
            ", RMSE below 1e-3 of the mean radiance): halve a piece while its optical depth "
            "per Gauss node, times the transmittance in front and its brightness in "
            "units of the scene's typical radiance, exceeds it. Fixed steps (default " +
            std::to_string(defaults.maxStepOpticalDepth).substr(0, 3) +
            "): sub-divide steps thicker than it");
    flags.step =
        cmd->add_option("--step", flags.stepVoxels,
                        "Fixed march step in voxels of the current level (selects fixed steps)")
            ->capture_default_str();
}

}  // namespace lh::cli
