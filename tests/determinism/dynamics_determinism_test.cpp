// Same model, integrator and initial state ⇒ bit-identical state: twice in this process with fresh
// objects, and once in a forked child process whose bytes come back through a pipe.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/support/model_matrix.hpp"

namespace gyrostab {
namespace dynamics_determinism_test {

void nothing() {}

std::vector<unsigned char> run_in_child(const testing::Case& c, long ticks) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const auto bytes = c.run(ticks, nothing);
    const auto n = write(fds[1], bytes.data(), bytes.size());
    _exit(n == static_cast<ssize_t>(bytes.size()) ? 0 : 1);
  }
  close(fds[1]);
  std::vector<unsigned char> out(256);
  ssize_t got = 0, n;
  while ((n = read(fds[0], out.data() + got, out.size() - static_cast<size_t>(got))) > 0) got += n;
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  out.resize(static_cast<size_t>(got));
  return out;
}

TEST(ModelDeterminism, EveryModelAndIntegratorIsBitIdenticalAcrossRunsAndProcesses) {
  for (const auto& c : testing::all_cases()) {
    const long ticks = 20'000;
    const auto first = c.run(ticks, nothing);
    const auto second = c.run(ticks, nothing);
    EXPECT_EQ(first, second) << c.name;
    EXPECT_EQ(first, run_in_child(c, ticks)) << c.name;
    // The run really moved: the state differs from a 1-tick-shorter run.
    EXPECT_NE(first, c.run(ticks - 1, nothing)) << c.name;
  }
}

}  // namespace dynamics_determinism_test
}  // namespace gyrostab
