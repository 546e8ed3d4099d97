// The child process that reads a netCDF-4 file (netcdf_child_read.h): the
// fork, the messages the child writes into a pipe, and the parent's reading
// of them under the header's time limit.
//
// Messages, each a tag byte and its fields (strings as a length and bytes,
// grids as their dims, placement, value count and floats):
//   'H'                      everything before the data is read
//   'S' source frames{time has_temperature grid [grid]}   the series
//   'I' file field detail    an InputError
//   'N' what                 an InternalError
//   'E' what                 another obscura::Error
//   'X' what                 any other exception
// The child is a fork of this very program, so that GridDims and
// GridPlacement travel as their bytes.
#include "obscura/io/netcdf_child_read.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <optional>
#include <string_view>
#include <type_traits>

#include "obscura/core/check.h"  // InternalError
#include "obscura/core/error.h"

namespace obscura::netcdf_cf {
namespace {

static_assert(std::is_trivially_copyable_v<GridDims>);
static_assert(std::is_trivially_copyable_v<GridPlacement>);

constexpr std::string_view kHdf5Signature("\x89HDF\r\n\x1a\n", 8);

// The child's end: every write complete, or the child ends (its parent is
// gone, or the pipe is broken).
class ChildWriter {
 public:
  explicit ChildWriter(int fd) : fd_(fd) {}

  void bytes(const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) ::_exit(3);
      p += w;
      n -= static_cast<std::size_t>(w);
    }
  }
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof v);
  }
  void text(std::string_view s) {
    value<std::uint64_t>(s.size());
    bytes(s.data(), s.size());
  }
  void grid(const ScalarGrid& g) {
    value(g.dims);
    value(g.placement);
    value<std::uint64_t>(g.values.size());
    bytes(g.values.data(), g.values.size() * sizeof(float));
  }

 private:
  int fd_;
};

void write_series(ChildWriter& w, const ConcentrationSeries& s) {
  w.value('S');
  w.text(s.source);
  w.value<std::uint64_t>(s.frames.size());
  for (const ConcentrationFrame& f : s.frames) {
    w.value(f.time_s);
    w.value<std::uint8_t>(f.temperature_k ? 1 : 0);
    w.grid(f.concentration_g_m3);
    if (f.temperature_k) w.grid(*f.temperature_k);
  }
}

[[noreturn]] void run_child(int fd, const ChildRead& read) {
  ChildWriter w(fd);
  try {
    const ConcentrationSeries series = read([&] { w.value('H'); });
    write_series(w, series);
  } catch (const InputError& e) {
    w.value('I');
    w.text(e.file());
    w.text(e.field());
    w.text(e.detail());
  } catch (const InternalError& e) {
    w.value('N');
    w.text(e.what());
  } catch (const Error& e) {
    w.value('E');
    w.text(e.what());
  } catch (const std::exception& e) {
    w.value('X');
    w.text(e.what());
  } catch (...) {
    w.value('X');
    w.text("an exception of unknown type");
  }
  ::close(fd);
  // No exit handlers, no destructors of the parent's objects, no stdio
  // flush: the child's whole output is the pipe.
  ::_exit(0);
}

// Kills and reaps the child on every exit path that has not reaped it.
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {}
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }
  // Waits for the child to end and returns its wait status.
  int wait() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return status;
  }

 private:
  pid_t pid_;
};

// A message cut short: the child ended, or ran out of time, mid-way.
struct Interrupted {
  bool timed_out;
};

// The parent's end: reads exactly what is asked, within the deadline while
// one is set, and throws Interrupted when it cannot.
class MessageReader {
 public:
  using Clock = std::chrono::steady_clock;

  MessageReader(int fd, Clock::time_point deadline) : fd_(fd), deadline_(deadline) {}

  void end_deadline() { deadline_.reset(); }

  void bytes(void* data, std::size_t n) {
    char* p = static_cast<char*>(data);
    while (n > 0) {
      if (deadline_) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(*deadline_ - Clock::now());
        if (left.count() <= 0) throw Interrupted{true};
        pollfd pfd{fd_, POLLIN, 0};
        const int ready = ::poll(&pfd, 1, static_cast<int>(left.count()));
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0) throw Interrupted{true};
      }
      const ssize_t r = ::read(fd_, p, n);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) throw Interrupted{false};
      p += r;
      n -= static_cast<std::size_t>(r);
    }
  }
  template <typename T>
  T value() {
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  std::string text() {
    std::string s(value<std::uint64_t>(), '\0');
    bytes(s.data(), s.size());
    return s;
  }
  ScalarGrid grid() {
    ScalarGrid g;
    g.dims = value<GridDims>();
    g.placement = value<GridPlacement>();
    // The child checked these sizes against the memory limit before reading.
    g.values.resize(value<std::uint64_t>());
    bytes(g.values.data(), g.values.size() * sizeof(float));
    return g;
  }

 private:
  int fd_;
  std::optional<Clock::time_point> deadline_;
};

ConcentrationSeries read_series(MessageReader& m) {
  ConcentrationSeries s;
  s.source = m.text();
  s.frames.resize(m.value<std::uint64_t>());
  for (ConcentrationFrame& f : s.frames) {
    f.time_s = m.value<double>();
    const bool temperature = m.value<std::uint8_t>() != 0;
    f.concentration_g_m3 = m.grid();
    if (temperature) f.temperature_k = m.grid();
  }
  return s;
}

// What the child's wait status says, for the message.
std::string describe_end(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::sigabbrev_np(sig);
    return fmt::format("died of signal {} (SIG{})", sig, name ? name : "?");
  }
  if (WIFEXITED(status)) return fmt::format("ended with exit status {}", WEXITSTATUS(status));
  return fmt::format("ended with wait status {}", status);
}

// Closes a descriptor on every exit path.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

bool is_hdf5_container(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> magic{};
  const auto read_at = [&](std::uint64_t offset) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    return static_cast<bool>(in.read(magic.data(), magic.size()));
  };
  const auto hdf5 = [&] { return std::string_view(magic.data(), magic.size()) == kHdf5Signature; };
  if (!read_at(0)) return false;
  if (hdf5()) return true;
  if (std::string_view(magic.data(), 3) == "CDF") return false;
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return false;
  for (std::uint64_t offset = 512; offset + magic.size() <= size; offset *= 2)
    if (read_at(offset) && hdf5()) return true;
  return false;
}

ConcentrationSeries read_in_child_process(const std::string& file, const ChildRead& read,
                                          double header_limit_s) {
  std::array<int, 2> fds{};
  if (::pipe2(fds.data(), O_CLOEXEC) != 0)
    throw Error(fmt::format("{}: cannot create a pipe to read the netCDF-4 file: {}", file,
                            std::strerror(errno)));
  Fd read_end{fds[0]}, write_end{fds[1]};
  const pid_t pid = ::fork();
  if (pid < 0)
    throw Error(fmt::format("{}: cannot start a process to read the netCDF-4 file: {}", file,
                            std::strerror(errno)));
  if (pid == 0) {
    ::close(read_end.fd);
    run_child(write_end.fd, read);
  }
  Child child(pid);
  ::close(write_end.fd);
  write_end.fd = -1;  // the child's end only: its end of file is the child's

  const auto limit = std::chrono::duration_cast<MessageReader::Clock::duration>(
      std::chrono::duration<double>(header_limit_s));
  MessageReader m(read_end.fd, MessageReader::Clock::now() + limit);
  try {
    char tag = m.value<char>();
    if (tag == 'H') {
      m.end_deadline();
      tag = m.value<char>();
    }
    switch (tag) {
      case 'S': {
        ConcentrationSeries series = read_series(m);
        child.wait();
        return series;
      }
      case 'I': {
        std::string f = m.text(), field = m.text(), detail = m.text();
        throw InputError(std::move(f), std::move(field), detail);
      }
      case 'N':
        throw InternalError(m.text());
      case 'E':
        throw Error(m.text());
      case 'X':
        throw std::runtime_error(m.text());
      default:
        throw InternalError(fmt::format("{}: an unknown message {:#x} from the process reading it",
                                        file, static_cast<unsigned char>(tag)));
    }
  } catch (const Interrupted& stop) {
    if (stop.timed_out)
      throw InputError(file, "",
                       fmt::format("HDF5 had not read the netCDF-4 file's structure after {} s "
                                   "and was stopped: the file is corrupt (HDF5 loops forever "
                                   "on some corrupt files)",
                                   header_limit_s));
    const int status = child.wait();
    throw InputError(file, "",
                     fmt::format("the process reading this netCDF-4 file {} inside HDF5 or "
                                 "netCDF-C: the file is corrupt",
                                 describe_end(status)));
  }
}

}  // namespace obscura::netcdf_cf
