// A child process for integration tests: started with its stdout on a pipe (stderr shared
// with the test's), read line by line with a deadline, signalled, and always reaped: the
// destructor kills what is still running.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace pf::testing {

class ChildProcess {
public:
    explicit ChildProcess(const std::vector<std::string>& argv);
    ~ChildProcess();
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    // The next line of stdout, without its newline; nullopt at end of output or after `seconds`.
    std::optional<std::string> ReadLine(double seconds);
    void Signal(int signal);
    // The exit code (128 + signal when killed by one); nullopt if still running after `seconds`.
    std::optional<int> Wait(double seconds);
    pid_t Pid() const { return pid_; }

private:
    pid_t pid_ = -1;
    int stdout_fd_ = -1;
    int pidfd_ = -1;  // readable when the child exits
    std::string buffer_;
    std::optional<int> exit_code_;
};

}  // namespace pf::testing
