#include "net/device.h"

#include "core/errors.h"

#include <thread>

namespace lh::net {

torch::Device selectDevice(const std::string& name) {
    if (name == "cpu") return torch::Device(torch::kCPU);
    if (name.rfind("cuda", 0) == 0) {
        if (!torch::cuda::is_available())
            throw InputError("--device " + name + ": this libtorch has no CUDA or no GPU is visible; use --device cpu");
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
}

}  // namespace lh::net
