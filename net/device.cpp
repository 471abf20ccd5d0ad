#include "net/device.h"

#include "core/errors.h"

#include <malloc.h>

#include <limits>

#include <thread>

namespace lh::net {

torch::Device selectDevice(const std::string& name) {
    if (name == "cpu") return torch::Device(torch::kCPU);
    if (name.rfind("cuda", 0) == 0) {
        if (!torch::cuda::is_available())
            throw InputError("--device " + name +
                             ": this libtorch has no CUDA or no GPU is visible; use --device cpu");
        try {
            return torch::Device(name);
        } catch (const c10::Error&) {
            throw InputError("--device " + name + ": not a device name (expected cuda or cuda:N)");
        }
    }
    throw InputError("--device " + name + ": unknown device (expected cpu or cuda)");
}

void setTorchThreads(int threads) {
    const int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    torch::set_num_threads(n);
    keepFreedMemoryInProcess();
}

void keepFreedMemoryInProcess() {
#ifdef __GLIBC__
    // glibc serves blocks above 32 MB with mmap and gives freed heap back to the kernel, so
    // every step's large tensors arrive as fresh pages that the kernel faults in and zeroes:
    // 40% of a training step on this project's 2-core machine
    // (GLIBC_TUNABLES=glibc.malloc.mmap_max=0 build/bench/lighthouse_train_step_bench shows
    // the same gain). Every block from the heap, and none given back, lets the next step reuse
    // them; the process keeps its peak footprint, which it reaches again every step anyway.
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
#endif
}

}  // namespace lh::net
