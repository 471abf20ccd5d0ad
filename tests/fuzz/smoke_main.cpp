// A fuzz target's replay (fuzz/, ctest `fuzz.smoke.<target>`): runs its LLVMFuzzerTestOneInput
// once on every file of the folders (or files) given, its seed corpus and the inputs that once
// crashed it, with whichever compiler built the test suite. A crash, an abort (a target's
// broken promise, or an exception the loader should have turned into lh::Error) or a hang fails
// the test; refused inputs pass, as they do under libFuzzer.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    std::vector<fs::path> inputs;
    for (int i = 1; i < argc; ++i) {
        if (fs::is_directory(argv[i])) {
            for (const auto& entry : fs::directory_iterator(argv[i]))
                if (entry.is_regular_file()) inputs.push_back(entry.path());
        } else if (fs::is_regular_file(argv[i])) {
            inputs.push_back(argv[i]);
        } else {
            std::fprintf(stderr,
                         "lighthouse: error: '%s' is neither a corpus folder nor an input file\n",
                         argv[i]);
            return 1;
        }
    }
    if (inputs.empty()) {  // an empty corpus would pass without testing anything
        std::fprintf(stderr, "lighthouse: error: no inputs to replay (give a corpus folder)\n");
        return 1;
    }
    std::sort(inputs.begin(), inputs.end());  // a failure then names the same input every run
    for (const fs::path& path : inputs) {
        std::fprintf(stderr, "replaying %s\n", path.c_str());
        std::ifstream in(path, std::ios::binary);
        const std::vector<char> bytes{std::istreambuf_iterator<char>(in),
                                      std::istreambuf_iterator<char>()};
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("replayed %zu input(s)\n", inputs.size());
    return 0;
}
