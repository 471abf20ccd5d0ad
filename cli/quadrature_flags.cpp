#include "cli/quadrature_flags.h"

#include "core/errors.h"

namespace lh::cli {

void QuadratureFlags::applyTo(MarchOptions& march) const {
    const bool stepGiven = step && step->count() > 0, nodesGiven = nodes && nodes->count() > 0;
    if (stepGiven && nodesGiven && gaussNodes > 0)
        throw InputError("--step sets fixed steps, which --gauss-nodes " + std::to_string(gaussNodes) +
                         " replaces; give one of them (or --gauss-nodes 0 with --step)");
    march.stepVoxels = stepVoxels;
    march.maxStepOpticalDepth = maxOpticalDepth;
    march.cellNodes = stepGiven && !nodesGiven ? 0 : gaussNodes;
}

void addQuadratureFlags(CLI::App* cmd, QuadratureFlags& flags) {
    flags.nodes = cmd->add_option("--gauss-nodes", flags.gaussNodes,
                                  "Gauss nodes per lattice cell (1-3: cell quadrature; 0: fixed steps)")
                      ->capture_default_str();
    cmd->add_option("--max-optical-depth", flags.maxOpticalDepth,
                    "Refine where a piece's optical depth (per Gauss node, times the transmittance "
                    "in front) exceeds this; smaller is more accurate and slower (0.1: RMSE ~1e-3)")
        ->capture_default_str();
    flags.step = cmd->add_option("--step", flags.stepVoxels,
                                 "Fixed march step in voxels of the current level (selects fixed steps)")
                     ->capture_default_str();
}

}  // namespace lh::cli
