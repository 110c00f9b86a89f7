// What a test takes from its surroundings, made explicit so that it is reproducible and does
// not flake under `ctest -j`: a temporary folder of its own process, the seed of a randomised
// test (PF_TEST_SEED) and timings scaled to the machine (PF_TEST_TIME_SCALE). Header-only, so
// that any test binary can use it without linking a support library.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <system_error>
#include <thread>

namespace pf::testing {

// A folder for this process alone, made on first use by mkdtemp under ::testing::TempDir()
// (TEST_TMPDIR or TMPDIR, else /tmp), so tests running side by side never share a file, and
// no file is left from an earlier process that had the same pid. Removed when the process
// exits, unless PF_TEST_KEEP_TEMP is set (then its path is printed). Thread-safe.
inline const std::filesystem::path& ProcessTempDir() {
    struct Folder {
        std::filesystem::path path;
        Folder() {
            std::string pattern = ::testing::TempDir() + "pf-test-XXXXXX";
            if (mkdtemp(pattern.data()) == nullptr) {
                std::fprintf(stderr, "test_env: cannot make a folder %s: %s\n", pattern.c_str(),
                             std::strerror(errno));
                std::abort();
            }
            path = pattern;
        }
        ~Folder() {
            if (std::getenv("PF_TEST_KEEP_TEMP") != nullptr) {
                std::fprintf(stderr, "test_env: kept %s (PF_TEST_KEEP_TEMP)\n", path.c_str());
                return;
            }
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Folder folder;
    return folder.path;
}

// ProcessTempDir() / name as a string, with the folders it names on the way made.
inline std::string TempPath(const std::string& name) {
    const std::filesystem::path path = ProcessTempDir() / name;
    std::filesystem::create_directories(path.parent_path());
    return path.string();
}

// ProcessTempDir() / name, made empty (whatever an earlier test of this process left there
// goes).
inline std::filesystem::path FreshTempDir(const std::string& name) {
    const std::filesystem::path path = ProcessTempDir() / name;
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
    return path;
}

// The seed of a randomised test: PF_TEST_SEED where it is set (a decimal integer), else one
// drawn from std::random_device, so that runs differ. Either way it is printed on stdout and
// recorded as the test's "seed" property (in --gtest_output XML), so that a failure is
// repeated by running the test again with PF_TEST_SEED set to it. A PF_TEST_SEED that is not a
// number fails the test.
inline uint64_t TestSeed() {
    uint64_t seed = 0;
    const char* text = std::getenv("PF_TEST_SEED");
    const char* origin = text ? "from the environment" : "drawn";
    if (text != nullptr) {
        const char* end = text + std::strlen(text);
        const auto [stop, error] = std::from_chars(text, end, seed);
        if (error != std::errc() || stop != end || stop == text) {
            ADD_FAILURE() << "PF_TEST_SEED=" << text << ": not a decimal integer below 2^64";
            seed = 0;
            origin = "PF_TEST_SEED unusable";
        }
    } else {
        std::random_device device;
        seed = (uint64_t{device()} << 32) | device();
    }
    std::printf("PF_TEST_SEED=%llu (%s; set PF_TEST_SEED to repeat this test's random choices)\n",
                static_cast<unsigned long long>(seed), origin);
    std::fflush(stdout);
    ::testing::Test::RecordProperty("seed", std::to_string(seed));
    return seed;
}

// How much longer than on an idle machine with 4 or more cores a test should allow for things
// that run on other threads and processes (heartbeats, timeouts): PF_TEST_TIME_SCALE where it
// is set (a number in [1, 100]), else 4 / cores, at least 1 (2 on a 2-core machine, where
// `ctest -j 2` runs two farms of several processes each on two cores).
inline double TimeScale() {
    static const double scale = [] {
        if (const char* text = std::getenv("PF_TEST_TIME_SCALE")) {
            char* end = nullptr;
            const double value = std::strtod(text, &end);
            if (end != text && *end == '\0' && std::isfinite(value) && value >= 1 && value <= 100)
                return value;
            std::fprintf(stderr,
                         "test_env: PF_TEST_TIME_SCALE=%s: must be a number in [1, 100]; "
                         "using the machine's own scale\n",
                         text);
        }
        const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
        return std::max(1.0, 4.0 / cores);
    }();
    return scale;
}

// `seconds` on this machine: seconds * TimeScale().
inline double ScaledSeconds(double seconds) { return seconds * TimeScale(); }

}  // namespace pf::testing
