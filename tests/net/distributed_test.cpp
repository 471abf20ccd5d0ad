// Data-parallel training (net/distributed.h) with known answers:
//   - two processes on localhost, each with half of a global batch of 2, end with the weights
//     of one process that trains on the whole batch (within 1e-4 after 3 steps: the ranks'
//     gradients are summed in another order than one process sums its two backward passes,
//     and Adam divides by the gradients' running RMS, which magnifies rounding where it is
//     tiny);
//   - a rank killed mid-training makes the other fail with a clear error well within its
//     timeout instead of waiting for ever;
//   - the world size, rank and rendezvous come from flags, torchrun's variables or srun's.
// The processes are this test executable again (DistributedWorker.Train, which does nothing
// unless LH_DIST_WORKER is set), started with posix_spawn.
#include "net/distributed.h"
#include "core/errors.h"
#include "net/lighthouse_net.h"
#include "net/trainer.h"
#include "synth/dataset.h"
#include "tests/net/net_test_scenes.h"
#include "tests/net/tiny_training_set.h"
#include "tests/support/temp_path.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

extern char** environ;

namespace lh::net {
namespace {

namespace fs = std::filesystem;

// The options both the one-process run and the ranks use; only batch slicing differs.
TrainOptions commonOptions(const std::string& data, const std::string& out) {
    TrainOptions o;
    o.data = data;
    o.configOverride = test::tinyHdrConfig();
    o.out = out;
    o.iterations = 3;
    o.batch = 2;
    o.checkpointEvery = 100;
    o.validateEvery = 100;
    o.validationScenes = 1;
    o.logEvery = 1;
    o.threads = 1;
    o.seed = 5;
    o.halfModel = false;  // compare float32 weights
    o.averageDecay = 0;   // the last step's weights: what the ranks all-reduce
    return o;
}

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

// A rank of a data-parallel run, when started by the tests below.
TEST(DistributedWorker, Train) {
    if (env("LH_DIST_WORKER").empty())
        GTEST_SKIP() << "runs only as a process started by the tests below";
    TrainOptions o = commonOptions(env("LH_DIST_DATA"), env("LH_DIST_OUT"));
    o.iterations = std::atoi(env("LH_DIST_ITERATIONS").c_str());
    DistributedFlags flags;
    flags.worldSize = 2;
    flags.rank = std::atoi(env("LH_DIST_RANK").c_str());
    flags.master = "127.0.0.1:" + env("LH_DIST_PORT");
    flags.timeoutSeconds = 60;
    o.distributed = resolveDistributed(flags);
    try {
        train(o, std::cerr);
    } catch (const Error& e) {
        std::cerr << "worker error: " << e.what() << std::endl;
        std::_Exit(3);
    }
    std::_Exit(0);
}

int freePort() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    socklen_t len = sizeof a;
    if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0)
        throw std::runtime_error("no free port");
    ::close(fd);
    return ntohs(a.sin_port);
}

// This executable as rank `rank` of 2, its stderr into `log`.
pid_t spawnRank(int rank, int port, const std::string& data, const std::string& out, int iterations,
                const std::string& log) {
    std::vector<std::string> vars;
    for (char** e = environ; *e; ++e) vars.push_back(*e);
    for (const auto& [k, v] :
         std::map<std::string, std::string>{{"LH_DIST_WORKER", "1"},
                                            {"LH_DIST_RANK", std::to_string(rank)},
                                            {"LH_DIST_PORT", std::to_string(port)},
                                            {"LH_DIST_DATA", data},
                                            {"LH_DIST_OUT", out},
                                            {"LH_DIST_ITERATIONS", std::to_string(iterations)}})
        vars.push_back(k + "=" + v);
    std::vector<char*> envp;
    for (auto& v : vars) envp.push_back(v.data());
    envp.push_back(nullptr);
    std::string exe = fs::read_symlink("/proc/self/exe").string(),
                filter = "--gtest_filter=DistributedWorker.Train";
    char* argv[] = {exe.data(), filter.data(), nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv, envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("posix_spawn failed");
    return pid;
}

// The exit status of `pid`, or -1 if it ran past `seconds` (then it is killed).
int waitFor(pid_t pid, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid)
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    return -1;
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

class DistributedTest : public test::TinyTrainingSetTest {
protected:
    static void removeOutputs(const std::string& out) {
        for (const std::string suffix : {"", ".csv", ".png", ".checkpoint"})
            fs::remove(out + suffix);
    }
};

TEST_F(DistributedTest, TwoRanksWithHalfTheBatchEachEndWithTheWeightsOfOneProcess) {
    const std::string oneOut = test::uniqueTempPath("lighthouse_dist_one.pt");
    const std::string twoOut = test::uniqueTempPath("lighthouse_dist_two.pt");
    const std::string rank1Out = test::uniqueTempPath("lighthouse_dist_rank1.pt");
    std::ostringstream log;
    train(commonOptions(dataDir(), oneOut), log);

    const int port = freePort();
    const std::string log0 = test::uniqueTempPath("dist_rank0.log"),
                      log1 = test::uniqueTempPath("dist_rank1.log");
    const pid_t r0 = spawnRank(0, port, dataDir(), twoOut, 3, log0);
    const pid_t r1 = spawnRank(1, port, dataDir(), rank1Out, 3, log1);
    const int s0 = waitFor(r0, 240), s1 = waitFor(r1, 60);
    ASSERT_EQ(s0, 0) << "rank 0:\n" << readText(log0);
    ASSERT_EQ(s1, 0) << "rank 1:\n" << readText(log1);
    EXPECT_NE(readText(log0).find("rank 0 of 2 joined"), std::string::npos) << readText(log0);
    EXPECT_NE(readText(log1).find("rank 1 of 2 joined"), std::string::npos) << readText(log1);
    EXPECT_FALSE(fs::exists(rank1Out)) << "rank 1 wrote a model: only rank 0 writes";
    EXPECT_FALSE(fs::exists(rank1Out + ".csv")) << "rank 1 wrote a log: only rank 0 writes";

    LighthouseNet one = loadModel(oneOut, torch::Device(torch::kCPU));
    LighthouseNet two = loadModel(twoOut, torch::Device(torch::kCPU));
    const auto pa = one->named_parameters(), pb = two->named_parameters();
    ASSERT_EQ(pa.size(), pb.size());
    double worst = 0;
    for (const auto& p : pa)
        worst = std::max(worst, (p.value() - pb[p.key()]).abs().max().item<double>());
    EXPECT_LT(worst, 1e-4)
        << "largest weight difference between 1 process x batch 2 and 2 ranks x 1";
    // Not vacuous: training moved the weights, and batch 1 on one process ends elsewhere.
    TrainOptions single =
        commonOptions(dataDir(), test::uniqueTempPath("lighthouse_dist_batch1.pt"));
    single.batch = 1;
    train(single, log);
    LighthouseNet batch1 = loadModel(single.out, torch::Device(torch::kCPU));
    double other = 0;
    for (const auto& p : batch1->named_parameters())
        other = std::max(other, (p.value() - pa[p.key()]).abs().max().item<double>());
    EXPECT_GT(other, 100 * worst) << "batch 1 should train to other weights than batch 2";
    EXPECT_GT(other, 1e-4);
    std::cerr << "largest weight difference: " << worst << " (2 ranks x 1 vs 1 process x 2); "
              << other << " (batch 1 vs batch 2)\n";
    for (const auto& out : {oneOut, twoOut, rank1Out, single.out}) removeOutputs(out);
    fs::remove(log0);
    fs::remove(log1);
}

TEST_F(DistributedTest, ARankThatDiesMakesTheOtherFailWithAClearError) {
    const std::string out0 = test::uniqueTempPath("lighthouse_dist_die0.pt");
    const std::string out1 = test::uniqueTempPath("lighthouse_dist_die1.pt");
    const int port = freePort();
    const std::string log0 = test::uniqueTempPath("dist_die0.log"),
                      log1 = test::uniqueTempPath("dist_die1.log");
    const pid_t r0 = spawnRank(0, port, dataDir(), out0, 100000, log0);
    const pid_t r1 = spawnRank(1, port, dataDir(), out1, 100000, log1);
    // Wait until training runs (rank 0 has logged an iteration), then kill rank 1.
    const auto start = std::chrono::steady_clock::now();
    while (readText(out0 + ".csv").find("\n1,") == std::string::npos &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_NE(readText(out0 + ".csv").find("\n1,"), std::string::npos)
        << "training never started:\n"
        << readText(log0);
    ::kill(r1, SIGKILL);
    EXPECT_EQ(waitFor(r1, 10), 128 + SIGKILL);
    const auto killed = std::chrono::steady_clock::now();
    const int s0 = waitFor(r0, 50);  // the collectives' timeout is 60 s; a dead peer is seen sooner
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
    ASSERT_NE(s0, -1) << "rank 0 still waiting 50 s after rank 1 died:\n" << readText(log0);
    EXPECT_EQ(s0, 3) << readText(log0);
    const std::string text = readText(log0);
    EXPECT_NE(text.find("worker error: distributed training, rank 0 of 2: "), std::string::npos)
        << text;
    EXPECT_NE(text.find("another rank died"), std::string::npos) << text;
    std::cerr << "rank 0 failed " << seconds
              << " s after rank 1 was killed: " << text.substr(text.find("worker error: "));
    removeOutputs(out0);
    removeOutputs(out1);
    fs::remove(log0);
    fs::remove(log1);
}

TEST(DistributedOptions, FlagsComeFirstThenTorchrunThenSrun) {
    std::map<std::string, std::string> vars;
    const auto getenv = [&](const char* name) -> const char* {
        const auto it = vars.find(name);
        return it == vars.end() ? nullptr : it->second.c_str();
    };
    EXPECT_FALSE(resolveDistributed({}, getenv).active()) << "nothing set: one process";

    DistributedFlags flags;
    flags.worldSize = 4;
    flags.rank = 3;
    flags.master = "node7:1234";
    DistributedOptions o = resolveDistributed(flags, getenv);
    EXPECT_EQ(o.worldSize, 4);
    EXPECT_EQ(o.rank, 3);
    EXPECT_EQ(o.masterAddress, "node7");
    EXPECT_EQ(o.masterPort, 1234);

    vars = {{"WORLD_SIZE", "2"},          {"RANK", "1"},          {"MASTER_ADDR", "10.0.0.1"},
            {"MASTER_PORT", "29400"},     {"SLURM_STEP_ID", "0"}, {"SLURM_PROCID", "5"},
            {"SLURM_STEP_NUM_TASKS", "8"}};
    o = resolveDistributed({}, getenv);
    EXPECT_EQ(o.worldSize, 2);
    EXPECT_EQ(o.rank, 1);
    EXPECT_EQ(o.masterAddress, "10.0.0.1");
    EXPECT_EQ(o.masterPort, 29400);

    vars = {{"SLURM_STEP_ID", "0"},
            {"SLURM_PROCID", "5"},
            {"SLURM_STEP_NUM_TASKS", "8"},
            {"SLURM_LAUNCH_NODE_IPADDR", "10.0.0.9"},
            {"SLURM_JOB_ID", "123456"}};
    o = resolveDistributed({}, getenv);
    EXPECT_EQ(o.worldSize, 8);
    EXPECT_EQ(o.rank, 5);
    EXPECT_EQ(o.masterAddress, "10.0.0.9");
    EXPECT_EQ(o.masterPort, 20000 + 123456 % 20000);

    // A batch script (no srun step) is one process, whatever its allocation.
    vars = {{"SLURM_PROCID", "0"}, {"SLURM_NTASKS", "8"}};
    EXPECT_FALSE(resolveDistributed({}, getenv).active());
}

TEST(DistributedOptions, InconsistentSettingsAreClearErrors) {
    const auto none = [](const char*) -> const char* { return nullptr; };
    DistributedFlags f;
    f.worldSize = 2;
    f.rank = 2;
    f.master = "localhost:1234";
    EXPECT_THROW(resolveDistributed(f, none), InputError) << "rank out of range";
    f.rank = 1;
    f.master = "";
    try {
        resolveDistributed(f, none);
        ADD_FAILURE() << "no rendezvous accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--master HOST:PORT"), std::string::npos) << e.what();
    }
    f.master = "localhost:99999";
    EXPECT_THROW(resolveDistributed(f, none), InputError) << "port out of range";
    f.master = "localhost";
    EXPECT_THROW(resolveDistributed(f, none), InputError) << "no port";
    f.worldSize = 2;
    f.rank = -1;
    f.master = "localhost:1234";
    EXPECT_THROW(resolveDistributed(f, none), InputError) << "world size without a rank";

    TrainOptions o;
    o.data = "x";
    o.distributed.worldSize = 2;
    o.batch = 3;
    EXPECT_THROW(o.validate(), InputError) << "batch not a multiple of the world size";
}

}  // namespace
}  // namespace lh::net
