// Data-parallel training on PyTorch's own distributed layer (c10d): a TCPStore for the
// rendezvous and a Gloo process group (NCCL on a CUDA build of libtorch, see
// docs/distributed.md) for the collectives. Every rank runs the whole training loop on its
// slice of each global batch; gradients are summed across ranks before every optimiser step.
//
// Torch-free header (the CLI includes it); tensors are passed as at::Tensor by reference.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace at {
class Tensor;
}

namespace lh::net {

struct DistributedOptions {
    int worldSize = 1;
    int rank = 0;
    std::string masterAddress;  // host of rank 0, which serves the TCPStore
    int masterPort = 29500;
    double timeoutSeconds = 600;  // rendezvous and every collective; a dead rank fails sooner
    // "gloo" (CPU tensors; Debian's libtorch), or "nccl" for CUDA tensors in a build against
    // a CUDA libtorch with -DLIGHTHOUSE_WITH_NCCL=ON (docs/distributed.md).
    std::string backend = "gloo";

    bool active() const { return worldSize > 1; }
};

// What the command line gave; unset fields come from the environment.
struct DistributedFlags {
    int worldSize = -1, rank = -1;  // -1: not given
    std::string master;             // "HOST:PORT", "" : not given
    double timeoutSeconds = 600;
    std::string backend = "gloo";
};

// Flags first, then torchrun's variables (WORLD_SIZE, RANK, MASTER_ADDR, MASTER_PORT), then
// Slurm's under srun (SLURM_STEP_NUM_TASKS or SLURM_NTASKS, SLURM_PROCID; the master is
// SLURM_LAUNCH_NODE_IPADDR with port 20000 + job id mod 20000 unless MASTER_* say otherwise).
// Throws InputError naming what is inconsistent or missing. `getenv` is replaceable for tests.
DistributedOptions resolveDistributed(const DistributedFlags& flags,
                                      const std::function<const char*(const char*)>& getenv = {});

// A process group of every rank. Constructing it is the rendezvous (each rank blocks until
// all have joined, or the timeout); its collectives throw lh::Error naming the rank and the
// cause when a peer dies or stops answering.
class Communicator {
public:
    explicit Communicator(const DistributedOptions& options);
    ~Communicator();
    Communicator(const Communicator&) = delete;
    Communicator& operator=(const Communicator&) = delete;

    int rank() const;
    int worldSize() const;

    // Sums the (defined) tensors over all ranks, in place: one flat buffer, one collective.
    void allReduceSum(std::vector<at::Tensor>& tensors, const char* what);
    // Sums the parameters' gradients over all ranks, in place. A parameter without a gradient
    // takes part as zeros and keeps none unless another rank gave it one, so the optimiser
    // skips what no rank trained, as it would in one process.
    void allReduceGradients(const std::vector<at::Tensor>& parameters, const char* what);
    // Copies rank 0's tensors into every rank's, in place.
    void broadcastFromRankZero(std::vector<at::Tensor>& tensors, const char* what);
    // Rank 0's value of `value` on every rank.
    long long broadcastValue(long long value, const char* what);

    double communicationSeconds() const;  // spent in collectives so far
    std::size_t bytesReduced() const;     // payload of allReduceSum calls so far

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace lh::net
