// Differentiable rendering of an MPI into another view (docs/method.md, training only): each
// plane is warped into the target camera by its homography and the planes are composited
// back to front with premultiplied colour.
#pragma once

#include "core/camera.h"
#include "net/torch_pch.h"

#include <vector>

namespace lh::net {

// mpi: [1, 4, D, H, W] (linear RGB, alpha), planes far (0) to near (D-1) at `depths` in the
// reference camera frame. Returns [1, 3, target.height, target.width]; pixels no plane covers
// stay black.
torch::Tensor renderMpiView(const torch::Tensor& mpi, const std::vector<double>& depths,
                            const PinholeCamera& ref, const PinholeCamera& target);

// Back-to-front "over" compositing of premultiplied planes [D, 4, H, W] -> [1, 3, H, W].
torch::Tensor compositePlanes(const torch::Tensor& premultipliedPlanes);

}  // namespace lh::net
