// Where the networks run. Written device-agnostic: `--device cuda` works with a CUDA build of
// libtorch (not tested here: Debian's libtorch is CPU-only and this machine has no GPU).
#pragma once

#include "net/torch_pch.h"

#include <string>

namespace lh::net {

// "cpu" or "cuda[:N]"; throws InputError naming what is wrong (unknown, or no CUDA here).
torch::Device selectDevice(const std::string& name);

// Intra-op threads for libtorch (it defaults to 1 here); 0 = every core. Also calls
// keepFreedMemoryInProcess: every command that runs a network starts here.
void setTorchThreads(int threads);

// Freed memory stays in the process's heap, for the next tensor of the same size (glibc only;
// device.cpp says why).
void keepFreedMemoryInProcess();

}  // namespace lh::net
