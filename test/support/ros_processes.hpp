#pragma once

// Processes a test starts itself (its own rosmaster on a free port, the node), for tests that are
// not rostests because they must own the master or see a process exit.

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <xmlrpcpp/XmlRpc.h>

extern char** environ;  // NOLINT: the children get this environment with the master's address.

namespace mrs_vpr {
namespace testing_support {

inline int freePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  const bool bound = bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 &&
                     getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0;
  close(fd);
  return bound ? ntohs(address.sin_port) : -1;
}

/// A process the test starts; killed when the test ends, whatever happens.
class Child {
 public:
  /// With `output`, the process's standard output and error go to that file.
  Child(const std::vector<std::string>& command, const std::vector<std::string>& environment,
        const std::string& output = "") {
    std::vector<char*> argv;
    for (const std::string& word : command) argv.push_back(const_cast<char*>(word.c_str()));
    argv.push_back(nullptr);
    std::vector<char*> envp;
    for (const std::string& entry : environment) envp.push_back(const_cast<char*>(entry.c_str()));
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!output.empty()) {
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    }
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() { stop(SIGKILL); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool started() const { return pid_ > 0; }
  /// False once the process has exited (a crash included); it is then reaped, and never signalled.
  bool running() {
    if (pid_ <= 0) return false;
    if (waitpid(pid_, nullptr, WNOHANG) == 0) return true;
    pid_ = -1;
    return false;
  }

  /// The exit status once the process has ended by itself within `seconds` (-signal when a signal
  /// ended it); nothing while it still runs.
  std::optional<int> exitWithin(double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (pid_ > 0) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
      }
      if (std::chrono::steady_clock::now() >= end) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return std::nullopt;
  }

  void stop(int signal) {
    if (pid_ <= 0) return;
    kill(pid_, signal);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

/// A call of the master API as any node makes it; true when the master answers with success.
inline bool masterSays(int port, const std::string& method, const std::string& argument = "") {
  XmlRpc::XmlRpcClient client("localhost", port, "/");  // A new connection: the old master may be gone.
  XmlRpc::XmlRpcValue params;
  params[0] = std::string("/mrs_vpr_test");
  if (!argument.empty()) params[1] = argument;
  XmlRpc::XmlRpcValue result;
  return client.execute(method.c_str(), params, result) && result.getType() == XmlRpc::XmlRpcValue::TypeArray &&
         result.size() == 3 && static_cast<int>(result[0]) == 1;
}

inline bool waitFor(const std::function<bool()>& condition, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return condition();
}

/// This process's environment for a master on `port` of this machine.
inline std::vector<std::string> environmentFor(int port) {
  std::vector<std::string> environment;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string text = *entry;
    if (text.rfind("ROS_MASTER_URI=", 0) != 0 && text.rfind("ROS_HOSTNAME=", 0) != 0 &&
        text.rfind("ROS_IP=", 0) != 0) {
      environment.push_back(text);
    }
  }
  environment.push_back("ROS_MASTER_URI=http://localhost:" + std::to_string(port) + "/");
  environment.push_back("ROS_HOSTNAME=localhost");
  return environment;
}

/// The command that runs a ROS master on `port` of this machine.
inline std::vector<std::string> rosmasterCommand(int port) {
  return {"/usr/bin/rosmaster", "--core", "-p", std::to_string(port)};
}

/// A rosmaster of its own on a free port, running once constructed (started() tells).
class PrivateMaster {
 public:
  PrivateMaster() : port_(freePort()), master_(rosmasterCommand(port_), environmentFor(port_)) {
    up_ = master_.started() && port_ > 0 && waitFor([this] { return masterSays(port_, "getPid"); }, 30.0);
  }
  bool started() const { return up_; }
  int port() const { return port_; }
  std::vector<std::string> environment() const { return environmentFor(port_); }

 private:
  int port_;
  Child master_;
  bool up_ = false;
};

}  // namespace testing_support
}  // namespace mrs_vpr
