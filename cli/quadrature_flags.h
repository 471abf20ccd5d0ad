// The march quadrature flags shared by render-envmap and render-view: cell quadrature (Gauss
// nodes per lattice cell) by default, or fixed steps when the user gives --step.
#pragma once

#include "render/ray_marcher.h"

#include <CLI/CLI.hpp>

namespace lh::cli {

struct QuadratureFlags {
    double stepVoxels = MarchOptions{}.stepVoxels;
    int gaussNodes = MarchOptions{}.cellNodes;
    double refineBound = 0.0;  // --max-optical-depth; MarchOptions' default when not given
    const CLI::Option* step = nullptr;
    const CLI::Option* nodes = nullptr;
    const CLI::Option* bound = nullptr;

    // --step alone selects fixed steps; --step with --gauss-nodes above 0 is refused
    // (InputError), since cell quadrature has no step.
    void applyTo(MarchOptions& march) const;
};

// Adds --gauss-nodes, --max-optical-depth and --step to `cmd`, bound to `flags`.
void addQuadratureFlags(CLI::App* cmd, QuadratureFlags& flags);

}  // namespace lh::cli
