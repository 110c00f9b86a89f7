// fork/exec with a stdout pipe, poll() for reads with deadlines, and for the exit on a pidfd
// (waitpid has no timeout), waitpid for reaping.
#include "tests/support/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace pf::testing {
namespace {

using Clock = std::chrono::steady_clock;

Clock::time_point Deadline(double seconds) {
    return Clock::now() +
           std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
        dup2(fds[1], STDOUT_FILENO);
        std::vector<char*> args;
        for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
        args.push_back(nullptr);
        execv(args[0], args.data());
        std::perror(args[0]);
        _exit(127);
    }
    close(fds[1]);
    stdout_fd_ = fds[0];
    // Readable once the child exits (a zombie still has one: it is not reaped yet); -1 on a
    // kernel without pidfd_open (before Linux 5.3), where Wait polls instead.
    pidfd_ = static_cast<int>(syscall(SYS_pidfd_open, pid_, 0));
}

ChildProcess::~ChildProcess() {
    if (!Wait(0)) {
        Signal(SIGKILL);
        Wait(30);
    }
    if (stdout_fd_ >= 0) close(stdout_fd_);
    if (pidfd_ >= 0) close(pidfd_);
}

std::optional<std::string> ChildProcess::ReadLine(double seconds) {
    const Clock::time_point deadline = Deadline(seconds);
    while (true) {
        if (const size_t end = buffer_.find('\n'); end != std::string::npos) {
            std::string line = buffer_.substr(0, end);
            buffer_.erase(0, end + 1);
            return line;
        }
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return std::nullopt;
        pollfd fd{stdout_fd_, POLLIN, 0};
        if (poll(&fd, 1, static_cast<int>(left)) <= 0) continue;
        char chunk[4096];
        const ssize_t got = read(stdout_fd_, chunk, sizeof chunk);
        if (got <= 0) return std::nullopt;
        buffer_.append(chunk, static_cast<size_t>(got));
    }
}

void ChildProcess::Signal(int signal) {
    if (!exit_code_) kill(pid_, signal);
}

std::optional<int> ChildProcess::Wait(double seconds) {
    const Clock::time_point deadline = Deadline(seconds);
    while (!exit_code_) {
        int status = 0;
        const pid_t done = waitpid(pid_, &status, WNOHANG);
        if (done == pid_) {
            exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            break;
        }
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) break;
        const int wait_ms = static_cast<int>(std::min<int64_t>(left, 60'000));
        if (pidfd_ >= 0) {
            pollfd fd{pidfd_, POLLIN, 0};
            poll(&fd, 1, wait_ms);
        } else {
            std::this_thread::sleep_for(std::chrono::milliseconds(std::min(wait_ms, 5)));
        }
    }
    return exit_code_;
}

}  // namespace pf::testing
