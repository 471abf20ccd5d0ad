#include "net/distributed.h"

// ProcessGroupGloo.hpp declares its class only with this defined (Debian's libtorch is built
// with Gloo, and libgloo-dev provides the headers it includes).
#define USE_C10D_GLOO 1

#include "core/errors.h"

#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>
#ifdef USE_C10D_NCCL
#include <torch/csrc/distributed/c10d/ProcessGroupNCCL.hpp>
#endif

#include <chrono>
#include <cstdlib>
#include <sstream>

namespace lh::net {

namespace {

bool parseInt(const char* text, long long& out) {
    if (!text || !*text) return false;
    char* end = nullptr;
    out = std::strtoll(text, &end, 10);
    return *end == '\0';
}

int intFrom(const char* text, const std::string& name) {
    long long v = 0;
    if (!parseInt(text, v) || v < 0 || v > 1000000)
        throw InputError(name + " must be a non-negative integer, got '" + text + "'");
    return int(v);
}

}  // namespace

DistributedOptions resolveDistributed(const DistributedFlags& f,
                                      const std::function<const char*(const char*)>& getenvFn) {
    const auto env = [&](const char* name) -> const char* {
        const char* v = getenvFn ? getenvFn(name) : std::getenv(name);
        return v && *v ? v : nullptr;
    };
    DistributedOptions o;
    o.timeoutSeconds = f.timeoutSeconds;
    if (!(f.timeoutSeconds > 0)) throw InputError("--dist-timeout must be positive");
    o.backend = f.backend;
    if (o.backend != "gloo" && o.backend != "nccl")
        throw InputError("--dist-backend must be gloo or nccl, got '" + o.backend + "'");
#ifndef USE_C10D_NCCL
    if (o.backend == "nccl")
        throw InputError(
            "--dist-backend nccl needs a build against a CUDA libtorch with "
            "-DLIGHTHOUSE_WITH_NCCL=ON; "
            "this one has Gloo only");
#endif
    // Slurm sets SLURM_PROCID and SLURM_NTASKS in a batch script too; only a task that srun
    // started (SLURM_STEP_ID) is one of several ranks.
    const bool underSrun = env("SLURM_STEP_ID") && env("SLURM_PROCID");
    if (f.worldSize >= 0)
        o.worldSize = f.worldSize;
    else if (env("WORLD_SIZE"))
        o.worldSize = intFrom(env("WORLD_SIZE"), "WORLD_SIZE");
    else if (underSrun && env("SLURM_STEP_NUM_TASKS"))
        o.worldSize = intFrom(env("SLURM_STEP_NUM_TASKS"), "SLURM_STEP_NUM_TASKS");
    else if (underSrun && env("SLURM_NTASKS"))
        o.worldSize = intFrom(env("SLURM_NTASKS"), "SLURM_NTASKS");
    if (o.worldSize < 1 || o.worldSize > 4096)
        throw InputError("--world-size must be in [1, 4096], got " + std::to_string(o.worldSize));
    if (f.rank >= 0)
        o.rank = f.rank;
    else if (env("RANK"))
        o.rank = intFrom(env("RANK"), "RANK");
    else if (underSrun)
        o.rank = intFrom(env("SLURM_PROCID"), "SLURM_PROCID");
    else if (o.worldSize > 1)
        throw InputError("world size " + std::to_string(o.worldSize) +
                         " but no rank: give --rank R or set RANK");
    if (o.rank < 0 || o.rank >= o.worldSize)
        throw InputError("--rank must be in [0, " + std::to_string(o.worldSize) + "), got " +
                         std::to_string(o.rank));
    if (!o.active()) return o;

    std::string port;
    if (!f.master.empty()) {
        const auto colon = f.master.rfind(':');
        if (colon == std::string::npos || colon == 0)
            throw InputError("--master must be HOST:PORT, got '" + f.master + "'");
        o.masterAddress = f.master.substr(0, colon);
        port = f.master.substr(colon + 1);
    } else if (env("MASTER_ADDR")) {
        o.masterAddress = env("MASTER_ADDR");
        port = env("MASTER_PORT") ? env("MASTER_PORT") : "29500";
    } else if (underSrun && env("SLURM_LAUNCH_NODE_IPADDR")) {
        o.masterAddress = env("SLURM_LAUNCH_NODE_IPADDR");
        long long job = 0;
        parseInt(env("SLURM_JOB_ID"), job);
        port = env("MASTER_PORT") ? env("MASTER_PORT") : std::to_string(20000 + job % 20000);
    } else {
        throw InputError("world size " + std::to_string(o.worldSize) +
                         " needs a rendezvous: give --master HOST:PORT (rank 0's host) or set "
                         "MASTER_ADDR and MASTER_PORT");
    }
    long long p = 0;
    if (!parseInt(port.c_str(), p) || p < 1 || p > 65535)
        throw InputError("the master's port must be in [1, 65535], got '" + port + "'");
    o.masterPort = int(p);
    return o;
}

struct Communicator::Impl {
    DistributedOptions options;
    c10::intrusive_ptr<c10d::Store> store;
    c10::intrusive_ptr<c10d::ProcessGroup> group;
    double seconds = 0;
    std::size_t bytes = 0;

    // Runs a collective and waits for it; turns what c10d and Gloo throw into one line.
    void run(const char* what, const std::function<c10::intrusive_ptr<c10d::Work>()>& start) {
        const auto t0 = std::chrono::steady_clock::now();
        try {
            auto work = start();
            work->wait();
        } catch (const std::exception& e) {
            std::string cause = e.what();
            const auto nl = cause.find('\n');
            if (nl != std::string::npos) cause.resize(nl);
            throw Error("distributed training, rank " + std::to_string(options.rank) + " of " +
                        std::to_string(options.worldSize) + ": " + what +
                        " failed (another rank died, or did not answer " + "within " +
                        std::to_string(int(options.timeoutSeconds)) + " s): " + cause);
        }
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
};

Communicator::Communicator(const DistributedOptions& o) : impl_(std::make_unique<Impl>()) {
    impl_->options = o;
    const auto timeout = std::chrono::milliseconds(static_cast<long long>(o.timeoutSeconds * 1000));
    try {
        c10d::TCPStoreOptions so;
        so.port = std::uint16_t(o.masterPort);
        so.isServer = o.rank == 0;
        so.numWorkers = std::size_t(o.worldSize);
        so.waitWorkers = true;
        so.timeout = timeout;
        impl_->store = c10::make_intrusive<c10d::TCPStore>(o.masterAddress, so);
        const auto prefixed = c10::make_intrusive<c10d::PrefixStore>("lighthouse", impl_->store);
#ifdef USE_C10D_NCCL
        if (o.backend == "nccl") {
            auto no = c10d::ProcessGroupNCCL::Options::create();
            no->timeout = timeout;
            impl_->group =
                c10::make_intrusive<c10d::ProcessGroupNCCL>(prefixed, o.rank, o.worldSize, no);
        }
#endif
        if (o.backend == "gloo") {
            auto go = c10d::ProcessGroupGloo::Options::create(timeout);
            // Gloo's device binds to the address this host resolves to; on one machine (or a
            // master given as localhost) the loopback interface.
            const bool local = o.masterAddress == "127.0.0.1" || o.masterAddress == "localhost";
            go->devices.push_back(local
                                      ? c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1")
                                      : c10d::ProcessGroupGloo::createDefaultDevice());
            go->threads = 1;
            impl_->group =
                c10::make_intrusive<c10d::ProcessGroupGloo>(prefixed, o.rank, o.worldSize, go);
        }
    } catch (const std::exception& e) {
        std::string cause = e.what();
        const auto nl = cause.find('\n');
        if (nl != std::string::npos) cause.resize(nl);
        throw Error("distributed training, rank " + std::to_string(o.rank) + " of " +
                    std::to_string(o.worldSize) + ": no rendezvous at " + o.masterAddress + ":" +
                    std::to_string(o.masterPort) + " within " +
                    std::to_string(int(o.timeoutSeconds)) + " s (" + cause + ")");
    }
}

Communicator::~Communicator() = default;

int Communicator::rank() const { return impl_->options.rank; }
int Communicator::worldSize() const { return impl_->options.worldSize; }
double Communicator::communicationSeconds() const { return impl_->seconds; }
std::size_t Communicator::bytesReduced() const { return impl_->bytes; }

void Communicator::allReduceSum(std::vector<at::Tensor>& tensors, const char* what) {
    if (tensors.empty()) return;
    std::vector<at::Tensor> pieces;
    for (const auto& t : tensors) pieces.push_back(t.reshape({-1}));
    std::vector<at::Tensor> buffer = {torch::cat(pieces)};
    impl_->bytes += std::size_t(buffer[0].numel()) * buffer[0].element_size();
    impl_->run(what, [&] { return impl_->group->allreduce(buffer); });
    int64_t offset = 0;
    for (auto& t : tensors) {
        t.copy_(buffer[0].narrow(0, offset, t.numel()).view_as(t));
        offset += t.numel();
    }
}

void Communicator::allReduceGradients(const std::vector<at::Tensor>& parameters, const char* what) {
    if (parameters.empty()) return;
    std::vector<at::Tensor> pieces;
    for (const auto& p : parameters)
        pieces.push_back(p.grad().defined() ? p.grad().reshape({-1})
                                            : torch::zeros({p.numel()}, p.options()));
    std::vector<at::Tensor> buffer = {torch::cat(pieces)};
    impl_->bytes += std::size_t(buffer[0].numel()) * buffer[0].element_size();
    impl_->run(what, [&] { return impl_->group->allreduce(buffer); });
    int64_t offset = 0;
    for (auto p : parameters) {
        const at::Tensor slice = buffer[0].narrow(0, offset, p.numel()).view_as(p);
        offset += p.numel();
        if (p.grad().defined())
            p.mutable_grad().copy_(slice);
        else if (p.numel() > 0 && slice.abs().max().item<double>() != 0)
            p.mutable_grad() = slice.clone();
    }
}

void Communicator::broadcastFromRankZero(std::vector<at::Tensor>& tensors, const char* what) {
    for (auto& t : tensors) {
        std::vector<at::Tensor> one = {t};
        impl_->run(what, [&] { return impl_->group->broadcast(one); });
    }
}

long long Communicator::broadcastValue(long long value, const char* what) {
    std::vector<at::Tensor> one = {
        torch::tensor({int64_t(value)}, torch::kInt64)
            .to(impl_->options.backend == "nccl" ? torch::kCUDA : torch::kCPU)};
    impl_->run(what, [&] { return impl_->group->broadcast(one); });
    return one[0].cpu().item<int64_t>();
}

}  // namespace lh::net
