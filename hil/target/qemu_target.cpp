#include "hil/target/qemu_target.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "hil/link/frame_transport.hpp"

extern char** environ;

namespace gyrostab::hil {
namespace {

int poll_ms(std::int64_t deadline_ns) {
  if (deadline_ns == kNoDeadline) return -1;
  const std::int64_t left = deadline_ns - monotonic_ns();
  if (left <= 0) return 0;
  return static_cast<int>(std::min<std::int64_t>((left + 999'999) / 1'000'000, 60'000));
}

std::string describe_errno(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

// The last line QEMU printed (at most 160 characters), or "".
std::string tail_of(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "";
  char buf[2048];
  const off_t size = ::lseek(fd, 0, SEEK_END);
  const off_t from = size > static_cast<off_t>(sizeof buf) ? size - static_cast<off_t>(sizeof buf) : 0;
  const ssize_t n = ::pread(fd, buf, sizeof buf, from);
  ::close(fd);
  if (n <= 0) return "";
  std::string text(buf, static_cast<std::size_t>(n));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  const std::size_t nl = text.find_last_of('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  if (line.size() > 160) line = line.substr(0, 160) + "...";
  return line;
}

}  // namespace

bool QemuTarget::start(const QemuLaunch& launch, std::string& error) {
  close();
  reaped_ = false;
  exit_status_ = -1;
  exit_text_.clear();
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/gyrostab-pil-XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (mkdtemp(buf.data()) == nullptr) {
    error = describe_errno(("cannot make a directory for the target link (" + pattern + ")").c_str());
    return false;
  }
  dir_ = buf.data();
  const std::string to = dir_ + (launch.uart ? "/uart.in" : "/to_target");
  const std::string from = dir_ + (launch.uart ? "/uart.out" : "/from_target");
  for (const std::string& f : {to, from}) {
    if (mkfifo(f.c_str(), 0600) != 0) {
      error = describe_errno(("cannot make the FIFO " + f).c_str());
      close();
      return false;
    }
    fifos_.push_back(f);
  }
  // O_RDWR: the open returns at once whether or not the emulator has opened its end yet.
  to_fd_ = ::open(to.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  from_fd_ = ::open(from.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (to_fd_ < 0 || from_fd_ < 0) {
    error = describe_errno("cannot open the target link's FIFOs");
    close();
    return false;
  }
  std::vector<std::string> args{launch.qemu,
                                "-M",
                                launch.machine,
                                "-cpu",
                                launch.cpu,
                                "-nographic",
                                "-monitor",
                                "none",
                                "-serial",
                                launch.uart ? "pipe:uart" : "none",
                                "-kernel",
                                launch.image,
                                "-icount",
                                "shift=0,sleep=off",
                                "-semihosting-config",
                                "enable=on,target=native,arg=" + launch.device + (launch.uart ? ",arg=uart" : ",arg=fifo")};
  args.insert(args.end(), launch.extra.begin(), launch.extra.end());
  std::vector<char*> argv;
  command_line_.clear();
  for (std::string& a : args) {
    argv.push_back(a.data());
    command_line_ += (command_line_.empty() ? "" : " ") + a;
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir_.c_str());
  // QEMU's own stdin must not be the terminal (-nographic would read it as the serial console's input); what it
  // prints (a lockup's register dump, a kernel it cannot load) goes to qemu.log, quoted when the target is lost.
  log_path_ = dir_ + "/qemu.log";
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  const int rc = posix_spawnp(&pid_, launch.qemu.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    errno = rc;
    error = describe_errno(("cannot start " + launch.qemu + " (apt-get install qemu-system-arm)").c_str());
    pid_ = -1;
    close();
    return false;
  }
  pidfd_ = static_cast<int>(syscall(SYS_pidfd_open, pid_, 0));
  if (pidfd_ < 0) {
    error = describe_errno("pidfd_open");
    close();
    return false;
  }
  return true;
}

bool QemuTarget::write(const std::uint8_t* data, std::size_t n, std::int64_t deadline_ns) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(to_fd_, data + done, n - done);
    if (w > 0) {
      done += static_cast<std::size_t>(w);
      continue;
    }
    if (w < 0 && errno != EAGAIN && errno != EINTR) return false;
    if (exited()) return false;
    pollfd p[2] = {{to_fd_, POLLOUT, 0}, {pidfd_, POLLIN, 0}};
    const int r = ::poll(p, 2, poll_ms(deadline_ns));
    if (r == 0) return false;  // the FIFO stayed full: the emulator does not read
  }
  return true;
}

ByteWait QemuTarget::read(std::uint8_t* buf, std::size_t n, std::int64_t deadline_ns, std::size_t& got) {
  got = 0;
  for (;;) {
    const ssize_t r = ::read(from_fd_, buf, n);
    if (r > 0) {
      got = static_cast<std::size_t>(r);
      return ByteWait::kData;
    }
    if (r < 0 && errno != EAGAIN && errno != EINTR) return ByteWait::kError;
    if (exited()) return ByteWait::kExited;
    pollfd p[2] = {{from_fd_, POLLIN, 0}, {pidfd_, POLLIN, 0}};
    const int ms = poll_ms(deadline_ns);
    const int pr = ::poll(p, 2, ms);
    if (pr < 0 && errno == EINTR) return ByteWait::kError;
    if (pr == 0 && ms >= 0 && monotonic_ns() >= deadline_ns) return ByteWait::kTimeout;
  }
}

void QemuTarget::note_status(int wstatus) {
  reaped_ = true;
  if (WIFEXITED(wstatus)) {
    exit_status_ = WEXITSTATUS(wstatus);
    exit_text_ = "exited with status " + std::to_string(exit_status_);
  } else if (WIFSIGNALED(wstatus)) {
    const char* name = sigabbrev_np(WTERMSIG(wstatus));
    exit_text_ = std::string("killed by SIG") + (name != nullptr ? name : "?");
  }
}

std::string QemuTarget::last_words() const { return log_path_.empty() ? last_words_ : tail_of(log_path_); }

bool QemuTarget::exited() {
  if (pid_ < 0) return true;
  if (reaped_) return true;
  int st = 0;
  const pid_t r = waitpid(pid_, &st, WNOHANG);
  if (r == pid_) {
    note_status(st);
    return true;
  }
  return false;
}

bool QemuTarget::wait_exit(std::int64_t deadline_ns) {
  while (!exited()) {
    pollfd p{pidfd_, POLLIN, 0};
    if (::poll(&p, 1, poll_ms(deadline_ns)) == 0) return exited();
  }
  return true;
}

void QemuTarget::freeze() {
  if (pid_ > 0 && !reaped_) ::kill(pid_, SIGSTOP);
}

void QemuTarget::kill_now() {
  if (pid_ > 0 && !reaped_) ::kill(pid_, SIGKILL);
}

void QemuTarget::close() {
  if (pid_ > 0 && !exited()) {
    ::kill(pid_, SIGKILL);
    int st = 0;
    if (waitpid(pid_, &st, 0) == pid_) note_status(st);
  }
  for (int* fd : {&to_fd_, &from_fd_, &pidfd_}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
  for (const std::string& f : fifos_) ::unlink(f.c_str());
  if (!log_path_.empty()) {
    last_words_ = tail_of(log_path_);
    ::unlink(log_path_.c_str());
    log_path_.clear();
  }
  fifos_.clear();
  if (!dir_.empty()) ::rmdir(dir_.c_str());
  dir_.clear();
  pid_ = -1;
}

}  // namespace gyrostab::hil
