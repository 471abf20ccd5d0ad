// Precompiled header of net/: libtorch costs ~8 s and 1 GB per translation unit without it.
// Only files in net/ may include libtorch (the renderer and tools build without it).
#pragma once
#include <torch/torch.h>
