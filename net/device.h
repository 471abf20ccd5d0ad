// Where the networks run. Written device-agnostic: `--device cuda` works with a CUDA build of
// libtorch (not tested here: Debian's libtorch is CPU-only and this machine has no GPU).
#pragma once

#include "net/torch_pch.h"

#include <string>

namespace lh::net {

// "cpu" or "cuda[:N]"; throws InputError naming what is wrong (unknown, or no CUDA here).
torch::Device selectDevice(const std::string& name);

// Intra-op threads for libtorch (it defaults to 1 here); 0 = every core.
void setTorchThreads(int threads);

}  // namespace lh::net
